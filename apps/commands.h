// motionfx's subcommands. Each takes the words after its name and returns the exit status:
// 0 success, 1 failure at run time (no device, unwritable output), 2 bad usage.
#pragma once

#include "apps/cli.h"
#include "core/gpu/context.h"
#include "fluid/vdb_export.h"
#include "sim/scene_simulation.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <span>
#include <string>

namespace mfx::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// Options every GPU subcommand takes.
std::vector<cli::OptionSpec> deviceOptions();
gpu::ContextOptions contextOptions(const cli::ParsedArgs& args);

// The Context the options ask for, or nullptr after printing why there is none.
std::unique_ptr<gpu::Context> createContext(const cli::ParsedArgs& args);

// Opens `path` for writing when it is not empty; false (after printing why) when it cannot be.
bool openOutputFile(const std::string& path, std::ofstream& file);

// The scene a command was given as its first word, or the built-in default without one, with
// --size (else `defaultSize`, where given), --frames and --fps applied where the command has them,
// and its character loaded. On failure prints the one-line reason, sets `exitCode` (1, or 2 for a
// bad option value) and returns false. A .gltf/.glb file in place of a scene previews that
// character (scene::previewScene); --clip, where the command has it, picks the clip. The scene is
// fitted to its character (scene::fitScene), and what was chosen for the user (a scale, a limb) is
// printed on stdout.
struct SceneArgument {
    scene::Scene scene;
    scene::Cast cast; // one character per scene.characters entry
};
bool loadSceneArgument(const cli::ParsedArgs& parsed, SceneArgument& out, int& exitCode,
                       const char* defaultSize = nullptr);
// What loadSceneArgument reads once the options have been checked, without printing: the scene
// and its characters, or the error; `lines` (when not null) gets the notes it would print (the
// character's scaling, the choices fitScene made). A viewer reloads its scene through it.
Result<SceneArgument> readSceneArgument(const cli::ParsedArgs& parsed, const char* defaultSize,
                                        std::vector<std::string>* lines);
// The second half of readSceneArgument: `scene` (as read) with the command line's options
// applied, its characters loaded and fitted (a viewer's panel edits a scene without a file).
Result<SceneArgument> prepareSceneArgument(const cli::ParsedArgs& parsed, const char* defaultSize,
                                           scene::Scene scene, std::vector<std::string>* lines);

// The --character and --clip options of the commands that take a scene or a character file (they
// change the scene's first character).
std::vector<cli::OptionSpec> characterOptions();

// At the end of a run over `frames` frames: one line naming the effects that showed no motion
// (their vertices never move while they are live, or they are never live), if there are any.
void reportMotionlessEffects(const scene::Scene& scene, std::span<const anim::Character> cast,
                             uint32_t frames);

// For each sparse smoke grid of `stats` that first wanted more bricks than its budget this frame:
// its one line, "motionfx: warning: ..." on stderr (the simulation goes on at the budget).
void reportBudget(const sim::SimulationFrameStats& stats);

// False (after printing why) when the scene's output size exceeds the device's largest image.
bool checkOutputSize(const gpu::Context& ctx, const scene::Scene& scene);

// The scene's simulation after checkOutputSize, or nullptr after printing why there is none
// (`exitCode` set). `argument` must outlive it.
std::unique_ptr<sim::SceneSimulation>
createSceneSimulation(const gpu::Context& ctx, const SceneArgument& argument, int& exitCode);

// --vdb DIR and --vdb-up (render, simulate): each frame's smoke as OpenVDB files
// (fluid/vdb_export.h), DIR/<effect>_NNNN.vdb for each smoke grid, named after the first smoke
// effect that feeds it.
struct VdbOutput {
    bool on = false;
    std::string dir;
    fluid::VdbUp up = fluid::VdbUp::Y;
    uint32_t files = 0; // written so far
};
std::vector<cli::OptionSpec> vdbOptions();
// False (after printing why) for a bad --vdb-up, a DIR that cannot be made, or a build without
// OpenVDB.
bool readVdbOutput(const cli::ParsedArgs& parsed, VdbOutput& out);
// Reads the smoke grids' fields back (waits for the GPU) and writes frame `frame`'s files.
Status writeFrameVdbs(sim::SceneSimulation& sim, uint32_t frame, VdbOutput& out);

// motionfx bench solver --domain sparse (command_bench_sparse.cpp).
int runBenchSparse(const cli::ParsedArgs& parsed);

// One frame's simulation statistics as JSON ({"frame", "time", "passes", "fluid_bytes", ...}).
nlohmann::json statsJson(const sim::SimulationFrameStats& stats);

// The median of `values` (0 when empty); benchmarks quote medians.
double median(std::vector<double> values);

// Prints "motionfx: error: <message>" to stderr.
void printError(const std::string& message);

// --samples (MSAA samples per pixel): 1, 2, 4 or 8, default 4.
Result<uint32_t> parseSamples(const cli::ParsedArgs& parsed);
// Prints the first error among `results` (option values as parsed); true if there was one.
template <class... Results>
bool reportFirstError(const Results&... results) {
    const Error* first = nullptr;
    ((first = first ? first : (results.ok() ? nullptr : &results.error())), ...);
    if (first) printError(first->message);
    return first != nullptr;
}

// A subcommand's command line: its help (the usage line, a blank line, what it does), its options
// and how many positionals it takes. A command that uses the GPU has the device options
// (--device, --validate) first; one that takes a scene or character file has the character
// options (--character, --clip) last.
class CommandLine {
public:
    enum Takes : unsigned { kPlain = 0, kDevice = 1u << 0, kScene = 1u << 1 };
    CommandLine(std::string help, size_t maxPositional, unsigned takes);

    // One more option (before the character options); returns *this.
    CommandLine& option(std::string name, std::string valueName, std::string help);
    // --json FILE, "also write <what> as JSON".
    CommandLine& json(const std::string& what = "the results");
    // --samples N (MSAA samples per pixel, read by parseSamples).
    CommandLine& samples();

    // Parses `args`. False when the command ends here: after --help (printed; exitCode() 0) or a
    // bad argument (printed as one line; exitCode() 2).
    bool parse(std::span<const std::string> args);
    const cli::ParsedArgs& parsed() const { return parsed_; }
    int exitCode() const { return exitCode_; }

private:
    std::string help_;
    size_t maxPositional_;
    unsigned takes_;
    std::vector<cli::OptionSpec> options_;
    cli::ParsedArgs parsed_;
    int exitCode_ = kExitOk;
};

// One subcommand: its name and one-line summary (motionfx --help), its command line (its help and
// options) and its entry point (command_<name>.cpp), which gets the words after its name parsed.
// A group ("bench") has a table of sub-commands instead, `members` naming them in its help.
struct Command {
    const char* name;
    const char* summary;
    CommandLine (*line)() = nullptr;
    int (*run)(const cli::ParsedArgs& args) = nullptr;
    std::span<const Command> (*group)() = nullptr;
    const char* members = nullptr;
};

// The subcommands (apps/command_lines.cpp: the program's whole command-line surface).
std::span<const Command> commands();

// Runs `command` on `args`, the words after its name: --help and a bad argument are answered here
// (exit status 0, and 2 after one line), a group passes the rest on to the sub-command named.
int runCommand(const Command& command, std::span<const std::string> args);

// Each subcommand's entry point (command_<name>.cpp), with the signature of Command::run.
using CommandMain = int(const cli::ParsedArgs& args);
CommandMain runInfo, runRender, runBake, runCompare, runBenchSolver, runBenchTrajectory,
    runBenchFrame, runBenchEffects, runBenchAccuracy, runInspect, runExportFighter, runScene,
    runSimulate, runView;

// The solver scenarios' and stages' names, comma-separated (for help and errors).
std::string scenarioNameList();
std::string stageNameList();
// The viewer's keys, for its help and its start-up line.
extern const char* const kViewKeysHelp;

// createContext, for a command that times the GPU: nullptr (after printing why) on a device
// without timestamp queries, `what` naming what cannot be timed ("the solver").
std::unique_ptr<gpu::Context> createTimingContext(const cli::ParsedArgs& args, const char* what);

// After a run with --validate: reports recorded validation errors; returns kExitFailure if any.
int finishValidation(const gpu::Context& ctx, int exitCode);

} // namespace mfx::app
