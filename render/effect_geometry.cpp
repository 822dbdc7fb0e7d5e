#include "render/effect_geometry.h"

#include "core/anim/sampling.h"
#include "render/render_target.h"
#include "shaders/embedded.h"
#include "shaders/shared/effect_draw.h"
#include "shaders/shared/trajectory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <string>

namespace mfx::render {

gpu::Program storageComputeProgram(const gpu::Context& ctx, const char* name,
                                   std::span<const uint32_t> spirv, uint32_t pushConstantSize) {
    gpu::ComputeProgramDesc desc;
    desc.name = name;
    desc.spirv = spirv;
    desc.pushConstantSize = pushConstantSize;
    return gpu::createComputeProgram(ctx, desc);
}

gpu::Program trajectoryDrawProgram(const gpu::Context& ctx, const char* name, TrajectoryShape shape,
                                   VkSampleCountFlagBits samples, bool depthWrite) {
    gpu::GraphicsProgramDesc desc;
    desc.name = name;
    desc.pushConstantSize = sizeof(shared::EffectDraw);
    desc.vertexStride = sizeof(shared::TrajectoryVertex);
    desc.attributes = {{0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                       {1, VK_FORMAT_R32G32B32A32_SFLOAT, 16},
                       {2, VK_FORMAT_R32G32B32A32_SFLOAT, 32}};
    auto stages = [&](VkPrimitiveTopology topology, std::span<const uint32_t> vertex,
                      std::span<const uint32_t> geometry, std::span<const uint32_t> fragment) {
        desc.topology = topology;
        desc.vertex = vertex;
        desc.geometry = geometry;
        desc.fragment = fragment;
    };
    switch (shape) {
    case TrajectoryShape::Triangles: // the volume's triangles as they are
        stages(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, shaders::effect_volume_vert, {},
               shaders::effect_volume_frag);
        break;
    case TrajectoryShape::Ribbons: // lines widened into ribbons by the geometry stage
        stages(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, shaders::effect_lines_vert,
               shaders::effect_lines_geom, shaders::effect_lines_frag);
        break;
    case TrajectoryShape::Sprites: // points expanded into camera-facing sprites
        stages(VK_PRIMITIVE_TOPOLOGY_POINT_LIST, shaders::effect_particles_vert,
               shaders::effect_particles_geom, shaders::effect_particles_frag);
        break;
    case TrajectoryShape::Sheet: // two lines joined into triangles, shaded as a ribbon
        stages(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, shaders::effect_sheet_vert, {},
               shaders::effect_lines_frag);
        break;
    }
    desc.colorFormats = {kSceneColorFormat};
    desc.depthFormat = kDepthFormat;
    desc.depthTest = true;
    desc.depthWrite = depthWrite;
    desc.blend = gpu::BlendMode::PremultipliedAlpha;
    desc.samples = samples;
    return gpu::createGraphicsProgram(ctx, desc);
}

namespace {

gpu::Buffer styleBuffer(const gpu::Context& ctx,
                        const std::vector<scene::GradientStop>& colourOverLife,
                        const std::vector<scene::CurveStop>& widthOverLife,
                        const std::vector<scene::CurveStop>& erosionOverLife = {}) {
    // Every stop filled: past the last given, the last again at life 1 (ribbon_style.glsl).
    shared::RibbonStyle style{};
    const size_t colours = colourOverLife.size();
    // A curve's stops into its values and places (four to a vec4).
    auto fillCurve = [](const std::vector<scene::CurveStop>& stops, glm::vec4* values,
                        glm::vec4* at) {
        for (size_t i = 0; i < MFX_RIBBON_MAX_STOPS && !stops.empty(); ++i) {
            const scene::CurveStop& s = stops[std::min(i, stops.size() - 1)];
            values[i / 4][int(i % 4)] = s.value;
            at[i / 4][int(i % 4)] = i < stops.size() ? s.at : 1.0f;
        }
    };
    for (size_t i = 0; i < MFX_RIBBON_MAX_STOPS && colours > 0; ++i) {
        const scene::GradientStop& c = colourOverLife[std::min(i, colours - 1)];
        style.colours[i] = c.colour;
        style.colourAt[i / 4][int(i % 4)] = i < colours ? c.at : 1.0f;
    }
    fillCurve(widthOverLife, style.widths, style.widthAt);
    fillCurve(erosionOverLife, style.erosion, style.erosionAt);
    gpu::Buffer buffer = gpu::createBuffer(ctx, sizeof style, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                           gpu::MemoryUsage::Upload, "ribbon style");
    std::memcpy(buffer.mapped, &style, sizeof style);
    return buffer;
}

} // namespace

gpu::Buffer ribbonStyleBuffer(const gpu::Context& ctx, const scene::RibbonLook& look) {
    return styleBuffer(ctx, look.colourOverLife, look.widthOverLife, look.texture.erosionOverLife);
}

gpu::Buffer volumeStyleBuffer(const gpu::Context& ctx, const scene::VolumeLook& look) {
    return styleBuffer(ctx, look.colourOverLife, {});
}

void setVolumeLook(shared::EffectDraw& draw, const scene::VolumeLook& look, bool lifeFromPlace) {
    draw.ribbonFlags = glm::vec4(look.colourOverLife.empty() ? 0.0f : 1.0f, 0.0f,
                                 look.additive ? 1.0f : 0.0f, lifeFromPlace ? 1.0f : 0.0f);
    draw.ribbonLight = glm::vec4(look.intensity, 0.0f, 0.0f, 0.0f);
    draw.rimLight = glm::vec4(look.rim, look.rimColour);
}

void setRibbonLook(shared::EffectDraw& draw, const scene::RibbonLook& look) {
    draw.ribbonFlags = glm::vec4(look.colourOverLife.empty() ? 0.0f : 1.0f,
                                 look.widthOverLife.empty() ? 0.0f : 1.0f,
                                 look.additive ? 1.0f : 0.0f, look.bladeFacing ? 1.0f : 0.0f);
    draw.ribbonLight =
        glm::vec4(look.intensity, look.core, look.tube ? 1.0f : 0.0f, look.depthFade);
}

FadeDepthSource::FadeDepthSource(const gpu::Context& ctx)
    : sampler_(gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)) {
    gpu::ImageDesc desc;
    desc.format = kDepthFormat;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.debugName = "far depth";
    far_ = gpu::createImage(ctx, desc);
    const float farPlane = 1.0f;
    gpu::uploadImage(ctx, far_, std::as_bytes(std::span(&farPlane, 1)),
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

gpu::DescriptorWrite FadeDepthSource::binding(const gpu::Image* sceneDepth) const {
    return gpu::bindImage(2, sceneDepth ? *sceneDepth : far_,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get());
}

RibbonTextureSource::RibbonTextureSource(const gpu::Context& ctx)
    : sampler_(gpu::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT)) {
    scene::TextureImage white;
    white.width = white.height = 1;
    white.rgba = {255, 255, 255, 255};
    white_ = upload(ctx, white, "no ribbon texture");
    noDistances_ = effectStorage(ctx, 64, 0, "no ribbon distances");
}

gpu::Image RibbonTextureSource::upload(const gpu::Context& ctx, const scene::TextureImage& texture,
                                       const char* name) {
    gpu::ImageDesc desc;
    desc.extent = {texture.width, texture.height, 1};
    desc.format = VK_FORMAT_R8G8B8A8_SRGB; // PNG colours are sRGB; sampling gives linear ones
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.debugName = name;
    gpu::Image image = gpu::createImage(ctx, desc);
    gpu::uploadImage(ctx, image, std::as_bytes(std::span(texture.rgba)),
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return image;
}

gpu::DescriptorWrite RibbonTextureSource::distances(const gpu::Buffer* distances) const {
    return gpu::bindBuffer(4, distances ? *distances : noDistances_);
}

gpu::DescriptorWrite RibbonTextureSource::texture(const gpu::Image* texture) const {
    return gpu::bindImage(5, texture ? *texture : white_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                          sampler_.get());
}

void setRibbonTexture(shared::EffectDraw& draw, const scene::RibbonLook& look, float now,
                      float ageSpan, float lifetime) {
    const scene::RibbonTexture& t = look.texture;
    draw.ribbonTexture = glm::vec4(0.0f);
    if (t.file.empty()) return;
    float scale = 1.0f;
    switch (t.uv) {
    case scene::TextureUv::Stretch:
        scale = 1.0f / std::max(ageSpan, 1e-6f);
        break;
    case scene::TextureUv::PerSegment:
        break;
    case scene::TextureUv::Tiled:
        scale = t.repeats / std::max(lifetime, 1e-6f);
        break;
    case scene::TextureUv::Distance:
        scale = 1.0f / t.tileLength;
        break;
    }
    // The offset of the moment: u grows towards the tail, so a texel flows that way as the offset
    // falls, -scroll * now, kept in [0, 1) (a float of scroll * now loses the fraction after a long
    // run); exactly 0 without scrolling.
    const double offset = t.scroll == 0.0f ? 0.0 : -double(t.scroll) * double(now);
    draw.ribbonTexture = glm::vec4(float(int(t.uv) + 1), scale, float(offset - std::floor(offset)),
                                   t.erosionOverLife.empty() ? 0.0f : t.erosionSoftness);
}

gpu::Buffer sceneFrameBuffer(const gpu::Context& ctx, const char* name) {
    return gpu::createBuffer(ctx, sizeof(shared::SceneFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             gpu::MemoryUsage::Upload, name);
}

gpu::Buffer effectStorage(const gpu::Context& ctx, VkDeviceSize bytes, VkBufferUsageFlags extra,
                          const char* name) {
    return gpu::createBuffer(ctx, std::max<VkDeviceSize>(bytes, 64),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | extra,
                             gpu::MemoryUsage::DeviceLocal, name);
}

gpu::Buffer effectCounters(const gpu::Context& ctx, VkDeviceSize bytes, const char* name) {
    gpu::Buffer counters =
        gpu::createBuffer(ctx, bytes,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          gpu::MemoryUsage::Readback, name);
    std::memset(counters.mapped, 0, bytes);
    return counters;
}

MeshEffect::MeshEffect(const gpu::Context& ctx, size_t effectIndex, std::optional<glm::vec4> colour,
                       trajectory::Source bound, VkBufferUsageFlags skinnedUsage, const char* label)
    : index(effectIndex), source(std::move(bound)), vertexCount(uint32_t(source.vertices.size())) {
    const std::string name(label);
    const VkDeviceSize n = vertexCount;
    input = effectStorage(ctx, n * sizeof(shared::SkinVertexIn), 0, (name + " bind pose").c_str());
    gpu::uploadBuffer(ctx, input, std::span<const shared::SkinVertexIn>(source.vertices));
    palette = gpu::createBuffer(
        ctx, std::max<size_t>(source.palette.size(), 1) * sizeof(shared::SkinJoint),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, (name + " palette").c_str());
    skinned = effectStorage(ctx, n * sizeof(shared::SkinVertexOut), skinnedUsage,
                            (name + " skinned").c_str());
    std::vector<glm::vec4> rgba = source.colours;
    if (colour) std::fill(rgba.begin(), rgba.end(), *colour);
    colours = effectStorage(ctx, n * sizeof(glm::vec4), 0, (name + " colours").c_str());
    gpu::uploadBuffer(ctx, colours, std::span<const glm::vec4>(rgba));
}

void MeshEffect::skin(VkCommandBuffer cmd, anim::SkinVertices& skinning,
                      const anim::Character& character, const anim::Pose& pose,
                      const glm::mat4& placement) const {
    const std::vector<shared::SkinJoint> joints =
        anim::packPalette(trajectory::sourcePalette(character, source, pose, placement));
    std::memcpy(palette.mapped, joints.data(), joints.size() * sizeof(shared::SkinJoint));
    skinning.record(cmd, palette, uint32_t(joints.size()), input, skinned, vertexCount);
}

void drawBuiltTriangles(VkCommandBuffer cmd, gpu::Program& program, const gpu::Buffer& frame,
                        const gpu::Buffer& vertices, const gpu::Buffer& counters, float fps,
                        const scene::VolumeLook& look, const gpu::Buffer& style) {
    shared::EffectDraw d{};
    d.timing = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f / fps);
    d.tint = glm::vec4(1.0f);
    setVolumeLook(d, look, true);
    program.bind(cmd, {gpu::bindBuffer(0, frame), gpu::bindBuffer(1, style)});
    program.push(cmd, d);
    const VkBuffer vb = vertices.get();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdDrawIndirect(cmd, counters.get(), 0, 1, sizeof(VkDrawIndirectCommand));
}

Welding weldByPosition(std::span<const shared::SkinVertexIn> vertices) {
    std::map<std::array<float, 3>, uint32_t> groups;
    Welding out;
    out.group.resize(vertices.size());
    for (size_t v = 0; v < vertices.size(); ++v) {
        const glm::vec4& p = vertices[v].position;
        out.group[v] = groups.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(groups.size()))
                           .first->second;
    }
    out.groupCount = uint32_t(groups.size());
    return out;
}

void transferToComputeBarrier(VkCommandBuffer cmd) {
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void computeToComputeBarrier(VkCommandBuffer cmd) {
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void computeToDrawBarrier(VkCommandBuffer cmd) {
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT |
            VK_PIPELINE_STAGE_2_HOST_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
            VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

FrameHistory::Step FrameHistory::step(uint64_t simulationSerial, uint32_t frame) {
    const bool sameRun = recorded_ && simulationSerial == serial_;
    if (sameRun && frame == frame_) return Step::Same;
    const bool next = sameRun && frame == frame_ + 1;
    recorded_ = true;
    serial_ = simulationSerial;
    frame_ = frame;
    return next ? Step::Next : Step::Restart;
}

} // namespace mfx::render
