#include "render/character_pass.h"

#include "core/anim/skinning.h"
#include "core/gpu/check.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "render/render_target.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <tuple>

namespace mfx::render {

namespace {

constexpr VkBufferUsageFlags kStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

} // namespace

CharacterPass::CharacterPass(const gpu::Context& ctx, std::span<const anim::Character> cast,
                             const scene::Scene& scene, VkSampleCountFlagBits samples)
    : ctx_(ctx), cast_(cast), scene_(scene), skinning_(ctx) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "character";
    desc.vertex = shaders::character_vert;
    desc.fragment = shaders::character_frag;
    desc.pushConstantSize = sizeof(shared::SceneObject);
    desc.vertexStride = sizeof(shared::SkinVertexOut);
    desc.attributes = {{0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                       {1, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
    desc.colorFormats = {kSceneColorFormat};
    desc.depthFormat = kDepthFormat;
    desc.depthTest = true;
    desc.depthWrite = true;
    desc.samples = samples;
    program_ = gpu::createGraphicsProgram(ctx, desc);
    auto outlines = [&](size_t c) {
        const scene::CharacterSpec& look = scene.characters[c];
        return scene::characterStyle(look) == scene::CharacterStyle::Toon &&
               look.outlineWidth > 0.0f;
    };
    const size_t characters = std::min(cast.size(), scene.characters.size());
    for (size_t c = 0; c < characters; ++c)
        outlined_ = outlined_ || outlines(c);
    if (outlined_) {
        gpu::GraphicsProgramDesc outline = desc;
        outline.name = "outline";
        outline.vertex = shaders::outline_vert;
        outline.fragment = shaders::outline_frag;
        outline.pushConstantSize = sizeof(shared::OutlineDraw);
        outline.cullMode = VK_CULL_MODE_FRONT_BIT; // the hull's back faces only
        outlineProgram_ = gpu::createGraphicsProgram(ctx, outline);
    }
    frame_ = gpu::createBuffer(ctx, sizeof(shared::SceneFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               gpu::MemoryUsage::Upload, "scene frame");

    // The key light's shadow map: depth only, sampled with comparison (outside it: lit).
    gpu::GraphicsProgramDesc shadowDesc;
    shadowDesc.name = "shadow";
    shadowDesc.vertex = shaders::shadow_vert;
    shadowDesc.pushConstantSize = sizeof(glm::mat4);
    shadowDesc.vertexStride = sizeof(shared::SkinVertexOut);
    shadowDesc.attributes = {{0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}};
    shadowDesc.depthFormat = kDepthFormat;
    shadowDesc.depthTest = true;
    shadowDesc.depthWrite = true;
    shadowProgram_ = gpu::createGraphicsProgram(ctx, shadowDesc);
    gpu::ImageDesc map;
    map.extent = {kShadowSize, kShadowSize, 1};
    map.format = kDepthFormat;
    map.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    map.debugName = "shadow map";
    shadowMap_ = gpu::createImage(ctx, map);
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = VK_FILTER_LINEAR;
    sampler.minFilter = VK_FILTER_LINEAR;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    sampler.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    sampler.compareEnable = VK_TRUE;
    sampler.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    VkSampler handle = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateSampler(ctx.device(), &sampler, nullptr, &handle));
    shadowSampler_ = gpu::UniqueSampler(ctx.device(), handle);
    // Until the first shadow(): a cleared map in the sampled layout.
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        gpu::transitionImage(cmd, shadowMap_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    resources_ = {gpu::bindBuffer(0, frame_),
                  gpu::bindImage(1, shadowMap_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                 shadowSampler_.get())};

    for (size_t c = 0; c < characters; ++c)
        addCharacter(ctx, c, outlines(c));
    const scene::StageSpec& stage = scene.stage;
    if (stage.floor)
        addStageQuad(ctx, glm::vec3(stage.floorCentre.x, stage.floorHeight, stage.floorCentre.z),
                     glm::vec3(0, 0, stage.floorHalfSize), glm::vec3(stage.floorHalfSize, 0, 0),
                     stage.floorColour);
    if (stage.backdrop)
        addStageQuad(ctx, stage.backdropCentre, stage.backdropHalfWidth,
                     glm::vec3(0, stage.backdropHalfHeight, 0), stage.backdropColour);
}

// Character `c`'s primitives as parts (with their outline hulls when `outlined`).
void CharacterPass::addCharacter(const gpu::Context& ctx, size_t c, bool outlined) {
    const anim::Character& character = cast_[c];
    for (const anim::Mesh& mesh : character.meshes)
        for (const anim::Primitive& p : mesh.primitives) {
            if (p.positions.empty() || p.indices.empty()) continue;
            Part part;
            part.primitive = &p;
            part.character = c;
            part.outlined = outlined;
            part.vertexCount = uint32_t(p.positions.size());
            part.indexCount = uint32_t(p.indices.size());
            part.jointCount =
                p.skin >= 0 ? uint32_t(character.skins[size_t(p.skin)].joints.size()) : 1;
            const auto packed = anim::packVertices(p);
            part.input = gpu::createBuffer(ctx, packed.size() * sizeof(shared::SkinVertexIn),
                                           kStorage, gpu::MemoryUsage::DeviceLocal, "bind pose");
            gpu::uploadBuffer(ctx, part.input, std::span<const shared::SkinVertexIn>(packed));
            part.output = gpu::createBuffer(ctx, packed.size() * sizeof(shared::SkinVertexOut),
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                            gpu::MemoryUsage::DeviceLocal, "skinned");
            if (part.outlined) {
                std::vector<shared::SkinVertexIn> hull = packed;
                const std::vector<glm::vec3> welded =
                    anim::weldedNormals(p.positions, p.normals, glm::vec3(0.0f, 1.0f, 0.0f));
                for (size_t v = 0; v < hull.size(); ++v)
                    hull[v].normal = glm::vec4(welded[v], 0.0f);
                part.outlineInput =
                    gpu::createBuffer(ctx, hull.size() * sizeof(shared::SkinVertexIn), kStorage,
                                      gpu::MemoryUsage::DeviceLocal, "outline bind pose");
                gpu::uploadBuffer(ctx, part.outlineInput,
                                  std::span<const shared::SkinVertexIn>(hull));
                part.outlineOutput = gpu::createBuffer(
                    ctx, hull.size() * sizeof(shared::SkinVertexOut),
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                    gpu::MemoryUsage::DeviceLocal, "outline skinned");
            }
            part.indices = gpu::createBuffer(ctx, p.indices.size() * sizeof(uint32_t),
                                             VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
                                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                             gpu::MemoryUsage::DeviceLocal, "character indices");
            gpu::uploadBuffer(ctx, part.indices, std::span<const uint32_t>(p.indices));
            part.palette = gpu::createBuffer(ctx, part.jointCount * sizeof(shared::SkinJoint),
                                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             gpu::MemoryUsage::Upload, "character palette");
            parts_.push_back(std::move(part));
        }
}

// A rectangle centre ± u ± v; its normal u × v.
void CharacterPass::addStageQuad(const gpu::Context& ctx, glm::vec3 centre, glm::vec3 u,
                                 glm::vec3 v, glm::vec3 colour) {
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const shared::SkinVertexOut vertices[4] = {
        {glm::vec4(centre - u - v, 1.0f), glm::vec4(n, 0.0f)},
        {glm::vec4(centre + u - v, 1.0f), glm::vec4(n, 0.0f)},
        {glm::vec4(centre + u + v, 1.0f), glm::vec4(n, 0.0f)},
        {glm::vec4(centre - u + v, 1.0f), glm::vec4(n, 0.0f)}};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    StageMesh mesh;
    mesh.vertices = gpu::createBuffer(
        ctx, sizeof vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        gpu::MemoryUsage::DeviceLocal, "stage vertices");
    gpu::uploadBuffer(ctx, mesh.vertices, std::span<const shared::SkinVertexOut>(vertices));
    mesh.indices = gpu::createBuffer(
        ctx, sizeof indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        gpu::MemoryUsage::DeviceLocal, "stage indices");
    gpu::uploadBuffer(ctx, mesh.indices, std::span<const uint32_t>(indices));
    mesh.indexCount = 6;
    mesh.colour = colour;
    stage_.push_back(std::move(mesh));
}

void CharacterPass::skin(VkCommandBuffer cmd, std::span<const anim::Pose> poses,
                         std::span<const glm::mat4> placements) {
    // One palette per character and skin (or rigid node), however many primitives it moves.
    std::map<std::tuple<size_t, int, int>, std::vector<shared::SkinJoint>> palettes;
    for (Part& part : parts_) {
        if (part.character >= poses.size() || part.character >= placements.size()) continue;
        const anim::Primitive& p = *part.primitive;
        const anim::Pose& pose = poses[part.character];
        const auto key = p.skin >= 0 ? std::make_tuple(part.character, p.skin, -1)
                                     : std::make_tuple(part.character, -1, p.node);
        auto it = palettes.find(key);
        if (it == palettes.end()) {
            std::vector<glm::mat4> matrices =
                p.skin >= 0 ? anim::jointMatrices(cast_[part.character], p.skin, pose)
                            : std::vector<glm::mat4>{p.node >= 0 ? pose.world[size_t(p.node)]
                                                                 : glm::mat4(1.0f)};
            for (glm::mat4& m : matrices)
                m = placements[part.character] * m;
            it = palettes.emplace(key, anim::packPalette(anim::dualQuatPalette(matrices))).first;
        }
        std::memcpy(part.palette.mapped, it->second.data(),
                    it->second.size() * sizeof(shared::SkinJoint));
        skinning_.record(cmd, part.palette, part.jointCount, part.input, part.output,
                         part.vertexCount);
        if (part.outlined)
            skinning_.record(cmd, part.palette, part.jointCount, part.outlineInput,
                             part.outlineOutput, part.vertexCount);
    }
}

void CharacterPass::shadow(VkCommandBuffer cmd) {
    // Around where the first character stands, big enough for a kick or a sword's reach
    // (fitScene sizes it to the characters' animated bounds when it frames the camera).
    const glm::vec3 centre = scene_.stage.shadowCentre.value_or(scene_.characters.front().position +
                                                                glm::vec3(0.0f, 1.0f, 0.0f));
    const scene::LightSpec key = scene_.lights.empty() ? scene::LightSpec{} : scene_.lights.front();
    lightViewProjection_ = lightViewProjection(key, centre, scene_.stage.shadowRadius);
    shadowReady_ = key.shadow;
    if (!key.shadow) return;
    gpu::imageBarrier(cmd, shadowMap_, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = shadowMap_.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {kShadowSize, kShadowSize}};
    rendering.layerCount = 1;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);
    const VkViewport viewport{0.0f, 0.0f, float(kShadowSize), float(kShadowSize), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {kShadowSize, kShadowSize}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    shadowProgram_.bind(cmd);
    shadowProgram_.push(cmd, lightViewProjection_);
    const VkDeviceSize offset = 0;
    for (const Part& part : parts_) { // the stage only receives shadows
        VkBuffer vb = part.output.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, part.indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, part.indexCount, 1, 0, 0, 0);
    }
    vkCmdEndRendering(cmd);
    gpu::imageBarrier(cmd, shadowMap_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void CharacterPass::draw(VkCommandBuffer cmd, const SceneCamera& camera, bool withStage) {
    const shared::SceneFrame frame =
        sceneFrame(scene_, camera, lightViewProjection_, shadowReady_ ? kShadowSize : 0);
    std::memcpy(frame_.mapped, &frame, sizeof frame);
    program_.bind(cmd, resources_);
    const VkDeviceSize offset = 0;
    // `look`: the character's, null for the stage.
    auto drawMesh = [&](const gpu::Buffer& vertices, const gpu::Buffer& indices, uint32_t count,
                        glm::vec3 colour, const scene::CharacterSpec* look) {
        shared::SceneObject object{};
        object.model = glm::mat4(1.0f);
        object.baseColor = glm::vec4(colour, 1.0f);
        if (look && scene::characterStyle(*look) == scene::CharacterStyle::Toon)
            object.style = glm::vec4(MFX_STYLE_TOON, float(look->toonBands), look->rim, 0.0f);
        program_.push(cmd, object);
        VkBuffer vb = vertices.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, count, 1, 0, 0, 0);
    };
    for (const StageMesh& m : stage_)
        if (withStage) drawMesh(m.vertices, m.indices, m.indexCount, m.colour, nullptr);
    for (const Part& part : parts_)
        drawMesh(part.output, part.indices, part.indexCount,
                 glm::vec3(part.primitive->baseColor) * scene_.characters[part.character].tint,
                 &scene_.characters[part.character]);
}

void CharacterPass::drawOutline(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    if (!outlined_) return;
    outlineProgram_.bind(cmd, {gpu::bindBuffer(0, frame_)}); // written by draw()
    const VkDeviceSize offset = 0;
    for (const Part& part : parts_) {
        if (!part.outlined) continue;
        const scene::CharacterSpec& look = scene_.characters[part.character];
        shared::OutlineDraw d{};
        d.colour = glm::vec4(look.outlineColour, 1.0f);
        d.width = glm::vec4(look.outlineWidth, 2.0f / float(width), 2.0f / float(height), 0.0f);
        outlineProgram_.push(cmd, d);
        VkBuffer vb = part.outlineOutput.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, part.indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, part.indexCount, 1, 0, 0, 0);
    }
}

} // namespace mfx::render
