// The C API of include/motionfx/motionfx.h over the project's own classes. Every entry point
// catches what the code below it throws: nothing but a result crosses the C boundary.
#include "motionfx/motionfx.h"

#include "core/anim/sampling.h"
#include "core/anim/skinning.h"
#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "core/scene/scene.h"
#include "render/host_frame.h"
#include "sim/scene_simulation.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <string>
#include <vector>

static_assert(MFX_VERSION_MAJOR == MOTIONFX_VERSION_MAJOR &&
                  MFX_VERSION_MINOR == MOTIONFX_VERSION_MINOR &&
                  MFX_VERSION_PATCH == MOTIONFX_VERSION_PATCH,
              "include/motionfx/motionfx.h and CMakeLists.txt give different versions");

struct MfxRuntime_T {
    std::unique_ptr<mfx::gpu::Context> context;
    MfxMessageCallback callback = nullptr;
    void* user = nullptr;
    std::string lastError;
    std::set<MfxEffects> effects; // alive: freed with the runtime if the host has not
};

struct MfxEffects_T {
    MfxRuntime runtime = nullptr;
    // The scene's characters (the host's animation drives the first); the simulation keeps a
    // reference to them: declared first.
    mfx::scene::Cast cast;
    std::unique_ptr<mfx::sim::SceneSimulation> simulation;
    std::vector<std::string> names;
    // The drawing into the host's frames, made by the first mfxRecordFrame (again when the
    // samples asked for change).
    std::unique_ptr<mfx::render::HostFrame> frame;
    uint32_t frameSamples = 0;
    int64_t lastFrame = -1;     // the simulation frame last recorded
    bool frameToFinish = false; // its statistics and sleep decisions not yet taken
};

namespace {

// Reports a failure through the callback (when there is one) and keeps it for LastError.
MfxResult fail(MfxRuntime runtime, MfxMessageCallback callback, void* user, MfxResult result,
               const std::string& message) {
    if (runtime != nullptr) runtime->lastError = message;
    if (callback != nullptr) callback(result, message.c_str(), user);
    return result;
}

MfxResult fail(MfxRuntime runtime, MfxResult result, const std::string& message) {
    return fail(runtime, runtime->callback, runtime->user, result, message);
}

// The scene a description names, parsed and checked.
mfx::Result<mfx::scene::Scene> readScene(const MfxEffectsDesc& desc) {
    namespace fs = std::filesystem;
    if (desc.sceneFile != nullptr) return mfx::scene::loadScene(fs::path(desc.sceneFile));
    // The text's relative paths are read against the base folder: the scene's `file` is where
    // they are resolved from (scene::characterFile) and what its errors name.
    const std::string where = desc.baseFolder != nullptr && *desc.baseFolder != '\0'
                                  ? (fs::path(desc.baseFolder) / "(scene JSON)").string()
                                  : std::string("(scene JSON)");
    return mfx::scene::parseScene(desc.sceneJson, where);
}

// Runs `body` on `runtime`, turning what it throws into a result and a message.
template <class Body>
MfxResult guarded(MfxRuntime runtime, Body&& body) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return fail(runtime, MFX_ERROR_VULKAN, "out of host memory");
    } catch (const mfx::gpu::VulkanError& e) {
        return fail(runtime, MFX_ERROR_VULKAN, e.what());
    } catch (const std::exception& e) {
        return fail(runtime, MFX_ERROR_INTERNAL, e.what());
    }
}

mfx::render::HostImage hostImage(const MfxImage& image) {
    return {image.image, image.format, image.layout, image.finalLayout};
}

} // namespace

extern "C" {

uint32_t mfxVersion(void) {
    return MOTIONFX_VERSION_MAJOR * 10000u + MOTIONFX_VERSION_MINOR * 100u + MOTIONFX_VERSION_PATCH;
}

const char* mfxResultName(MfxResult result) {
    switch (result) {
    case MFX_SUCCESS:
        return "MFX_SUCCESS";
    case MFX_ERROR_INVALID_ARGUMENT:
        return "MFX_ERROR_INVALID_ARGUMENT";
    case MFX_ERROR_UNSUPPORTED_DEVICE:
        return "MFX_ERROR_UNSUPPORTED_DEVICE";
    case MFX_ERROR_VULKAN:
        return "MFX_ERROR_VULKAN";
    case MFX_ERROR_INTERNAL:
        return "MFX_ERROR_INTERNAL";
    case MFX_ERROR_SCENE:
        return "MFX_ERROR_SCENE";
    }
    return "MFX_ERROR_UNKNOWN";
}

uint32_t mfxRequiredDeviceExtensions(const char** names, uint32_t capacity) {
    const auto required = mfx::gpu::requiredDeviceExtensions();
    for (uint32_t i = 0; names != nullptr && i < capacity && i < required.size(); ++i)
        names[i] = required[i];
    return uint32_t(required.size());
}

MfxResult mfxCreateRuntime(const MfxRuntimeDesc* desc, MfxRuntime* runtime) {
    if (runtime != nullptr) *runtime = nullptr;
    if (desc == nullptr || runtime == nullptr)
        return MFX_ERROR_INVALID_ARGUMENT; // no callback to say it through
    MfxMessageCallback callback = desc->messageCallback;
    void* user = desc->messageUser;
    if (desc->structVersion != MFX_RUNTIME_DESC_VERSION)
        return fail(nullptr, callback, user, MFX_ERROR_INVALID_ARGUMENT,
                    "MfxRuntimeDesc.structVersion is " + std::to_string(desc->structVersion) +
                        "; this library reads version " + std::to_string(MFX_RUNTIME_DESC_VERSION));
    if (desc->enabledExtensionCount > 0 && desc->enabledExtensionNames == nullptr)
        return fail(nullptr, callback, user, MFX_ERROR_INVALID_ARGUMENT,
                    "MfxRuntimeDesc.enabledExtensionNames is null but enabledExtensionCount is " +
                        std::to_string(desc->enabledExtensionCount));
    try {
        mfx::gpu::AdoptedDevice host;
        host.instance = desc->instance;
        host.physicalDevice = desc->physicalDevice;
        host.device = desc->device;
        host.queueFamily = desc->queueFamilyIndex;
        host.queue = desc->queue;
        host.enabledFeatures = desc->enabledFeatures;
        for (uint32_t i = 0; i < desc->enabledExtensionCount; ++i)
            if (desc->enabledExtensionNames[i] != nullptr)
                host.enabledExtensions.emplace_back(desc->enabledExtensionNames[i]);
        auto adopted = mfx::gpu::Context::adopt(host);
        if (!adopted) {
            const bool handles = desc->instance && desc->physicalDevice && desc->device &&
                                 desc->queue && desc->enabledFeatures;
            return fail(nullptr, callback, user,
                        handles ? MFX_ERROR_UNSUPPORTED_DEVICE : MFX_ERROR_INVALID_ARGUMENT,
                        adopted.error().message);
        }
        auto made = std::make_unique<MfxRuntime_T>();
        made->context = std::move(adopted).value();
        made->callback = callback;
        made->user = user;
        *runtime = made.release();
        return MFX_SUCCESS;
    } catch (const std::bad_alloc&) {
        return fail(nullptr, callback, user, MFX_ERROR_VULKAN, "out of host memory");
    } catch (const mfx::gpu::VulkanError& e) {
        return fail(nullptr, callback, user, MFX_ERROR_VULKAN, e.what());
    } catch (const std::exception& e) {
        return fail(nullptr, callback, user, MFX_ERROR_INTERNAL, e.what());
    }
}

void mfxDestroyRuntime(MfxRuntime runtime) {
    if (runtime == nullptr) return;
    // Effects the host did not destroy go first: they use the runtime's device objects.
    if (!runtime->effects.empty()) vkQueueWaitIdle(runtime->context->graphicsQueue().queue);
    for (MfxEffects effects : runtime->effects)
        delete effects;
    delete runtime;
}

const char* mfxRuntimeLastError(MfxRuntime runtime) {
    return runtime != nullptr ? runtime->lastError.c_str() : "";
}

const char* mfxRuntimeDeviceName(MfxRuntime runtime) {
    return runtime != nullptr ? runtime->context->info().name.c_str() : "";
}

MfxResult mfxCreateEffects(MfxRuntime runtime, const MfxEffectsDesc* desc, MfxEffects* effects) {
    if (effects != nullptr) *effects = nullptr;
    if (runtime == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    runtime->lastError.clear();
    if (desc == nullptr || effects == nullptr)
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxCreateEffects: the description and the handle to fill must be given");
    if (desc->structVersion != MFX_EFFECTS_DESC_VERSION)
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "MfxEffectsDesc.structVersion is " + std::to_string(desc->structVersion) +
                        "; this library reads version " + std::to_string(MFX_EFFECTS_DESC_VERSION));
    if ((desc->sceneFile == nullptr) == (desc->sceneJson == nullptr))
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "MfxEffectsDesc: give exactly one of sceneFile and sceneJson");
    return guarded(runtime, [&] {
        auto scene = readScene(*desc);
        if (!scene) return fail(runtime, MFX_ERROR_SCENE, scene.error().message);
        auto cast = mfx::scene::loadCast(scene.value());
        if (!cast) return fail(runtime, MFX_ERROR_SCENE, cast.error().message);
        auto made = std::make_unique<MfxEffects_T>();
        made->runtime = runtime;
        made->cast = std::move(cast).value();
        auto simulation =
            mfx::sim::SceneSimulation::create(*runtime->context, scene.value(), made->cast);
        if (!simulation) return fail(runtime, MFX_ERROR_SCENE, simulation.error().message);
        made->simulation = std::move(simulation).value();
        for (const mfx::scene::EffectSpec& effect : made->simulation->scene().effects)
            made->names.push_back(effect.name);
        runtime->effects.insert(made.get());
        *effects = made.release();
        return MFX_SUCCESS;
    });
}

void mfxDestroyEffects(MfxEffects effects) {
    if (effects == nullptr) return;
    // Frames recorded into the host's command buffers may still run.
    vkQueueWaitIdle(effects->runtime->context->graphicsQueue().queue);
    effects->runtime->effects.erase(effects);
    delete effects;
}

MfxResult mfxGetEffectsInfo(MfxEffects effects, MfxEffectsInfo* info) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    if (info == nullptr)
        return fail(effects->runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetEffectsInfo: the info to fill must be given");
    if (info->structVersion != MFX_EFFECTS_INFO_VERSION)
        return fail(effects->runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "MfxEffectsInfo.structVersion is " + std::to_string(info->structVersion) +
                        "; this library writes version " +
                        std::to_string(MFX_EFFECTS_INFO_VERSION));
    const mfx::sim::SceneSimulation& simulation = *effects->simulation;
    info->effectCount = uint32_t(effects->names.size());
    info->smokeGrids = uint32_t(simulation.smokeGrids().size());
    info->frameCount = simulation.frameCount();
    info->framesPerSecond = simulation.scene().output.fps;
    info->floorHeight = simulation.scene().stage.floorHeight;
    return MFX_SUCCESS;
}

const char* mfxEffectName(MfxEffects effects, uint32_t index) {
    if (effects == nullptr || index >= effects->names.size()) return nullptr;
    return effects->names[index].c_str();
}

MfxResult mfxGetCharacterMeshSize(MfxEffects effects, uint32_t* vertexCount, uint32_t* indexCount) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    effects->runtime->lastError.clear();
    if (vertexCount == nullptr || indexCount == nullptr)
        return fail(effects->runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetCharacterMeshSize: both counts to fill must be given");
    uint64_t vertices = 0, indices = 0;
    for (const mfx::anim::Mesh& mesh : effects->cast.front().meshes)
        for (const mfx::anim::Primitive& primitive : mesh.primitives) {
            vertices += primitive.positions.size();
            indices += primitive.indices.size();
        }
    if (vertices > UINT32_MAX || indices > UINT32_MAX)
        return fail(effects->runtime, MFX_ERROR_INTERNAL, "the character has over 2^32 vertices");
    *vertexCount = uint32_t(vertices);
    *indexCount = uint32_t(indices);
    return MFX_SUCCESS;
}

MfxResult mfxGetCharacterMesh(MfxEffects effects, double time, float* positions, float* normals,
                              uint32_t* indices) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    MfxRuntime runtime = effects->runtime;
    runtime->lastError.clear();
    if (!std::isfinite(time) || time < 0.0)
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetCharacterMesh: time must be a finite number of seconds >= 0; got " +
                        std::to_string(time));
    return guarded(runtime, [&] {
        const mfx::sim::SceneSimulation& simulation = *effects->simulation;
        const mfx::anim::Pose pose = simulation.poseAt(0, float(time));
        const glm::mat4 placement = simulation.placement();
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(placement)));
        size_t vertex = 0, index = 0;
        for (const mfx::anim::Mesh& mesh : effects->cast.front().meshes)
            for (const mfx::anim::Primitive& primitive : mesh.primitives) {
                if (indices != nullptr)
                    for (uint32_t i : primitive.indices)
                        indices[index++] = uint32_t(vertex) + i;
                if (positions != nullptr || normals != nullptr)
                    for (const mfx::anim::SkinnedVertex& v :
                         mfx::anim::skinPrimitive(effects->cast.front(), primitive, pose)) {
                        const glm::vec3 p = glm::vec3(placement * glm::vec4(v.position, 1.0f));
                        const glm::vec3 n = glm::normalize(normalMatrix * v.normal);
                        for (int c = 0; c < 3; ++c) {
                            if (positions != nullptr) positions[3 * vertex + size_t(c)] = p[c];
                            if (normals != nullptr) normals[3 * vertex + size_t(c)] = n[c];
                        }
                        ++vertex;
                    }
                else
                    vertex += primitive.positions.size();
            }
        return MFX_SUCCESS;
    });
}

MfxResult mfxGetSceneCamera(MfxEffects effects, float aspect, MfxCamera* camera) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    effects->runtime->lastError.clear();
    if (camera == nullptr)
        return fail(effects->runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetSceneCamera: the camera to fill must be given");
    if (!std::isfinite(aspect) || !(aspect > 1e-3f) || aspect > 1e3f)
        return fail(effects->runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetSceneCamera: aspect must be a width / height from 0.001 to 1000; got " +
                        std::to_string(aspect));
    const mfx::render::SceneCamera scene =
        mfx::render::makeCamera(effects->simulation->scene().camera, aspect);
    std::memcpy(camera->view, glm::value_ptr(scene.view), sizeof camera->view);
    std::memcpy(camera->projection, glm::value_ptr(scene.projection), sizeof camera->projection);
    camera->clipYDown = 0;
    return MFX_SUCCESS;
}

uint32_t mfxGetCharacterNodeCount(MfxEffects effects) {
    return effects != nullptr ? uint32_t(effects->cast.front().nodes.size()) : 0;
}

const char* mfxGetCharacterNodeName(MfxEffects effects, uint32_t index) {
    if (effects == nullptr || index >= effects->cast.front().nodes.size()) return nullptr;
    return effects->cast.front().nodes[index].name.c_str();
}

MfxResult mfxGetCharacterNodeMatrices(MfxEffects effects, double time, float* matrices) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    MfxRuntime runtime = effects->runtime;
    runtime->lastError.clear();
    if (matrices == nullptr)
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetCharacterNodeMatrices: the matrices to fill must be given");
    if (!std::isfinite(time) || time < 0.0)
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT,
                    "mfxGetCharacterNodeMatrices: time must be a finite number of seconds >= 0; "
                    "got " +
                        std::to_string(time));
    return guarded(runtime, [&] {
        const mfx::anim::Pose pose = effects->simulation->poseAt(0, float(time));
        for (size_t node = 0; node < pose.world.size(); ++node)
            std::memcpy(matrices + 16 * node, glm::value_ptr(pose.world[node]), 16 * sizeof(float));
        return MFX_SUCCESS;
    });
}

MfxResult mfxRecordFrame(MfxEffects effects, const MfxFrameDesc* desc) {
    if (effects == nullptr) return MFX_ERROR_INVALID_ARGUMENT;
    MfxRuntime runtime = effects->runtime;
    runtime->lastError.clear();
    auto invalid = [&](const std::string& message) {
        return fail(runtime, MFX_ERROR_INVALID_ARGUMENT, message);
    };
    if (desc == nullptr) return invalid("mfxRecordFrame: the frame's description must be given");
    if (desc->structVersion != MFX_FRAME_DESC_VERSION)
        return invalid("MfxFrameDesc.structVersion is " + std::to_string(desc->structVersion) +
                       "; this library reads version " + std::to_string(MFX_FRAME_DESC_VERSION));
    if (desc->commandBuffer == VK_NULL_HANDLE) return invalid("MfxFrameDesc.commandBuffer is null");
    if (!std::isfinite(desc->time) || desc->time < 0.0 || desc->time > 1e7)
        return invalid("MfxFrameDesc.time must be a number of seconds from 0 to 1e7; got " +
                       std::to_string(desc->time));
    const uint32_t samples = desc->samples == 0 ? 4u : desc->samples;
    if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
        return invalid("MfxFrameDesc.samples must be 0, 1, 2, 4 or 8; got " +
                       std::to_string(desc->samples));
    auto camera = mfx::render::cameraFromMatrices(glm::make_mat4(desc->camera.view),
                                                  glm::make_mat4(desc->camera.projection),
                                                  desc->camera.clipYDown != 0);
    if (!camera) return invalid("MfxFrameDesc." + camera.error().message);
    // The host's pose, checked whole before anything is recorded.
    std::optional<mfx::anim::Pose> pose;
    if (desc->nodeMatrices != nullptr || desc->nodeMatrixCount != 0) {
        const size_t nodes = effects->cast.front().nodes.size();
        if (desc->nodeMatrices == nullptr || desc->nodeMatrixCount != nodes)
            return invalid("MfxFrameDesc.nodeMatrixCount is " +
                           std::to_string(desc->nodeMatrixCount) +
                           (desc->nodeMatrices != nullptr ? "" : " and nodeMatrices is null") +
                           "; the character has " + std::to_string(nodes) +
                           " nodes (mfxGetCharacterNodeCount)");
        std::vector<glm::mat4> world(nodes);
        for (size_t node = 0; node < nodes; ++node) {
            for (size_t k = 0; k < 16; ++k)
                if (!std::isfinite(desc->nodeMatrices[16 * node + k]))
                    return invalid("MfxFrameDesc.nodeMatrices: node " + std::to_string(node) +
                                   " (" + effects->cast.front().nodes[node].name +
                                   ") has a value that is not a finite number");
            world[node] = glm::make_mat4(desc->nodeMatrices + 16 * node);
        }
        pose = mfx::anim::poseFromWorld(effects->cast.front(), std::move(world));
    }
    return guarded(runtime, [&] {
        mfx::sim::SceneSimulation& simulation = *effects->simulation;
        if (!effects->frame || effects->frameSamples != samples) {
            effects->frame = std::make_unique<mfx::render::HostFrame>(
                *runtime->context, simulation, VkSampleCountFlagBits(samples));
            effects->frameSamples = samples;
        }
        mfx::render::HostTargets targets;
        targets.width = desc->width;
        targets.height = desc->height;
        targets.colour = hostImage(desc->colour);
        targets.depth = hostImage(desc->depth);
        if (auto checked = effects->frame->check(targets); !checked)
            return invalid("MfxFrameDesc." + checked.error().message);

        // The frame the time has reached (a thousandth of a frame early counts: times summed
        // from 1 / fps in floating point fall just short of a frame's).
        const double fps = double(simulation.scene().output.fps);
        const int64_t reached = int64_t(std::floor(desc->time * fps + 1e-3));
        if (reached < effects->lastFrame)
            return invalid("MfxFrameDesc.time " + std::to_string(desc->time) +
                           " s is before frame " + std::to_string(effects->lastFrame) +
                           " already simulated (at " +
                           std::to_string(double(effects->lastFrame) / fps) +
                           " s): the effects only run forward; make them again to restart");
        // The previous frame's commands have finished (the host waited): its statistics, and
        // whether its grids sleep.
        if (effects->frameToFinish) {
            simulation.finishFrame();
            effects->frameToFinish = false;
        }
        uint32_t next = 0;
        const uint32_t* advance = nullptr;
        if (reached > effects->lastFrame) {
            next = uint32_t(effects->lastFrame + 1);
            advance = &next;
            effects->lastFrame = next;
            effects->frameToFinish = true;
        }
        effects->frame->record(desc->commandBuffer, simulation, advance,
                               simulation.frameTime(uint32_t(effects->lastFrame)), camera.value(),
                               targets, pose ? &*pose : nullptr);
        return MFX_SUCCESS;
    });
}

} // extern "C"
