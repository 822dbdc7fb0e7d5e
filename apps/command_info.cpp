// motionfx info: the chosen device, its driver and the capabilities the project relies on.
#include "apps/commands.h"

#include <cstdio>

namespace mfx::app {

int runInfo(const cli::ParsedArgs& parsed) {

    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const gpu::DeviceInfo& info = ctx.info();
    const gpu::DeviceFeatures& f = ctx.features();
    auto yes = [](bool b) { return b ? "yes" : "no"; };

    std::printf("device                          %s\n", info.name.c_str());
    std::printf("type                            %s\n", gpu::toString(info.type));
    std::printf("CPU implementation              %s\n", yes(info.isCpu()));
    std::printf("driver                          %s (%s)\n", info.driverName.c_str(),
                info.driverInfo.c_str());
    std::printf("Vulkan version                  %s\n",
                gpu::versionString(info.apiVersion).c_str());
    std::printf("features\n");
    std::printf("  geometryShader                %s\n", yes(f.geometryShader));
    std::printf("  transformFeedback             %s\n", yes(f.transformFeedback));
    std::printf("  geometryStreams               %s\n", yes(f.geometryStreams));
    std::printf("  shaderFloat16                 %s\n", yes(f.shaderFloat16));
    std::printf("  storageBuffer16BitAccess      %s\n", yes(f.storageBuffer16BitAccess));
    std::printf("  bufferFloat32AtomicAdd        %s\n", yes(f.bufferFloat32AtomicAdd));
    std::printf("  imageFloat32AtomicAdd         %s\n", yes(f.imageFloat32AtomicAdd));
    std::printf("  timestamps                    %s\n", yes(f.timestamps));
    std::printf("limits\n");
    std::printf("  maxComputeWorkGroupInvocations %u\n",
                ctx.limits().maxComputeWorkGroupInvocations);
    std::printf("  maxImageDimension3D           %u\n", ctx.limits().maxImageDimension3D);
    std::printf("  timestampPeriod               %g ns\n", double(ctx.limits().timestampPeriod));
    std::printf("validation                      %s\n", ctx.validationEnabled() ? "on" : "off");
    if (parsed.has("list")) {
        std::printf("all devices\n");
        for (const gpu::DeviceInfo& d : ctx.listDevices())
            std::printf("  %s (%s, Vulkan %s)\n", d.name.c_str(), gpu::toString(d.type),
                        gpu::versionString(d.apiVersion).c_str());
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
