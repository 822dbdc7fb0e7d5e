// Shaders embedded at build time: every one is present and is SPIR-V.
#include "shaders/embedded.h"

#include <gtest/gtest.h>
#include <set>
#include <string>

namespace mfx::shaders {
namespace {

TEST(EmbeddedShaders, EveryShaderIsSpirv) {
    ASSERT_FALSE(allShaders().empty());
    for (const EmbeddedShader& shader : allShaders()) {
        ASSERT_GE(shader.spirv.size(), 5u) << shader.fileName;
        EXPECT_EQ(shader.spirv[0], 0x07230203u) << shader.fileName << " lacks the SPIR-V magic";
    }
}

TEST(EmbeddedShaders, NamesAreUniqueAndCarryTheirStage) {
    std::set<std::string> names;
    for (const EmbeddedShader& shader : allShaders()) {
        EXPECT_TRUE(names.insert(shader.fileName).second) << shader.fileName;
        const std::string name = shader.fileName;
        const std::string stage = name.substr(name.rfind('.') + 1);
        EXPECT_TRUE(stage == "comp" || stage == "vert" || stage == "frag" || stage == "geom")
            << name;
    }
}

} // namespace
} // namespace mfx::shaders
