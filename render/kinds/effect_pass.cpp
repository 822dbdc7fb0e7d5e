#include "render/kinds/effect_pass.h"

#include "core/gpu/context.h"
#include "render/effect_geometry.h"
#include "render/render_target.h"
#include "shaders/embedded.h"
#include "shaders/shared/effect_draw.h"

#include "core/scene/kinds/trail_effects.h"

#include <cstring>
#include <string_view>

namespace mfx::render {

EffectPass::EffectPass(const gpu::Context& ctx, VkSampleCountFlagBits samples)
    : ctx_(ctx), fadeDepthSource_(ctx) {
    volumes_ =
        trajectoryDrawProgram(ctx, "effect_volume", TrajectoryShape::Triangles, samples, false);
    lines_ = trajectoryDrawProgram(ctx, "effect_lines", TrajectoryShape::Ribbons, samples, false);
    particles_ =
        trajectoryDrawProgram(ctx, "effect_particles", TrajectoryShape::Sprites, samples, false);
    frame_ = sceneFrameBuffer(ctx, "effect frame");
}

uint32_t EffectPass::draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                          const SceneCamera& camera, float now, std::span<const uint8_t> shown) {
    const shared::SceneFrame frame = sceneFrame(simulation.scene(), camera);
    std::memcpy(frame_.mapped, &frame, sizeof frame);
    uint32_t draws = 0;
    // Volumes first, then lines, then particles: the thin effects stay on top of the blur.
    const std::pair<const char*, gpu::Program*> kinds[] = {
        {scene::MotionBlurSpec::kType, &volumes_},
        {scene::SpeedLinesSpec::kType, &lines_},
        {scene::MotionParticlesSpec::kType, &particles_}};
    for (const auto& [type, kindProgram] : kinds) {
        gpu::Program& program = *kindProgram;
        for (const sim::SceneSimulation::TrajectoryEffect& effect : simulation.trajectories()) {
            if (std::string_view(effect.spec->type()) != type) continue;
            const size_t index = simulation.effectIndex(effect);
            if (!effectShown(shown, index)) continue;
            const trajectory::Queue& queue = *effect.queue;
            const auto live = queue.liveSegments();
            if (live.empty()) continue;
            // The ribbon's width and look, the sprite's size and look, or the volume's look.
            const auto* lines = effect.spec->as<scene::SpeedLinesSpec>();
            const auto* particles = effect.spec->as<scene::MotionParticlesSpec>();
            const auto* blur = effect.spec->as<scene::MotionBlurSpec>();
            const scene::RibbonLook* look = lines       ? &lines->ribbon
                                            : particles ? &particles->look
                                                        : nullptr;
            auto style = styles_.find(index);
            if (style == styles_.end())
                style = styles_
                            .emplace(index, look ? ribbonStyleBuffer(ctx_, *look)
                                                 : volumeStyleBuffer(ctx_, blur->look))
                            .first;
            if (look)
                program.bind(cmd, {gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, style->second),
                                   fadeDepthSource_.binding(fadeDepth_)});
            else
                program.bind(cmd, {gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, style->second)});
            shared::EffectDraw d{};
            const float width = lines ? lines->width : particles ? particles->size : 0.0f;
            d.timing = glm::vec4(now, float(effect.trail->lifetime) / simulation.scene().output.fps,
                                 width, 1.0f / simulation.scene().output.fps);
            d.tint = glm::vec4(1.0f);
            if (look)
                setRibbonLook(d, *look);
            else
                setVolumeLook(d, blur->look, false);
            program.push(cmd, d);
            const VkBuffer vertices = queue.vertices().get();
            const VkDeviceSize offset = 0;
            vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
            if (queue.indicesPerSegment() > 0)
                vkCmdBindIndexBuffer(cmd, queue.indices().get(), 0, VK_INDEX_TYPE_UINT32);
            for (const trajectory::LiveSegment& segment : live) {
                if (queue.indicesPerSegment() > 0)
                    vkCmdDrawIndexed(cmd, queue.indicesPerSegment(), 1, 0,
                                     int32_t(segment.firstVertex), 0);
                else
                    vkCmdDraw(cmd, queue.verticesPerSegment(), 1, segment.firstVertex, 0);
                ++draws;
            }
        }
    }
    return draws;
}

} // namespace mfx::render
