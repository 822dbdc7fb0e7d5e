// A scene from JSON text and its simulation, for the tests that run scenes frame by frame
// (test_scene_simulation.cpp, test_scene_sparse.cpp). Both fail the test with the reader's or the
// simulation's error.
#pragma once

#include "core/scene/scene.h"
#include "sim/scene_simulation.h"

#include <gtest/gtest.h>
#include <memory>
#include <string>

namespace mfx::test {

inline scene::Scene parseScene(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "test.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    return s ? std::move(s).value() : scene::Scene{};
}

inline std::unique_ptr<sim::SceneSimulation>
simulate(const gpu::Context& ctx, const scene::Scene& s, const anim::Character& character) {
    auto created = sim::SceneSimulation::create(ctx, s, character);
    EXPECT_TRUE(created.ok()) << created.error().message;
    return created ? std::move(created).value() : nullptr;
}

} // namespace mfx::test
