// motionfx: one program, git-style subcommands (`motionfx info`, `motionfx render`, ...).
#include "apps/commands.h"
#include "core/gpu/check.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

void printUsage(std::FILE* out) {
    std::fprintf(out, "usage: motionfx <command> [options]\n\ncommands:\n");
    for (const mfx::app::Command& c : mfx::app::commands())
        std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
    std::fprintf(out, "\n'motionfx <command> --help' describes a command's options.\n");
}

} // namespace

int main(int argc, char** argv) {
    using namespace mfx::app;
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        printUsage(stderr);
        return kExitUsage;
    }
    if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        printUsage(stdout);
        return kExitOk;
    }
    for (const Command& command : commands()) {
        if (args[0] != command.name) continue;
        try {
            return runCommand(command, std::span<const std::string>(args).subspan(1));
        } catch (const mfx::gpu::VulkanError& e) {
            printError(std::string("Vulkan call failed: ") + e.what());
        } catch (const std::exception& e) {
            printError(e.what());
        }
        return kExitFailure;
    }
    printError("unknown command '" + args[0] + "' (see motionfx --help)");
    return kExitUsage;
}
