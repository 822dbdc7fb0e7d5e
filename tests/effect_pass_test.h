// Fixture for the tests of the mesh-effect passes (render/kinds/afterimage_pass.h,
// render/kinds/swept_volume_pass.h, render/kinds/silhouette_shell_pass.h): a scene's simulation and
// one pass, recorded frame by frame as FrameRenderer does, and the small scenes they run.
#pragma once

#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "shaders/shared/skinning.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mfx::test {

// The built-in fighter playing `clip` at 30 fps for `frames` frames (64x36, the pose held after
// the clip's end); `effect` is the JSON of the scene's one effect.
inline scene::Scene clipScene(const std::string& clip, const std::string& effect, uint32_t frames) {
    const std::string text = R"({"character": {"clip": ")" + clip + R"("},
        "output": {"width": 64, "height": 36, "fps": 30, "frames": )" +
                             std::to_string(frames) + R"(}, "effects": [)" + effect + "]}";
    Result<scene::Scene> s = scene::parseScene(text, "test.json");
    EXPECT_TRUE(s) << (s ? "" : s.error().message);
    return s ? std::move(s).value() : scene::Scene{};
}

// A cube from -1 to 1 whose faces have their own vertices (24, as a flat-shaded mesh has: each
// corner is three copies at one position), two triangles a face, appended to the lists.
inline void flatShadedCube(std::vector<shared::SkinVertexIn>& vertices,
                           std::vector<uint32_t>& triangles) {
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            const uint32_t base = uint32_t(vertices.size());
            for (int corner = 0; corner < 4; ++corner) {
                glm::vec3 p(0.0f);
                p[axis] = side;
                p[(axis + 1) % 3] = (corner & 1) ? 1.0f : -1.0f;
                p[(axis + 2) % 3] = (corner & 2) ? 1.0f : -1.0f;
                shared::SkinVertexIn v{};
                v.position = glm::vec4(p, 1.0f);
                vertices.push_back(v);
            }
            triangles.insert(triangles.end(), {base, base + 1, base + 3, base, base + 3, base + 2});
        }
}

template <class Pass>
class EffectPassTest : public GpuTest {
protected:
    void start(const scene::Scene& s) {
        scene_ = s;
        Result<anim::Character> c = scene::loadCharacter(scene_);
        ASSERT_TRUE(c) << c.error().message;
        character_ = std::make_unique<anim::Character>(std::move(c).value());
        auto sim = sim::SceneSimulation::create(ctx(), scene_, *character_);
        ASSERT_TRUE(sim) << sim.error().message;
        sim_ = std::move(sim).value();
        pass_ = std::make_unique<Pass>(ctx(), scene_, sim_->cast());
        ASSERT_FALSE(pass_->empty());
    }
    // Records frames first..last in order (the pass's history advances once a frame).
    void play(uint32_t first, uint32_t last) {
        for (uint32_t f = first; f <= last; ++f) {
            gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
                sim_->recordFrame(cmd, f);
                pass_->advance(cmd, *sim_, f);
            });
            sim_->finishFrame();
        }
    }
    typename Pass::Counts counts() const { return pass_->counts(0); }

    scene::Scene scene_;
    std::unique_ptr<anim::Character> character_;
    std::unique_ptr<sim::SceneSimulation> sim_;
    std::unique_ptr<Pass> pass_;
};

} // namespace mfx::test
