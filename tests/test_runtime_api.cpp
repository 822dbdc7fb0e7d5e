// The runtime library's C API (include/motionfx/motionfx.h) on a device the host made with plain
// Vulkan calls: it borrows the device and leaves it working, several runtimes live in one process,
// and a device without what motionfx needs is refused with every missing thing named.
#include "core/scene/scene.h"
#include "motionfx/motionfx.h"
#include "tests/cli_run.h"
#include "tests/runtime/host_device.h"

#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

// The messages a callback received.
struct Messages {
    std::vector<std::pair<MfxResult, std::string>> received;
    static void callback(MfxResult result, const char* message, void* user) {
        static_cast<Messages*>(user)->received.emplace_back(result, message);
    }
};

MfxRuntimeDesc describe(const HostDevice& host, Messages* messages = nullptr) {
    return messages != nullptr ? runtimeDesc(host, &Messages::callback, messages)
                               : runtimeDesc(host);
}

std::unique_ptr<HostDevice> makeHost(const HostDeviceOptions& options = {}) {
    std::string why;
    auto host = HostDevice::make(options, why);
    EXPECT_NE(host, nullptr) << why;
    return host;
}

// A buffer made and freed on the host's device: it still works.
bool deviceStillWorks(const HostDevice& host) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 256;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(host.device, &info, nullptr, &buffer) != VK_SUCCESS) return false;
    vkDestroyBuffer(host.device, buffer, nullptr);
    return vkQueueWaitIdle(host.queue) == VK_SUCCESS;
}

// The one message mfxCreateRuntime sends when refusing a device made with `options`.
std::string deviceRefusal(const HostDeviceOptions& options) {
    auto host = makeHost(options);
    if (host == nullptr) return {};
    Messages messages;
    const MfxRuntimeDesc desc = describe(*host, &messages);
    MfxRuntime runtime = reinterpret_cast<MfxRuntime>(&messages); // overwritten with null
    EXPECT_EQ(mfxCreateRuntime(&desc, &runtime), MFX_ERROR_UNSUPPORTED_DEVICE);
    EXPECT_EQ(runtime, nullptr);
    EXPECT_EQ(messages.received.size(), 1u);
    EXPECT_TRUE(deviceStillWorks(*host)); // refused, it is the host's as before
    if (messages.received.empty()) return {};
    EXPECT_EQ(messages.received[0].first, MFX_ERROR_UNSUPPORTED_DEVICE);
    return messages.received[0].second;
}

TEST(RuntimeApi, TheLibraryIsTheHeadersVersion) {
    EXPECT_EQ(mfxVersion(),
              MFX_VERSION_MAJOR * 10000u + MFX_VERSION_MINOR * 100u + MFX_VERSION_PATCH);
    EXPECT_STREQ(mfxResultName(MFX_ERROR_UNSUPPORTED_DEVICE), "MFX_ERROR_UNSUPPORTED_DEVICE");
}

TEST(RuntimeApi, RequiredExtensionsAreListed) {
    ASSERT_EQ(mfxRequiredDeviceExtensions(nullptr, 0), 1u);
    const char* names[4] = {};
    EXPECT_EQ(mfxRequiredDeviceExtensions(names, 4), 1u);
    EXPECT_STREQ(names[0], VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    EXPECT_EQ(names[1], nullptr);
}

TEST(RuntimeApi, MadeOnTheHostsDeviceAndGoneWithoutIt) {
    auto host = makeHost();
    ASSERT_NE(host, nullptr);
    Messages messages;
    const MfxRuntimeDesc desc = describe(*host, &messages);
    MfxRuntime runtime = nullptr;
    ASSERT_EQ(mfxCreateRuntime(&desc, &runtime), MFX_SUCCESS)
        << (messages.received.empty() ? "" : messages.received[0].second);
    ASSERT_NE(runtime, nullptr);
    EXPECT_EQ(std::string(mfxRuntimeDeviceName(runtime)), host->name);
    EXPECT_STREQ(mfxRuntimeLastError(runtime), "");
    EXPECT_TRUE(messages.received.empty());
    mfxDestroyRuntime(runtime);
    // The host's device and queue are the host's still.
    EXPECT_TRUE(deviceStillWorks(*host));
    mfxDestroyRuntime(nullptr); // allowed
    // The validation layer watched it all (the set-up installs it; without it this proves less).
    EXPECT_TRUE(host->validated());
    EXPECT_EQ(host->validationErrors(), 0u);
}

// dynamicRendering and synchronization2 may come in their own structs instead of the 1.3 one.
TEST(RuntimeApi, FeaturesInTheirOwnStructsAreRead) {
    HostDeviceOptions standalone;
    standalone.standaloneStructs = true;
    auto host = makeHost(standalone);
    ASSERT_NE(host, nullptr);
    Messages messages;
    const MfxRuntimeDesc desc = describe(*host, &messages);
    MfxRuntime runtime = nullptr;
    EXPECT_EQ(mfxCreateRuntime(&desc, &runtime), MFX_SUCCESS)
        << (messages.received.empty() ? "" : messages.received[0].second);
    mfxDestroyRuntime(runtime);
    standalone.synchronization2 = false;
    EXPECT_NE(deviceRefusal(standalone).find("synchronization2"), std::string::npos);
}

TEST(RuntimeApi, SeveralRuntimesInOneProcess) {
    auto first = makeHost(), second = makeHost();
    ASSERT_NE(first, nullptr);
    ASSERT_NE(second, nullptr);
    const MfxRuntimeDesc a = describe(*first), b = describe(*second);
    MfxRuntime onFirst = nullptr, alsoOnFirst = nullptr, onSecond = nullptr;
    ASSERT_EQ(mfxCreateRuntime(&a, &onFirst), MFX_SUCCESS);
    ASSERT_EQ(mfxCreateRuntime(&a, &alsoOnFirst), MFX_SUCCESS);
    ASSERT_EQ(mfxCreateRuntime(&b, &onSecond), MFX_SUCCESS);
    EXPECT_NE(onFirst, alsoOnFirst);
    mfxDestroyRuntime(alsoOnFirst);
    // The others are untouched by it.
    EXPECT_EQ(std::string(mfxRuntimeDeviceName(onFirst)), first->name);
    EXPECT_EQ(std::string(mfxRuntimeDeviceName(onSecond)), second->name);
    mfxDestroyRuntime(onFirst);
    mfxDestroyRuntime(onSecond);
    EXPECT_TRUE(deviceStillWorks(*first));
    EXPECT_TRUE(deviceStillWorks(*second));
}

TEST(RuntimeApi, ADeviceWithoutWhatMotionfxNeedsIsRefusedNamingEachMissingThing) {
    HostDeviceOptions lacking;
    lacking.pushDescriptor = false;
    lacking.geometryShader = false;
    const std::string text = deviceRefusal(lacking);
    auto host = makeHost(); // the same physical device, made with everything
    ASSERT_NE(host, nullptr);
    EXPECT_NE(text.find(host->name), std::string::npos) << text;
    EXPECT_NE(text.find("geometryShader"), std::string::npos) << text;
    EXPECT_NE(text.find(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME), std::string::npos) << text;
    EXPECT_EQ(lineCount(text), 3u) << text; // the device, then one line for each
}

TEST(RuntimeApi, AMissingVulkan13FeatureIsNamed) {
    HostDeviceOptions lacking;
    lacking.synchronization2 = false;
    const std::string text = deviceRefusal(lacking);
    EXPECT_NE(text.find("synchronization2"), std::string::npos) << text;
    EXPECT_EQ(text.find("dynamicRendering"), std::string::npos) << text;
    EXPECT_EQ(lineCount(text), 2u) << text;
}

TEST(RuntimeApi, BadDescriptionsAreRefused) {
    auto host = makeHost();
    ASSERT_NE(host, nullptr);
    MfxRuntime runtime = nullptr;
    EXPECT_EQ(mfxCreateRuntime(nullptr, &runtime), MFX_ERROR_INVALID_ARGUMENT);
    Messages messages;
    MfxRuntimeDesc desc = describe(*host, &messages);
    EXPECT_EQ(mfxCreateRuntime(&desc, nullptr), MFX_ERROR_INVALID_ARGUMENT);

    const auto refused = [&](MfxRuntimeDesc bad, const char* word) {
        messages.received.clear();
        EXPECT_EQ(mfxCreateRuntime(&bad, &runtime), MFX_ERROR_INVALID_ARGUMENT) << word;
        EXPECT_EQ(runtime, nullptr);
        ASSERT_EQ(messages.received.size(), 1u) << word;
        EXPECT_NE(messages.received[0].second.find(word), std::string::npos)
            << messages.received[0].second;
    };
    MfxRuntimeDesc version = desc;
    version.structVersion = 99;
    refused(version, "structVersion");
    MfxRuntimeDesc noDevice = desc;
    noDevice.device = VK_NULL_HANDLE;
    refused(noDevice, "device");
    MfxRuntimeDesc noFeatures = desc;
    noFeatures.enabledFeatures = nullptr;
    refused(noFeatures, "VkPhysicalDeviceFeatures2");
    MfxRuntimeDesc noNames = desc;
    noNames.enabledExtensionCount = 2;
    noNames.enabledExtensionNames = nullptr;
    refused(noNames, "enabledExtensionNames");
    MfxRuntimeDesc badFamily = desc;
    badFamily.queueFamilyIndex = 1000;
    messages.received.clear();
    EXPECT_EQ(mfxCreateRuntime(&badFamily, &runtime), MFX_ERROR_UNSUPPORTED_DEVICE);
    ASSERT_EQ(messages.received.size(), 1u);
    EXPECT_NE(messages.received[0].second.find("queue family 1000"), std::string::npos);
}

// A runtime on a host device, for the effects tests.
class RuntimeEffects : public ::testing::Test {
protected:
    void SetUp() override {
        host_ = makeHost();
        ASSERT_NE(host_, nullptr);
        const MfxRuntimeDesc desc = describe(*host_, &messages_);
        ASSERT_EQ(mfxCreateRuntime(&desc, &runtime_), MFX_SUCCESS);
    }
    void TearDown() override {
        mfxDestroyRuntime(runtime_);
        // Everything motionfx did on the host's device passed the validation layer.
        if (host_ != nullptr) {
            EXPECT_EQ(host_->validationErrors(), 0u);
        }
    }

    MfxEffectsDesc fromFile(const std::string& path) {
        path_ = path;
        MfxEffectsDesc desc{};
        desc.structVersion = MFX_EFFECTS_DESC_VERSION;
        desc.sceneFile = path_.c_str();
        return desc;
    }
    MfxEffectsDesc fromJson(const std::string& json, const char* baseFolder = nullptr) {
        json_ = json;
        MfxEffectsDesc desc{};
        desc.structVersion = MFX_EFFECTS_DESC_VERSION;
        desc.sceneJson = json_.c_str();
        desc.baseFolder = baseFolder;
        return desc;
    }
    // The one message a refused call sent, after checking its result.
    std::string refusal(const MfxEffectsDesc& desc, MfxResult expected) {
        messages_.received.clear();
        MfxEffects effects = reinterpret_cast<MfxEffects>(&messages_);
        EXPECT_EQ(mfxCreateEffects(runtime_, &desc, &effects), expected);
        EXPECT_EQ(effects, nullptr);
        EXPECT_EQ(messages_.received.size(), 1u);
        if (messages_.received.empty()) return {};
        EXPECT_EQ(messages_.received[0].first, expected);
        EXPECT_EQ(messages_.received[0].second, mfxRuntimeLastError(runtime_));
        return messages_.received[0].second;
    }

    std::unique_ptr<HostDevice> host_;
    Messages messages_;
    MfxRuntime runtime_ = nullptr;
    std::string path_, json_;
};

TEST_F(RuntimeEffects, FromASceneFileWithItsEffectsInOrder) {
    const MfxEffectsDesc desc = fromFile(std::string(MFX_SOURCE_DIR) + "/docs/scenes/hero.json");
    MfxEffects effects = nullptr;
    ASSERT_EQ(mfxCreateEffects(runtime_, &desc, &effects), MFX_SUCCESS)
        << mfxRuntimeLastError(runtime_);
    MfxEffectsInfo info{};
    EXPECT_EQ(mfxGetEffectsInfo(effects, &info), MFX_ERROR_INVALID_ARGUMENT); // no version set
    info.structVersion = MFX_EFFECTS_INFO_VERSION;
    ASSERT_EQ(mfxGetEffectsInfo(effects, &info), MFX_SUCCESS);
    // What the program reads from the same file.
    const auto scene = scene::loadScene(std::string(MFX_SOURCE_DIR) + "/docs/scenes/hero.json");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(info.effectCount, scene.value().effects.size());
    for (uint32_t i = 0; i < info.effectCount; ++i)
        EXPECT_EQ(std::string(mfxEffectName(effects, i)), scene.value().effects[i].name);
    EXPECT_EQ(mfxEffectName(effects, info.effectCount), nullptr);
    EXPECT_EQ(info.smokeGrids, 1u);
    EXPECT_FLOAT_EQ(info.framesPerSecond, scene.value().output.fps);
    EXPECT_GT(info.frameCount, 10u);
    mfxDestroyEffects(effects);
    mfxDestroyEffects(nullptr); // allowed
    EXPECT_TRUE(deviceStillWorks(*host_));
}

// Effects the host did not destroy go with their runtime (the sanitizers' pass sees no leak).
TEST_F(RuntimeEffects, ARuntimeFreesTheEffectsLeftOnIt) {
    const MfxEffectsDesc desc = fromFile(std::string(MFX_SOURCE_DIR) + "/docs/scenes/smoke.json");
    MfxEffects first = nullptr, second = nullptr;
    ASSERT_EQ(mfxCreateEffects(runtime_, &desc, &first), MFX_SUCCESS);
    ASSERT_EQ(mfxCreateEffects(runtime_, &desc, &second), MFX_SUCCESS);
    mfxDestroyEffects(first);
    mfxDestroyRuntime(runtime_); // `second` goes with it
    runtime_ = nullptr;
    EXPECT_TRUE(deviceStillWorks(*host_));
}

TEST_F(RuntimeEffects, FromSceneJsonWithPathsAgainstTheBaseFolder) {
    const std::string assets = std::string(MFX_SOURCE_DIR) + "/../shared/assets";
    const MfxEffectsDesc desc = fromJson(
        R"({"character": {"source": "RiggedSimple.gltf"},
            "effects": [{"type": "speed_lines", "name": "lines"}]})",
        assets.c_str());
    MfxEffects effects = nullptr;
    ASSERT_EQ(mfxCreateEffects(runtime_, &desc, &effects), MFX_SUCCESS)
        << mfxRuntimeLastError(runtime_);
    EXPECT_STREQ(mfxEffectName(effects, 0), "lines");
    mfxDestroyEffects(effects);
    // Without the base folder the same text looks in the working folder, and says so.
    const std::string message = refusal(fromJson(json_), MFX_ERROR_SCENE);
    EXPECT_NE(message.find("RiggedSimple.gltf"), std::string::npos) << message;
}

TEST_F(RuntimeEffects, ABadSceneIsOneErrorNamingWhatAndWhere) {
    std::string message = refusal(
        fromJson(R"({"effects": [{"type": "speed_lines", "widht": 0.1}]})"), MFX_ERROR_SCENE);
    EXPECT_NE(message.find("(scene JSON)"), std::string::npos) << message;
    EXPECT_NE(message.find("widht"), std::string::npos) << message;
    EXPECT_EQ(lineCount(message), 1u) << message;

    message = refusal(fromJson("{\"effects\": [}"), MFX_ERROR_SCENE);
    EXPECT_NE(message.find("(scene JSON)"), std::string::npos) << message;

    const std::string missing = std::string(MFX_TEST_OUTPUT_DIR) + "/no_such_scene.json";
    message = refusal(fromFile(missing), MFX_ERROR_SCENE);
    EXPECT_NE(message.find("no_such_scene.json"), std::string::npos) << message;

    MfxEffectsDesc both = fromJson("{}");
    both.sceneFile = "scene.json";
    EXPECT_NE(refusal(both, MFX_ERROR_INVALID_ARGUMENT).find("exactly one"), std::string::npos);
    MfxEffectsDesc neither = fromJson("{}");
    neither.sceneJson = nullptr;
    EXPECT_NE(refusal(neither, MFX_ERROR_INVALID_ARGUMENT).find("exactly one"), std::string::npos);
    MfxEffectsDesc version = fromJson("{}");
    version.structVersion = 7;
    EXPECT_NE(refusal(version, MFX_ERROR_INVALID_ARGUMENT).find("structVersion"),
              std::string::npos);
    MfxEffects effects = nullptr;
    EXPECT_EQ(mfxCreateEffects(nullptr, &version, &effects), MFX_ERROR_INVALID_ARGUMENT);
    // The runtime still makes effects after all that.
    const MfxEffectsDesc good = fromJson(R"({"effects": [{"type": "speed_lines"}]})");
    ASSERT_EQ(mfxCreateEffects(runtime_, &good, &effects), MFX_SUCCESS)
        << mfxRuntimeLastError(runtime_);
    EXPECT_STREQ(mfxRuntimeLastError(runtime_), "");
    mfxDestroyEffects(effects);
}

} // namespace
} // namespace mfx::test
