#include "apps/view_panel.h"

#ifdef MFX_HAVE_IMGUI

#include "apps/view_panel_keys.h"
#include "core/gpu/check.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/gpu/swapchain.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

namespace mfx::app {

namespace {

constexpr float kPanelWidth = 400.0f;

void checkVk(VkResult result) {
    if (result != VK_SUCCESS) std::fprintf(stderr, "motionfx: panel: Vulkan error %d\n", result);
}

double passMs(const sim::SimulationFrameStats& stats, const std::string& prefix) {
    double ms = 0.0;
    for (const auto& pass : stats.passes)
        if (pass.name.rfind(prefix, 0) == 0) ms += pass.gpuMs;
    return ms;
}

} // namespace

Result<std::unique_ptr<ViewPanel>> ViewPanel::create(const gpu::Context& ctx, GLFWwindow* window,
                                                     const gpu::Swapchain& swapchain) {
    std::unique_ptr<ViewPanel> panel(new ViewPanel(ctx));
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.95f;
    if (!ImGui_ImplGlfw_InitForVulkan(window, true)) {
        ImGui::DestroyContext();
        return Error{"the panel: ImGui's GLFW backend did not start"};
    }
    panel->backendsUp_ = true;

    VkAttachmentDescription colour{};
    colour.format = swapchain.format();
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    dependency.dstAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &colour;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dependency;
    MFX_VK_CHECK(vkCreateRenderPass(ctx.device(), &info, nullptr, &panel->renderPass_));

    VkDescriptorPoolSize sizes{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 4;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &sizes;
    MFX_VK_CHECK(vkCreateDescriptorPool(ctx.device(), &pool, nullptr, &panel->descriptors_));

    ImGui_ImplVulkan_InitInfo init{};
    init.Instance = ctx.instance();
    init.PhysicalDevice = ctx.physicalDevice();
    init.Device = ctx.device();
    init.QueueFamily = ctx.graphicsQueue().family;
    init.Queue = ctx.graphicsQueue().queue;
    init.DescriptorPool = panel->descriptors_;
    init.Subpass = 0;
    init.MinImageCount = std::max(2u, swapchain.imageCount());
    init.ImageCount = std::max(2u, swapchain.imageCount());
    init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    init.CheckVkResultFn = checkVk;
    if (!ImGui_ImplVulkan_Init(&init, panel->renderPass_))
        return Error{"the panel: ImGui's Vulkan backend did not start"};
    panel->vulkanUp_ = true;

    gpu::CommandBuffer upload = gpu::CommandBuffer::create(ctx, ctx.graphicsQueue());
    VkCommandBuffer cmd = upload.begin();
    ImGui_ImplVulkan_CreateFontsTexture(cmd);
    upload.end();
    upload.submit();
    upload.wait();
    ImGui_ImplVulkan_DestroyFontUploadObjects();

    panel->makeFramebuffers(swapchain);
    return panel;
}

ViewPanel::~ViewPanel() {
    vkDeviceWaitIdle(ctx_.device());
    if (vulkanUp_) ImGui_ImplVulkan_Shutdown();
    if (backendsUp_) {
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    destroyFramebuffers();
    if (descriptors_) vkDestroyDescriptorPool(ctx_.device(), descriptors_, nullptr);
    if (renderPass_) vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
}

void ViewPanel::makeFramebuffers(const gpu::Swapchain& swapchain) {
    extent_ = swapchain.extent();
    for (uint32_t i = 0; i < swapchain.imageCount(); ++i) {
        const VkImageView view = swapchain.view(i);
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = renderPass_;
        info.attachmentCount = 1;
        info.pAttachments = &view;
        info.width = extent_.width;
        info.height = extent_.height;
        info.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        MFX_VK_CHECK(vkCreateFramebuffer(ctx_.device(), &info, nullptr, &framebuffer));
        framebuffers_.push_back(framebuffer);
    }
}

void ViewPanel::destroyFramebuffers() {
    for (VkFramebuffer f : framebuffers_)
        vkDestroyFramebuffer(ctx_.device(), f, nullptr);
    framebuffers_.clear();
}

void ViewPanel::resize(const gpu::Swapchain& swapchain) {
    vkDeviceWaitIdle(ctx_.device());
    destroyFramebuffers();
    ImGui_ImplVulkan_SetMinImageCount(std::max(2u, swapchain.imageCount()));
    makeFramebuffers(swapchain);
}

bool ViewPanel::wantsMouse() const {
    return visible_ && ImGui::GetIO().WantCaptureMouse;
}
bool ViewPanel::typing() const {
    return visible_ && ImGui::GetIO().WantTextInput;
}

PanelRequests ViewPanel::build(const PanelView& view) {
    PanelRequests out;
    built_ = false;
    if (!visible_) return out;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const ImGuiIO& io = ImGui::GetIO();
    const float width = std::min(kPanelWidth, io.DisplaySize.x);
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - width, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("motionfx", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-150.0f);

    // The file.
    scene::SceneDocument* doc = view.document;
    ImGui::TextWrapped("%s", doc ? doc->where().c_str() : "(no scene document: a preview)");
    if (doc) {
        if (ImGui::Button("Save")) out.save = true;
        ImGui::SameLine();
        ImGui::SetNextItemWidth(-70.0f);
        const bool enter =
            ImGui::InputTextWithHint("##saveas", "another file.json", saveAs_, sizeof saveAs_,
                                     ImGuiInputTextFlags_EnterReturnsTrue);
        ImGui::SameLine();
        if ((ImGui::Button("Save as") || enter) && saveAs_[0]) out.saveAs = saveAs_;
    }
    if (!view.message.empty()) ImGui::TextWrapped("%s", view.message.c_str());

    // The timeline.
    if (ImGui::Button(view.paused ? "Play" : "Pause")) out.togglePause = true;
    ImGui::SameLine();
    int frame = view.frame + 1;
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::SliderInt("##frame", &frame, 1, int(view.frameCount), "frame %d"))
        out.seek = uint32_t(frame - 1);

    // The effects: show/hide, and the selected one's keys.
    selected_ = std::clamp(selected_, 0, std::max(0, int(view.effects.size()) - 1));
    if (ImGui::CollapsingHeader("Effects", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t e = 0; e < view.effects.size(); ++e) {
            ImGui::PushID(int(e));
            bool shown = e < view.shown.size() && view.shown[e];
            if (ImGui::Checkbox("##shown", &shown)) out.show.emplace_back(e, shown);
            ImGui::SameLine();
            if (ImGui::Selectable(view.effects[e].c_str(), int(e) == selected_)) selected_ = int(e);
            ImGui::PopID();
        }
        // The document and the scene playing list the same effects, unless a reload of the file
        // was read by one and not the other: then the document's keys are not offered.
        const auto found = doc ? doc->document().find("effects") : nlohmann::json::const_iterator();
        const nlohmann::json* effects = doc && found != doc->document().end() ? &*found : nullptr;
        if (effects && effects->is_array() && size_t(selected_) < effects->size() &&
            effects->size() == view.effects.size()) {
            const std::string section = "effects[" + std::to_string(selected_) + "]";
            const std::string type = (*effects)[size_t(selected_)].value("type", std::string());
            ImGui::Separator();
            ImGui::TextUnformatted(type.c_str());
            if (type == "smoke" && view.history && !view.history->empty())
                ImGui::Text("solver step: %.2f ms GPU (this frame's smoke passes)",
                            passMs(view.history->back(), "smoke"));
            editSection(*doc, section, out);
        }
    }
    if (doc)
        for (const std::string& name : scene::sceneSections()) {
            // A scene of several characters lists them as "characters": one section each.
            const bool cast = name == "character" && doc->document().contains("characters");
            const std::string list = cast ? "characters" : name;
            const bool many = name == "lights" || cast;
            const size_t count =
                many && doc->document().contains(list) && doc->document()[list].is_array()
                    ? doc->document()[list].size()
                    : 1;
            for (size_t i = 0; i < count; ++i) {
                const std::string section = many ? list + "[" + std::to_string(i) + "]" : name;
                if (ImGui::CollapsingHeader(section.c_str())) editSection(*doc, section, out);
            }
        }

    // The passes' GPU milliseconds over the last frames.
    if (view.history && !view.history->empty() &&
        ImGui::CollapsingHeader("GPU time", ImGuiTreeNodeFlags_DefaultOpen)) {
        std::vector<float> whole;
        std::map<std::string, std::vector<float>> passes;
        std::vector<std::string> order;
        for (const sim::SimulationFrameStats& stats : *view.history) {
            whole.push_back(float(passMs(stats, "")));
            for (const auto& pass : stats.passes) {
                if (!passes.count(pass.name)) order.push_back(pass.name);
                passes[pass.name].push_back(float(pass.gpuMs));
            }
        }
        const float top = *std::max_element(whole.begin(), whole.end());
        char caption[64];
        std::snprintf(caption, sizeof caption, "frame %.2f ms", double(whole.back()));
        ImGui::PlotLines("##whole", whole.data(), int(whole.size()), 0, caption, 0.0f,
                         std::max(top, 1e-3f), ImVec2(-1.0f, 60.0f));
        if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingStretchProp)) {
            for (const std::string& name : order) {
                const std::vector<float>& ms = passes[name];
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(name.c_str());
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", double(ms.back()));
                ImGui::TableNextColumn();
                ImGui::PushID(name.c_str());
                ImGui::PlotLines("##p", ms.data(), int(ms.size()), 0, nullptr, 0.0f,
                                 std::max(top, 1e-3f), ImVec2(-1.0f, 14.0f));
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
    }
    ImGui::PopItemWidth();
    ImGui::End();
    ImGui::Render();
    built_ = true;
    return out;
}

void ViewPanel::record(VkCommandBuffer cmd, uint32_t index) {
    if (!visible_ || !built_ || index >= framebuffers_.size()) return;
    built_ = false;
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = renderPass_;
    begin.framebuffer = framebuffers_[index];
    begin.renderArea = {{0, 0}, extent_};
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

} // namespace mfx::app

#else

namespace mfx::app {

// Without Dear ImGui: no panel (create says why; the rest is never reached).
Result<std::unique_ptr<ViewPanel>> ViewPanel::create(const gpu::Context&, GLFWwindow*,
                                                     const gpu::Swapchain&) {
    return Error{"this build has no Dear ImGui (install libimgui-dev, or run ./build.sh, and "
                 "build again)"};
}
ViewPanel::~ViewPanel() = default;
void ViewPanel::resize(const gpu::Swapchain&) {}
PanelRequests ViewPanel::build(const PanelView&) {
    return {};
}
void ViewPanel::record(VkCommandBuffer, uint32_t) {}
bool ViewPanel::wantsMouse() const {
    return false;
}
bool ViewPanel::typing() const {
    return false;
}

} // namespace mfx::app

#endif
