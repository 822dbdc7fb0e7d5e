#include "apps/commands.h"

#include "core/scene/scene_fit.h"
#include "fluid/body_solids.h"
#include "render/image_output.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

namespace mfx::app {

std::vector<cli::OptionSpec> deviceOptions() {
    return {
        {"device", "NAME",
         std::string("use the Vulkan device whose name contains NAME (default: $") +
             gpu::kDeviceEnvironmentVariable + ", else a GPU, else lavapipe)"},
        {"validate", "", "enable the Vulkan validation layer; validation errors fail the run"},
    };
}

gpu::ContextOptions contextOptions(const cli::ParsedArgs& args) {
    gpu::ContextOptions options;
    options.deviceName = args.value("device");
    options.validation = args.has("validate");
    return options;
}

std::unique_ptr<gpu::Context> createContext(const cli::ParsedArgs& args) {
    auto created = gpu::Context::create(contextOptions(args));
    if (!created) {
        printError(created.error().message);
        return nullptr;
    }
    return std::move(created).value();
}

bool openOutputFile(const std::string& path, std::ofstream& file) {
    if (path.empty()) return true;
    file.open(path);
    if (file) return true;
    printError("cannot write " + path);
    return false;
}

bool loadSceneArgument(const cli::ParsedArgs& parsed, SceneArgument& out, int& exitCode,
                       const char* defaultSize) {
    // The options first: their errors are the command line's (exit status 2).
    for (const char* name : {"character", "clip"})
        if (parsed.has(name) && parsed.value(name).empty()) {
            printError(std::string(name) == "character"
                           ? "--character needs a .gltf/.glb file or \"fighter\""
                           : "--clip needs a clip name");
            exitCode = kExitUsage;
            return false;
        }
    const Result<std::pair<uint32_t, uint32_t>> size =
        cli::parseSize(parsed.value("size", defaultSize ? defaultSize : "1x1"), 16384);
    const Result<uint32_t> frames =
        cli::parseUnsigned(parsed.value("frames", "1"), 1, 100000, "--frames");
    const Result<double> fps = cli::parseNumber(parsed.value("fps", "30"), 1.0, 240.0, "--fps");
    if (reportFirstError(size, frames, fps)) {
        exitCode = kExitUsage;
        return false;
    }
    std::vector<std::string> lines;
    Result<SceneArgument> read = readSceneArgument(parsed, defaultSize, &lines);
    if (!read) {
        printError(read.error().message);
        exitCode = kExitFailure;
        return false;
    }
    out = std::move(read).value();
    for (const std::string& line : lines)
        std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    return true;
}

Result<SceneArgument> readSceneArgument(const cli::ParsedArgs& parsed, const char* defaultSize,
                                        std::vector<std::string>* lines) {
    const bool preview = !parsed.positional.empty() && scene::isCharacterFile(parsed.positional[0]);
    Result<scene::Scene> loaded =
        parsed.positional.empty() ? Result<scene::Scene>(scene::defaultScene())
        : preview                 ? Result<scene::Scene>(scene::previewScene(parsed.positional[0]))
                                  : scene::loadScene(parsed.positional[0]);
    if (!loaded) return loaded.error();
    return prepareSceneArgument(parsed, defaultSize, std::move(loaded).value(), lines);
}

Result<SceneArgument> prepareSceneArgument(const cli::ParsedArgs& parsed, const char* defaultSize,
                                           scene::Scene scene, std::vector<std::string>* lines) {
    const bool preview = !parsed.positional.empty() && scene::isCharacterFile(parsed.positional[0]);
    SceneArgument out;
    out.scene = std::move(scene);
    if (parsed.has("character") && !parsed.value("character").empty()) {
        const std::string file = parsed.value("character");
        // Relative to where the command runs, not to the scene file.
        out.scene.characters.front().source =
            file == "fighter" ? file : std::filesystem::absolute(file).string();
        if (!parsed.has("clip")) out.scene.characters.front().clip.clear();
    }
    if (parsed.has("clip") && !parsed.value("clip").empty())
        out.scene.characters.front().clip = parsed.value("clip");
    // --size, --frames and --fps, where given (and the command has them), over the scene's (the
    // values are checked by loadSceneArgument; one that does not parse is not applied).
    scene::OutputSpec& output = out.scene.output;
    if (parsed.has("size") || defaultSize) {
        if (auto size =
                cli::parseSize(parsed.value("size", defaultSize ? defaultSize : ""), 16384)) {
            output.width = size.value().first;
            output.height = size.value().second;
        }
    }
    if (parsed.has("frames"))
        if (auto frames = cli::parseUnsigned(parsed.value("frames"), 1, 100000, "--frames"))
            output.frames = frames.value();
    if (parsed.has("fps"))
        if (auto fps = cli::parseNumber(parsed.value("fps"), 1.0, 240.0, "--fps"))
            output.fps = float(fps.value());
    std::vector<std::string> scaleNotes;
    Result<scene::Cast> cast = scene::loadCast(out.scene, &scaleNotes);
    if (!cast) return cast.error();
    out.cast = std::move(cast).value();
    std::vector<std::string> notes;
    if (Status fitted = scene::fitScene(out.scene, out.cast, &notes); !fitted)
        return fitted.error();
    if (!lines) return out;
    lines->insert(lines->end(), scaleNotes.begin(), scaleNotes.end());
    if (preview) {
        // One line: the clip, the size and the bones the preview's effects were bound to.
        const anim::Clip& clip = scene::sceneClip(out.scene.characters.front(), out.cast.front());
        std::string bones = notes.empty() ? std::string() : notes.front();
        const size_t bound = bones.find("\": ");
        if (bound != std::string::npos) bones = bones.substr(bound + 3);
        char text[512];
        std::snprintf(text, sizeof text,
                      "preview of %s: clip \"%s\" (%.3g s), %.2f m tall; effects ",
                      parsed.positional[0].c_str(), clip.name.c_str(), double(clip.duration),
                      double(scene::characterHeight(out.scene, 0, out.cast.front())));
        lines->push_back(text + bones);
    } else {
        lines->insert(lines->end(), notes.begin(), notes.end());
    }
    return out;
}

std::vector<cli::OptionSpec> characterOptions() {
    return {{"character", "FILE",
             "put this character (a .gltf/.glb file, or \"fighter\") in the scene instead of "
             "its (first) own, playing its first clip unless --clip names one"},
            {"clip", "NAME",
             "play the (first) character's clip NAME (default: the scene's, else the "
             "first)"}};
}

std::vector<cli::OptionSpec> vdbOptions() {
    return {{"vdb", "DIR",
             "also write each frame's smoke as OpenVDB files, DIR/<effect>_NNNN.vdb: grids "
             "density, colour and velocity in world units (metres)"},
            {"vdb-up", "y|z",
             "the .vdb files' up axis: y, the scene's own (default), or z, as Blender's glTF "
             "import turns the character"}};
}

bool readVdbOutput(const cli::ParsedArgs& parsed, VdbOutput& out) {
    const std::string up = parsed.value("vdb-up", "y");
    if (up != "y" && up != "z") {
        printError("--vdb-up must be y or z, not \"" + up + "\"");
        return false;
    }
    out.up = up == "z" ? fluid::VdbUp::Z : fluid::VdbUp::Y;
    if (!parsed.has("vdb")) return true;
    out.on = true;
    out.dir = parsed.value("vdb");
    if (!fluid::vdbAvailable()) {
        printError(fluid::writeVdb(out.dir, {}).error().message);
        return false;
    }
    if (Status dir = render::ensureOutputDirectory(out.dir); !dir) {
        printError(dir.error().message);
        return false;
    }
    return true;
}

Status writeFrameVdbs(sim::SceneSimulation& sim, uint32_t frame, VdbOutput& out) {
    if (!out.on) return Ok{};
    for (sim::SceneSimulation::SmokeGrid& g : sim.smokeGrids()) {
        std::string name = g.grid.name();
        if (!g.effects.empty()) {
            // The effect's name, with what a file name should not hold made '_'.
            name = sim.scene().effects[sim.effectIndex(sim.trajectories()[g.effects.front()])].name;
            for (char& c : name)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
            if (name.empty()) name = g.grid.name();
        }
        const fluid::FieldState state = g.grid.state();
        const std::vector<uint8_t> stored =
            g.grid.sparse() ? g.grid.storedCells() : std::vector<uint8_t>{};
        std::vector<uint8_t> solid = g.lastSolids.empty()
                                         ? std::vector<uint8_t>{}
                                         : fluid::solidCellMask(state.grid, g.lastSolids);
        // On the sparse domain only stored cells are solid (what is not stored is air).
        if (!stored.empty())
            for (size_t cell = 0; cell < solid.size(); ++cell)
                solid[cell] &= stored[cell];
        fluid::VdbFrame vdb;
        vdb.state = &state;
        vdb.storedCells = stored.empty() ? nullptr : &stored;
        vdb.solidCells = solid.empty() ? nullptr : &solid;
        vdb.origin = g.grid.origin();
        vdb.up = out.up;
        char file[32];
        std::snprintf(file, sizeof file, "_%04u.vdb", frame);
        if (Status written = fluid::writeVdb(out.dir + "/" + name + file, vdb); !written)
            return written;
        ++out.files;
    }
    return Ok{};
}

void reportBudget(const sim::SimulationFrameStats& stats) {
    for (const sim::GridFrameState& g : stats.grids)
        if (!g.budgetLine.empty())
            std::fprintf(stderr, "motionfx: warning: frame %u: %s\n", stats.frame,
                         g.budgetLine.c_str());
}

void reportMotionlessEffects(const scene::Scene& scene, std::span<const anim::Character> cast,
                             uint32_t frames) {
    const std::vector<std::string> still = scene::motionlessEffects(scene, cast, frames);
    if (still.empty()) return;
    std::string list;
    for (const std::string& s : still)
        list += (list.empty() ? "" : "; ") + s;
    std::printf("note: %s no motion to draw: %s\n",
                still.size() == 1 ? "one effect had"
                                  : (std::to_string(still.size()) + " effects had").c_str(),
                list.c_str());
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

bool checkOutputSize(const gpu::Context& ctx, const scene::Scene& scene) {
    const uint32_t largest = ctx.limits().maxImageDimension2D;
    if (scene.output.width <= largest && scene.output.height <= largest) return true;
    printError("size " + std::to_string(scene.output.width) + "x" +
               std::to_string(scene.output.height) + " exceeds " + ctx.info().name +
               "'s largest image, " + std::to_string(largest));
    return false;
}

std::unique_ptr<sim::SceneSimulation>
createSceneSimulation(const gpu::Context& ctx, const SceneArgument& argument, int& exitCode) {
    if (!checkOutputSize(ctx, argument.scene)) {
        exitCode = kExitUsage;
        return nullptr;
    }
    auto created = sim::SceneSimulation::create(ctx, argument.scene, argument.cast);
    if (!created) {
        printError(created.error().message);
        exitCode = kExitFailure;
        return nullptr;
    }
    return std::move(created).value();
}

void printError(const std::string& message) {
    std::fprintf(stderr, "motionfx: error: %s\n", message.c_str());
}

CommandLine::CommandLine(std::string help, size_t maxPositional, unsigned takes)
    : help_(std::move(help)), maxPositional_(maxPositional), takes_(takes) {
    if (takes_ & kDevice) options_ = deviceOptions();
}

CommandLine& CommandLine::option(std::string name, std::string valueName, std::string help) {
    options_.push_back({std::move(name), std::move(valueName), std::move(help)});
    return *this;
}

CommandLine& CommandLine::json(const std::string& what) {
    return option("json", "FILE", "also write " + what + " as JSON");
}

CommandLine& CommandLine::samples() {
    return option("samples", "N",
                  "MSAA samples per pixel: 1, 2, 4 or 8 (default 4; fewer where the device has "
                  "fewer)");
}

bool CommandLine::parse(std::span<const std::string> args) {
    std::vector<cli::OptionSpec> options = options_;
    if (takes_ & kScene)
        for (const cli::OptionSpec& o : characterOptions())
            options.push_back(o);
    Result<cli::ParsedArgs> result = cli::parseArgs(args, options, maxPositional_);
    if (!result) {
        printError(result.error().message + " (see --help)");
        exitCode_ = kExitUsage;
        return false;
    }
    parsed_ = std::move(result).value();
    if (parsed_.has("help")) {
        std::printf("%s\n%s", help_.c_str(), cli::describeOptions(options).c_str());
        exitCode_ = kExitOk;
        return false;
    }
    return true;
}

int runCommand(const Command& command, std::span<const std::string> args) {
    if (!command.group) {
        CommandLine line = command.line();
        if (!line.parse(args)) return line.exitCode();
        return command.run(line.parsed());
    }
    std::string names, list;
    for (const Command& member : command.group()) {
        names += (names.empty() ? "" : "|") + std::string(member.name);
        list += (list.empty() ? "" : ", ") + std::string(member.name);
    }
    if (args.empty() || args[0] == "--help") {
        std::printf("usage: motionfx %s %s [options]   (see --help of each)\n\n%s:\n", command.name,
                    names.c_str(), command.members);
        for (const Command& member : command.group())
            std::printf("  %-12s %s\n", member.name, member.summary);
        return args.empty() ? kExitUsage : kExitOk;
    }
    for (const Command& member : command.group())
        if (args[0] == member.name) return runCommand(member, args.subspan(1));
    std::string one = command.members;
    one.pop_back(); // "benchmarks" -> "benchmark"
    printError("unknown " + one + " '" + args[0] + "'; " + command.members + " are: " + list);
    return kExitUsage;
}

std::unique_ptr<gpu::Context> createTimingContext(const cli::ParsedArgs& args, const char* what) {
    std::unique_ptr<gpu::Context> context = createContext(args);
    if (context && !context->features().timestamps) {
        printError(context->info().name + " has no timestamp queries; " + what +
                   " cannot be timed");
        return nullptr;
    }
    return context;
}

Result<uint32_t> parseSamples(const cli::ParsedArgs& parsed) {
    Result<uint32_t> samples = cli::parseUnsigned(parsed.value("samples", "4"), 1, 8, "--samples");
    if (samples && (samples.value() & (samples.value() - 1)) != 0)
        return Error{"--samples: expected 1, 2, 4 or 8, got " + parsed.value("samples")};
    return samples;
}

int finishValidation(const gpu::Context& ctx, int exitCode) {
    if (!ctx.validationEnabled()) return exitCode;
    const size_t errors = ctx.validationErrorCount();
    if (errors == 0) return exitCode;
    printError(std::to_string(errors) + " Vulkan validation error(s) were reported (above)");
    return kExitFailure;
}

} // namespace mfx::app
