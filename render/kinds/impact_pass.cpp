#include "render/kinds/impact_pass.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "render/render_target.h"
#include "shaders/embedded.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mfx::render {

namespace {

// The sparks' look: the effect's, with the defaults of a hot spark where it gives none (white-gold
// cooling through orange to a dying red; shrinking to a third).
scene::RibbonLook sparkLook(const scene::ImpactSpec& impact) {
    scene::RibbonLook look = impact.look;
    if (look.colourOverLife.empty())
        look.colourOverLife = {{0.0f, {1.0f, 0.95f, 0.75f, 1.0f}},
                               {0.35f, {1.0f, 0.6f, 0.2f, 1.0f}},
                               {1.0f, {0.8f, 0.15f, 0.05f, 0.0f}}};
    if (look.widthOverLife.empty()) look.widthOverLife = {{0.0f, 1.0f}, {1.0f, 0.3f}};
    return look;
}

} // namespace

ImpactPass::ImpactPass(const gpu::Context& ctx, const scene::Scene& scene,
                       std::span<const anim::Character> /*cast*/, VkSampleCountFlagBits samples)
    : ctx_(ctx), scene_(scene), fadeDepthSource_(ctx) {
    sparksProgram_ = storageComputeProgram(ctx, "impact_sparks", shaders::impact_sparks_comp,
                                           sizeof(shared::ImpactSparkConstants));
    gpu::GraphicsProgramDesc desc;
    desc.name = "impact";
    desc.vertex = shaders::impact_vert;
    desc.fragment = shaders::impact_frag;
    desc.pushConstantSize = sizeof(shared::ImpactDraw);
    desc.colorFormats = {kSceneColorFormat};
    desc.depthFormat = kDepthFormat;
    desc.depthTest = true;
    desc.depthWrite = false;
    desc.blend = gpu::BlendMode::PremultipliedAlpha;
    desc.samples = samples;
    draw_ = gpu::createGraphicsProgram(ctx, desc);
    desc.name = "impact overlay";
    desc.depthTest = false;
    overlay_ = gpu::createGraphicsProgram(ctx, desc);
    frame_ = sceneFrameBuffer(ctx, "impact frame");

    for (size_t i = 0; i < scene_.effects.size(); ++i) {
        const scene::ImpactSpec* impact = scene_.effects[i].as<scene::ImpactSpec>();
        if (!impact) continue;
        Effect e;
        e.index = i;
        e.spec = impact;
        std::vector<shared::ImpactSpark> sparks;
        for (size_t h = 0; h < scene_.hits.size(); ++h) {
            const scene::Hit& hit = scene_.hits[h];
            if (hit.effect != i) continue;
            e.hits.push_back(h);
            e.firstSpark.push_back(uint32_t(sparks.size()));
            for (const scene::SparkLaunch& s :
                 scene::impactSparks(*impact, hit.point, hit.direction, hit.time, uint32_t(h)))
                sparks.push_back({glm::vec4(s.origin, s.time), glm::vec4(s.velocity, s.life)});
        }
        e.sparkCount = uint32_t(sparks.size());
        const VkDeviceSize bytes =
            std::max<VkDeviceSize>(sparks.size(), 1) * sizeof(shared::ImpactSpark);
        e.sparks = effectStorage(ctx, bytes, 0, "impact sparks");
        if (!sparks.empty())
            gpu::uploadBuffer(ctx, e.sparks, std::span<const shared::ImpactSpark>(sparks));
        e.streaks = effectStorage(
            ctx, std::max<VkDeviceSize>(sparks.size(), 1) * sizeof(shared::ImpactStreak), 0,
            "impact streaks");
        e.style = ribbonStyleBuffer(ctx, sparkLook(*impact));
        effects_.push_back(std::move(e));
    }
}

void ImpactPass::advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                         uint32_t frame) {
    const float now = simulation.frameTime(frame);
    bool recorded = false;
    for (Effect& e : effects_) {
        e.evaluatedFirst = e.evaluatedCount = 0;
        const float life = e.spec->sparkLife; // a spark lives at most this long
        // The hits whose sparks are in the air: thrown at or before now, within their life.
        uint32_t first = e.sparkCount, last = 0;
        for (size_t k = 0; k < e.hits.size(); ++k) {
            const float t = scene_.hits[e.hits[k]].time;
            if (t > now || now - t >= life) continue;
            const uint32_t begin = e.firstSpark[k];
            const uint32_t end = k + 1 < e.hits.size() ? e.firstSpark[k + 1] : e.sparkCount;
            first = std::min(first, begin);
            last = std::max(last, end);
        }
        if (first >= last) continue;
        shared::ImpactSparkConstants c{};
        c.motion = glm::vec4(now, e.spec->gravity, e.spec->drag, e.spec->sparkStretch);
        c.first = first;
        c.count = last - first;
        sparksProgram_.bind(cmd, {gpu::bindBuffer(0, e.sparks), gpu::bindBuffer(1, e.streaks)});
        sparksProgram_.push(cmd, c);
        vkCmdDispatch(cmd, (c.count + MFX_IMPACT_GROUP_SIZE - 1) / MFX_IMPACT_GROUP_SIZE, 1, 1);
        e.evaluatedFirst = first;
        e.evaluatedCount = c.count;
        recorded = true;
    }
    if (recorded) // the streaks, to the vertex stage that reads them
        gpu::memoryBarrier(
            cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

uint32_t ImpactPass::draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                          const SceneCamera& camera, float time, std::span<const uint8_t> shown) {
    if (effects_.empty()) return 0;
    const shared::SceneFrame frame = sceneFrame(simulation.scene(), camera);
    std::memcpy(frame_.mapped, &frame, sizeof frame);
    uint32_t draws = 0;
    for (const Effect& e : effects_) {
        if (!effectShown(shown, e.index)) continue;
        const scene::ImpactSpec& impact = *e.spec;
        const std::vector<gpu::DescriptorWrite> bindings = {
            gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, e.style),
            fadeDepthSource_.binding(fadeDepth_), gpu::bindBuffer(3, e.streaks)};
        draw_.bind(cmd, bindings);
        const float additive = impact.look.additive ? 1.0f : 0.0f;
        if (e.evaluatedCount > 0) {
            shared::ImpactDraw d{};
            d.centre = glm::vec4(0.0f, 0.0f, 0.0f, MFX_IMPACT_SPARKS);
            d.axisV = glm::vec4(0.0f, 0.0f, 0.0f, impact.sparkSize);
            d.colour = glm::vec4(glm::vec3(impact.look.intensity), 1.0f);
            d.ring = glm::vec4(0.0f, 0.0f, additive, impact.look.depthFade);
            draw_.push(cmd, d);
            vkCmdDraw(cmd, 6 * e.evaluatedCount, 1, 6 * e.evaluatedFirst, 0);
            ++draws;
        }
        // Each hit's flash and ring while they live (light: added to what is behind).
        for (size_t h : e.hits) {
            const scene::Hit& hit = scene_.hits[h];
            const float age = time - hit.time;
            if (age < 0.0f) continue;
            if (impact.flashSize > 0.0f && age < impact.flashSeconds) {
                const float u = age / impact.flashSeconds;
                shared::ImpactDraw d{};
                d.centre = glm::vec4(hit.point, MFX_IMPACT_FLASH);
                d.axisU = glm::vec4(0.0f, 0.0f, 0.0f, 0.5f * impact.flashSize * (0.6f + 0.4f * u));
                const float fade = (1.0f - u) * (1.0f - u);
                d.colour = glm::vec4(glm::vec3(impact.flashColour) * impact.flashIntensity,
                                     impact.flashColour.a * fade);
                d.ring = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
                overlay_.bind(cmd, bindings);
                overlay_.push(cmd, d);
                vkCmdDraw(cmd, 6, 1, 0, 0);
                ++draws;
            }
            if (impact.ring != scene::RingFacing::None && age < impact.ringSeconds) {
                const float u = age / impact.ringSeconds;
                const float eased = 1.0f - (1.0f - u) * (1.0f - u) * (1.0f - u);
                const float radius = impact.ringRadius * eased;
                const float half = radius + impact.ringWidth;
                shared::ImpactDraw d{};
                d.centre = glm::vec4(hit.point, MFX_IMPACT_RING);
                if (impact.ring == scene::RingFacing::HitPlane) {
                    const scene::BlowAxes blow = scene::blowAxes(hit.direction);
                    d.axisU = glm::vec4(blow.u, half);
                    d.axisV = glm::vec4(blow.v, 0.0f);
                } else {
                    d.axisU = glm::vec4(0.0f, 0.0f, 0.0f, half);
                }
                d.colour = glm::vec4(glm::vec3(impact.ringColour) * impact.flashIntensity * 0.5f,
                                     impact.ringColour.a * (1.0f - u) * (1.0f - u));
                const bool onPlane = impact.ring == scene::RingFacing::HitPlane;
                d.ring = glm::vec4(std::max(radius - 0.5f * impact.ringWidth, 0.0f) / half,
                                   (radius + 0.5f * impact.ringWidth) / half, 1.0f,
                                   onPlane ? impact.look.depthFade : 0.0f);
                gpu::Program& program = onPlane ? draw_ : overlay_;
                program.bind(cmd, bindings);
                program.push(cmd, d);
                vkCmdDraw(cmd, 6, 1, 0, 0);
                ++draws;
            }
        }
    }
    return draws;
}

std::vector<shared::ImpactSpark> ImpactPass::sparks(size_t effect) const {
    for (const Effect& e : effects_)
        if (e.index == effect && e.sparkCount > 0) {
            auto all = gpu::readBufferAs<shared::ImpactSpark>(ctx_, e.sparks);
            all.resize(e.sparkCount);
            return all;
        }
    return {};
}

std::vector<shared::ImpactStreak> ImpactPass::streaks(size_t effect) const {
    for (const Effect& e : effects_)
        if (e.index == effect && e.evaluatedCount > 0) {
            auto all = gpu::readBufferAs<shared::ImpactStreak>(ctx_, e.streaks);
            return std::vector<shared::ImpactStreak>(
                all.begin() + e.evaluatedFirst, all.begin() + e.evaluatedFirst + e.evaluatedCount);
        }
    return {};
}

} // namespace mfx::render
