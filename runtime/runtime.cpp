// The C API of include/motionfx/motionfx.h over the project's own classes. Every entry point
// catches what the code below it throws: nothing but a result crosses the C boundary.
#include "motionfx/motionfx.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "core/scene/scene.h"
#include "sim/scene_simulation.h"

#include <exception>
#include <filesystem>
#include <memory>
#include <new>
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
    mfx::anim::Character character; // the simulation keeps a reference to it: declared first
    std::unique_ptr<mfx::sim::SceneSimulation> simulation;
    std::vector<std::string> names;
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
    try {
        auto scene = readScene(*desc);
        if (!scene) return fail(runtime, MFX_ERROR_SCENE, scene.error().message);
        auto character = mfx::scene::loadCharacter(scene.value());
        if (!character) return fail(runtime, MFX_ERROR_SCENE, character.error().message);
        auto made = std::make_unique<MfxEffects_T>();
        made->runtime = runtime;
        made->character = std::move(character).value();
        auto simulation =
            mfx::sim::SceneSimulation::create(*runtime->context, scene.value(), made->character);
        if (!simulation) return fail(runtime, MFX_ERROR_SCENE, simulation.error().message);
        made->simulation = std::move(simulation).value();
        for (const mfx::scene::EffectSpec& effect : made->simulation->scene().effects)
            made->names.push_back(effect.name);
        runtime->effects.insert(made.get());
        *effects = made.release();
        return MFX_SUCCESS;
    } catch (const std::bad_alloc&) {
        return fail(runtime, MFX_ERROR_VULKAN, "out of host memory");
    } catch (const mfx::gpu::VulkanError& e) {
        return fail(runtime, MFX_ERROR_VULKAN, e.what());
    } catch (const std::exception& e) {
        return fail(runtime, MFX_ERROR_INTERNAL, e.what());
    }
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
    return MFX_SUCCESS;
}

const char* mfxEffectName(MfxEffects effects, uint32_t index) {
    if (effects == nullptr || index >= effects->names.size()) return nullptr;
    return effects->names[index].c_str();
}

} // extern "C"
