// motionfx render: renders headless and writes PNG. For now the lit test scene.
#include "apps/commands.h"

#include "core/gpu/commands.h"
#include "core/gpu/timer.h"
#include "render/image_output.h"
#include "render/render_target.h"
#include "render/test_scene_pass.h"

#include <cstdio>

namespace mfx::app {

int runRender(std::span<const std::string> args) {
    std::vector<cli::OptionSpec> options = deviceOptions();
    options.push_back({"out", "DIR", "write the PNG into DIR (default: out)"});
    options.push_back({"size", "WxH", "image size in pixels (default: 1280x720)"});
    cli::ParsedArgs parsed;
    int exitCode = kExitOk;
    if (!parseOrExit(args, options, 0,
                     "usage: motionfx render [options]\n\nRenders the lit test scene headless "
                     "and writes DIR/test_scene.png.",
                     parsed, exitCode))
        return exitCode;

    auto size = cli::parseSize(parsed.value("size", "1280x720"), 16384);
    if (!size) {
        printError(size.error().message);
        return kExitUsage;
    }
    const auto [width, height] = size.value();
    const std::string outDir = parsed.value("out", "out");
    // Check the output before the (slower) GPU work, so a typo fails at once.
    if (Status dir = render::ensureOutputDirectory(outDir); !dir) {
        printError(dir.error().message);
        return kExitFailure;
    }

    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    if (width > ctx.limits().maxImageDimension2D || height > ctx.limits().maxImageDimension2D) {
        printError("size " + std::to_string(width) + "x" + std::to_string(height) + " exceeds " +
                   ctx.info().name + "'s largest image, " +
                   std::to_string(ctx.limits().maxImageDimension2D));
        return kExitUsage;
    }

    render::RenderTarget target = render::createRenderTarget(ctx, width, height);
    render::TestScenePass scene(ctx);
    gpu::GpuTimer timer(ctx, 4);
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        gpu::ScopedPass pass(timer, cmd, "test_scene");
        scene.record(cmd, target, render::TestSceneView::standard());
    });
    const std::vector<uint8_t> rgba = render::readColor(ctx, target);
    const std::string path = outDir + "/test_scene.png";
    if (Status written = render::writePng(path, width, height, rgba); !written) {
        printError(written.error().message);
        return kExitFailure;
    }
    std::printf("wrote %s (%ux%u) on %s", path.c_str(), width, height, ctx.info().name.c_str());
    for (const gpu::PassTime& t : timer.results())
        std::printf(", %s pass %.2f ms GPU", t.name.c_str(), t.milliseconds);
    std::printf("\n");
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
