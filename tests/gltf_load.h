// Loading a glTF file through the importer in a test: the character, its invariants checked; a
// refused file fails the test and gives an empty character.
#pragma once

#include "core/anim/gltf_import.h"

#include <gtest/gtest.h>
#include <string>
#include <utility>

namespace mfx::test {

inline void expectValid(const anim::Character& character) {
    const Status invariants = anim::checkInvariants(character);
    EXPECT_TRUE(invariants.ok()) << invariants.error().message;
}

inline anim::Character load(const std::string& path) {
    Result<anim::Character> result = anim::importGltf(path);
    EXPECT_TRUE(result.ok()) << result.error().message;
    if (!result) return {};
    expectValid(result.value());
    return std::move(result).value();
}

} // namespace mfx::test
