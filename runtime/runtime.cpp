// The C API of include/motionfx/motionfx.h over the project's own classes. Every entry point
// catches what the code below it throws: nothing but a result crosses the C boundary.
#include "motionfx/motionfx.h"

#include "core/gpu/context.h"

#include <exception>
#include <memory>
#include <new>
#include <string>

static_assert(MFX_VERSION_MAJOR == MOTIONFX_VERSION_MAJOR &&
                  MFX_VERSION_MINOR == MOTIONFX_VERSION_MINOR &&
                  MFX_VERSION_PATCH == MOTIONFX_VERSION_PATCH,
              "include/motionfx/motionfx.h and CMakeLists.txt give different versions");

struct MfxRuntime_T {
    std::unique_ptr<mfx::gpu::Context> context;
    MfxMessageCallback callback = nullptr;
    void* user = nullptr;
    std::string lastError;
};

namespace {

// Reports a failure through the callback (when there is one) and keeps it for LastError.
MfxResult fail(MfxRuntime runtime, MfxMessageCallback callback, void* user, MfxResult result,
               const std::string& message) {
    if (runtime != nullptr) runtime->lastError = message;
    if (callback != nullptr) callback(result, message.c_str(), user);
    return result;
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
    } catch (const std::exception& e) {
        return fail(nullptr, callback, user, MFX_ERROR_INTERNAL, e.what());
    }
}

void mfxDestroyRuntime(MfxRuntime runtime) {
    delete runtime;
}

const char* mfxRuntimeLastError(MfxRuntime runtime) {
    return runtime != nullptr ? runtime->lastError.c_str() : "";
}

const char* mfxRuntimeDeviceName(MfxRuntime runtime) {
    return runtime != nullptr ? runtime->context->info().name.c_str() : "";
}

} // extern "C"
