// Shaders embedded at build time, the program's (shaders/) and the tests' own (tests/shaders):
// every one is present and is SPIR-V, and the two lists do not share a name.
#include "shaders/embedded.h"
#include "test_shaders/embedded.h"

#include <gtest/gtest.h>
#include <set>
#include <string>

namespace mfx::test {
namespace {

template <class Table>
void expectSpirv(const Table& table) {
    ASSERT_FALSE(table.empty());
    for (const auto& shader : table) {
        ASSERT_GE(shader.spirv.size(), 5u) << shader.fileName;
        EXPECT_EQ(shader.spirv[0], 0x07230203u) << shader.fileName << " lacks the SPIR-V magic";
    }
}

template <class Table>
void expectUniqueStagedNames(const Table& table, std::set<std::string>& names) {
    for (const auto& shader : table) {
        EXPECT_TRUE(names.insert(shader.fileName).second) << shader.fileName;
        const std::string name = shader.fileName;
        const std::string stage = name.substr(name.rfind('.') + 1);
        EXPECT_TRUE(stage == "comp" || stage == "vert" || stage == "frag" || stage == "geom")
            << name;
    }
}

TEST(EmbeddedShaders, EveryShaderIsSpirv) {
    expectSpirv(shaders::allShaders());
    expectSpirv(test_shaders::allShaders());
}

TEST(EmbeddedShaders, NamesAreUniqueAndCarryTheirStage) {
    std::set<std::string> names;
    expectUniqueStagedNames(shaders::allShaders(), names);
    expectUniqueStagedNames(test_shaders::allShaders(), names);
}

TEST(EmbeddedShaders, TheProgramCarriesNoTestShader) {
    for (const shaders::EmbeddedShader& shader : shaders::allShaders()) {
        const std::string name = shader.fileName;
        EXPECT_NE(name.rfind("selftest_", 0), 0u) << name;
        EXPECT_NE(name.rfind("test_", 0), 0u) << name;
    }
}

} // namespace
} // namespace mfx::test
