// The program's whole command-line surface in one place: each subcommand's help (its usage line
// and what it does) and its options. The subcommands (command_<name>.cpp) parse their words with
// these; README.md "The program" describes the same.
#include "apps/commands.h"
#include "fluid/scenarios.h"
#include "fluid/solver_options.h"

#include <string>

namespace mfx::app {

namespace {

std::string workgroupLabel(const std::array<uint32_t, 3>& s) {
    return std::to_string(s[0]) + "x" + std::to_string(s[1]) + "x" + std::to_string(s[2]);
}

} // namespace

std::string scenarioNameList() {
    std::string list;
    for (const char* name : fluid::scenarioNames())
        list += (list.empty() ? "" : ", ") + std::string(name);
    return list;
}

std::string stageNameList() {
    std::string list;
    for (fluid::Stage stage : fluid::allStages())
        list += (list.empty() ? "" : ", ") + std::string(fluid::stageName(stage));
    return list;
}

const char* const kViewKeysHelp =
    "keys: space play/pause; right/left (or . and ,) one frame forward/back; page down/up ten "
    "frames forward/back; home or r restart; 1-9 show/hide the scene's effects by their order; "
    "left drag orbits the camera, middle or shift + left drag pans it, the wheel zooms; f frames "
    "the character, c goes back to the scene's camera, p prints the camera as a scene \"camera\" "
    "block; tab shows/hides the parameter panel; s writes a screenshot (to the --screenshot file, "
    "else motionfx_view.png); escape or q "
    "quit. The scene file (and the character file it names) is watched: a "
    "saved change plays at once, from the frame shown";

namespace {

CommandLine infoCommandLine() {
    CommandLine command("usage: motionfx info [options]\n\nPrints the Vulkan device motionfx "
                        "would use, its driver, and the features and limits the project relies on.",
                        0, CommandLine::kDevice);
    command.option("list", "", "also list every Vulkan device found");
    return command;
}

CommandLine renderCommandLine() {
    CommandLine command(
        "usage: motionfx render [SCENE | CHARACTER.glb] [options]\n\nRenders a "
        "scene file (JSON; README.md \"Scene files\"), or a .gltf/.glb character "
        "with the default effects on its fastest limb, framed, or without either the "
        "built-in default scene headless into DIR/frame_0000.png, frame_0001.png, ... "
        "and, when ffmpeg is installed, DIR/scene.mp4 (H.264, yuv420p: it plays in "
        "browsers). With --layers each frame also comes as DIR/character_NNNN.png (drawn "
        "without its effects) and DIR/effects_NNNN.png: the effects alone, RGBA with "
        "premultiplied colour, which laid over the character frame (rgb + (1 - a) * "
        "under) gives the full frame.",
        1, CommandLine::kDevice | CommandLine::kScene);
    command.option("out", "DIR", "write the frames into DIR (default: out)")
        .option("frames", "N", "render the first N frames (default: the scene's)")
        .option("size", "WxH", "image size in pixels (default: the scene's, 1280x720)")
        .option("fps", "N",
                "frames per second of the simulation, the frames and the video, 1 to 240 "
                "(default: the scene's, 30)")
        .option("stats", "FILE", "write per-frame statistics as JSON")
        .option("layers", "",
                "also write each frame without its effects and the effects alone "
                "(premultiplied RGBA)");
    for (const cli::OptionSpec& o : vdbOptions())
        command.option(o.name, o.valueName, o.help);
    return command;
}

CommandLine bakeCommandLine() {
    CommandLine command(
        "usage: motionfx bake [SCENE | CHARACTER.glb] [options]\n\nBakes a scene's effects "
        "(default: the built-in scene's) into flipbook sheets for game engines (docs/flipbook.md): "
        "DIR/colour.png, the effects alone frame after frame in a grid of cells (premultiplied "
        "RGBA; the character left out or kept as a holdout), DIR/motion.png, each cell's motion "
        "toward the next as motion vectors for smooth blending, and DIR/flipbook.json, the "
        "layout, timing, encodings and camera. The frames are sampled evenly from the scene's "
        "clip (or --range) into the cells, drawn through a camera framed on what the effects "
        "draw (or the scene's).",
        1, CommandLine::kDevice | CommandLine::kScene);
    command.option("out", "DIR", "write the sheets into DIR (default: bake)")
        .option("grid", "CxR", "columns and rows of cells, each 1 to 64 (default 8x8)")
        .option("cell", "N|WxH",
                "a cell's size in pixels, at least 8, the sheet at most 16384 a side "
                "(default 256)")
        .option("range", "FIRST:LAST", "bake scene frames FIRST to LAST (default: all)")
        .option("fps", "N",
                "frames per second of the simulation, 1 to 240 (default: the scene's); more "
                "frames to sample from")
        .option("effects", "LIST", "bake the effects of these names (comma-separated; default all)")
        .option("holdout", "", "keep the character as a holdout: it hides the effects behind it")
        .option("camera", "effect|scene",
                "frame the cells on what the effects draw (default), or use the scene's camera")
        .option("margin", "F",
                "share of a cell kept empty on each side when framed on the effects, 0 to 0.4 "
                "(default 0.06)")
        .option("loop", "N", "cross-fade the last N cells into the first, for a seamless loop")
        .option("motion", "flow|none",
                "motion vectors measured as optical flow between the cells (default), or none")
        .option("hdr", "",
                "also write DIR/colour.exr: the colour in linear light, half floats, before the "
                "tone map (for emissive effects)")
        .option("six-way", "",
                "also bake the smoke's six-way light maps (lit from right, top, back, left, "
                "bottom, front), packed in two sheets as Unity's six-way smoke takes them")
        .option("evaluate", "R",
                "also measure the sheets played at 1/R of their rate (the mean error of the "
                "motion-vector blend and of a cross-fade against the cells between) and, with "
                "--six-way, the six-way blend against the smoke lit from three diagonal lights");
    return command;
}

CommandLine compareCommandLine() {
    CommandLine command("usage: motionfx compare SCENARIO [options]\n\nRuns SCENARIO (" +
                            scenarioNameList() +
                            ") on the GPU solver and on the CPU reference from the same input and "
                            "prints, after every stage of every step, the largest absolute and the "
                            "relative L2 difference of velocity, pressure and pigment.\nStages: " +
                            stageNameList() + ".",
                        1, CommandLine::kDevice);
    command.option("steps", "K", "number of steps (default 20)")
        .option("grid", "NXxNYxNZ", "grid cells (default 32x32x32)")
        .option("stage", "NAME", "compare this stage alone, from the same input each step")
        .option("pressure", "NAME",
                "pressure solver of both sides: jacobi, rbgs, multigrid or mgpcg (default: the "
                "scenario's)")
        .json("the comparison")
        .option("tolerance", "X", "exit with status 1 if any relative L2 difference exceeds X");
    return command;
}

CommandLine benchSolverCommandLine() {
    CommandLine command(
        "usage: motionfx bench solver [options]\n\nTimes the GPU smoke solver "
        "with timestamp queries: the median milliseconds of each stage and of a "
        "whole step, per grid size, and against the device's copy bandwidth measured "
        "in the same run: the bytes each stage must move, the GB/s it reaches "
        "and their share of the copy's. Pipelines are compiled and warmed up "
        "before timing.",
        0, CommandLine::kDevice);
    command.option("grids", "LIST", "comma-separated grids, N or NXxNYxNZ (default 32,64,96,128)")
        .option("jacobi", "N", "Jacobi (or red-black) sweeps per step (default 20)")
        .option("turbulence", "A",
                "dense: curl-noise turbulence of A m/s² on (default 0: the scenario's, off), to "
                "time its stage")
        .option("pressure", "NAME",
                "pressure solver: jacobi, rbgs, multigrid or mgpcg (default jacobi; multigrid "
                "and mgpcg with their default options)")
        .option("steps", "K", "timed steps per grid after 3 warm-up steps (default 10)")
        .option("scenario", "NAME", "scenario whose stages are timed (default puff)")
        .option("workgroups", "LIST",
                "comma-separated compute workgroup shapes XxYxZ to compare (default: the "
                "solver's, " +
                    workgroupLabel(fluid::SolverOptions{}.workgroup) + ")")
        .option("domain", "dense|sparse",
                "dense grids (default), or the sparse domain: ms a step against the number of "
                "active 8³ bricks, with a dense grid of the same cells in the same run")
        .option("virtual", "N", "sparse: the virtual domain's cells a side (default 256)")
        .option("bricks", "LIST",
                "sparse: comma-separated active brick counts (default "
                "8,27,64,125,216,343,512,729,1000)")
        .option("store", "auto|buffer|direct",
                "how stages store a whole field: into a buffer copied into the image, straight "
                "into the image, or by the device (default auto: buffer on a CPU device)")
        .option("coarse-group", "N",
                "multigrid and mgpcg: invocations of the workgroup that cycles the coarse "
                "levels (default 0: by device, 8 on a CPU device, on a GPU one per brick of a 16³ "
                "level)")
        .option("coarse-cells", "N",
                "multigrid and mgpcg: the largest level, in cells, cycled in that one workgroup "
                "(default 0: 4096, 16³; at most 4096)")
        .option("brick", "N",
                "multigrid, mgpcg and rbgs: rows and layers (1, 2 or 4) of the brick of cells one "
                "invocation handles (default 0: by device, 4 on a CPU device, 1 on a GPU)")
        .option("residual-in-restriction", "auto|on|off",
                "multigrid: the restriction computes the residual instead of a pass before it "
                "(default auto: on a GPU only)")
        .option("solids", "none|body|both",
                "dense, jacobi: moving solids in the grid, none (default) or the built-in "
                "fighter's body capsules mid-kick, half size, standing in the box; both: a "
                "solver without and one with them, stepped by turns, and the steps' ratio")
        .option("solid-lists", "auto|on|off",
                "with solids: each stage that reads them dispatched over the blocks away from "
                "them and over those near them (default auto: on a CPU device only)")
        .option("first-sweep-in-divergence", "auto|on|off",
                "jacobi: the divergence pass computes the cold solve's first sweep (default "
                "auto: on every device)")
        .option("copy-mib", "N",
                "MiB the copy-bandwidth yardstick copies (default 256, at most one storage "
                "buffer binding)")
        .option("plot", "FILE",
                "write an SVG plot: the rate each stage reaches against the copy bandwidth "
                "(sparse: the cost against active bricks)")
        .option("markdown", "FILE",
                "write the tables as a Markdown section into FILE (e.g. docs/performance.md), "
                "replacing the section of the same device and command")
        .json();
    return command;
}

CommandLine benchTrajectoryCommandLine() {
    CommandLine command(
        "usage: motionfx bench trajectory [options]\n\nBuilds the built-in "
        "fighter's trail (every vertex, motion lines) with the split method (one new "
        "segment per frame into a ring) and with the unsplit baseline (the whole "
        "trail rebuilt every frame), for each lifetime L, and reports skinning "
        "evaluations, vertices and GPU milliseconds per frame.",
        0, CommandLine::kDevice);
    command.option("lifetimes", "LIST", "comma-separated lifetimes L (default 1,2,4,8,16,32,64)")
        .option("sub-samples", "S", "sub-samples per segment, 1-16 (default 4)")
        .option("frames", "N", "timed frames per row after the trail has filled (default 20)")
        .option("clip", "NAME", "the fighter's clip (default roundhouse_kick)")
        .option("plot", "FILE", "the SVG plot (default out/bench_trajectory.svg)")
        .json("the table")
        .option("stats", "FILE", "also write every timed frame's statistics as JSON");
    return command;
}

CommandLine benchFrameCommandLine() {
    CommandLine command("usage: motionfx bench frame [SCENE] [options]\n\nRuns a scene (default: "
                        "the built-in one) frame by frame with its clip looping, simulating and "
                        "drawing every frame as `motionfx render` does (without writing images), "
                        "and reports the median GPU milliseconds of each pass (timestamp queries) "
                        "and the median wall time of a whole frame; the smoke's ray-march as the "
                        "rate it reads its pigment volumes at, against the device's copy "
                        "bandwidth measured in the same run.",
                        1, CommandLine::kDevice);
    command.option("size", "WxH", "image size (default 960x540)")
        .option("frames", "N", "timed frames (default 60)")
        .option("warmup", "N", "frames run first and not timed (default 5)")
        .option("sparse", "N",
                "also run the scene with its smoke on a sparse domain of N^3 cells (a multiple "
                "of 8, same cell size) and compare the smoke's GPU ms a step, same run")
        .option("smoke-looks", "",
                "also run the scene with its smoke in each look (smoke, fire, energy, cartoon), "
                "one after another in the same process, and compare the smoke pass's GPU ms")
        .option("smoke-march", "auto|fragment|compute",
                "the shader that marches the smoke: a fragment pass over the pigment's box or a "
                "compute pass (default auto: fragment on a CPU device, compute on a GPU)")
        .option("markdown", "FILE",
                "write the pass table as a Markdown section into FILE (e.g. "
                "docs/performance.md), replacing the section of the same device and command")
        .samples()
        .json();
    return command;
}

CommandLine benchAccuracyCommandLine() {
    CommandLine command(
        "usage: motionfx bench accuracy [options]\n\nRuns every configuration of the solver's "
        "accuracy options (pressure solver and effort, advection, storage) for K steps of each "
        "scenario on the GPU, times it, and measures the divergence it leaves and its velocity "
        "and pigment error against the CPU reference with the exact pressure solve on the same "
        "grid and against a grid twice as fine; then each pressure solver's time to a relative "
        "residual of 1e-3 at 64^3. A configuration the device cannot run (fp16 needs 16-bit "
        "float storage images) is measured on the CPU reference only (no time).\n\nScenarios: "
        "puff, jet, swirl and random-impulses as in motionfx compare, and kick: the impulses the "
        "built-in default scene's roundhouse kick splats into its smoke grid, recorded on the GPU "
        "step by step and mapped onto the benchmark's grid.",
        0, CommandLine::kDevice);
    command.option("grid", "N", "cells per axis of the accuracy runs (default 32)")
        .option("steps", "K", "steps per run (default 20)")
        .option("scenarios", "LIST",
                "comma-separated scenarios: puff, jet, swirl, random-impulses, kick (default "
                "puff,jet,kick)")
        .option("target-grid", "N",
                "cells per axis of the time-to-1e-3 runs (default 64; 0 skips them)")
        .option("target-solvers", "LIST",
                "comma-separated pressure solvers of the time-to-1e-3 runs (default "
                "jacobi,rbgs,multigrid,mgpcg)")
        .option("budgets", "LIST",
                "comma-separated GPU ms per step for the best-per-budget table (default "
                "2,5,10,20,50,100,200)")
        .option("csv", "FILE", "the table as CSV (default out/bench_accuracy.csv)")
        .option("plot", "FILE", "the SVG plot (default out/bench_accuracy.svg)")
        .json();
    return command;
}

CommandLine benchEffectsCommandLine() {
    CommandLine command(
        "usage: motionfx bench effects [SCENE...] [options]\n\nFor each scene "
        "(default: the demo scene of every technique, docs/scenes/{lines,blur,"
        "particles,smoke,afterimage,swept,shell}.json, from the project root), runs "
        "it simulated and drawn as `motionfx render` does, and again with its "
        "effects removed, and reports the extra GPU milliseconds and triangles per "
        "frame its effects cost against the character alone, and their share of the "
        "frame's time.",
        64, CommandLine::kDevice);
    command.option("size", "WxH", "image size (default 960x540)")
        .samples()
        .option("skip", "N", "first frames of each run not timed (default 2)")
        .json();
    return command;
}

CommandLine inspectCommandLine() {
    CommandLine command(
        "usage: motionfx inspect FILE\n\nLoads a glTF 2.0 character (.gltf or "
        ".glb) and prints its meshes, joints, clips, rest-pose bounds and the bones "
        "each bone group (right_leg, head, ...) resolves to, or the reason the file "
        "is refused.",
        1, CommandLine::kPlain);
    return command;
}

CommandLine exportFighterCommandLine() {
    CommandLine command("usage: motionfx export-fighter OUT.glb\n\nWrites the built-in fighter "
                        "(body and sword meshes, its 21-joint skin and its clips) as glTF 2.0: a "
                        "binary .glb, or a .gltf with the buffer embedded when OUT ends in .gltf.",
                        1, CommandLine::kPlain);
    return command;
}

CommandLine sceneCommandLine() {
    CommandLine command(
        "usage: motionfx scene [FILE | CHARACTER.glb]\n\nChecks a scene file "
        "(JSON; see README.md \"Scene files\") and prints what it asks for: the "
        "character and clip, the frames, and each effect with its window, its bones "
        "(bone groups and patterns resolved; the limb chosen for an effect that "
        "names none) and the vertices they select. Without FILE, the built-in "
        "default scene; a .gltf/.glb character file gets the default effects on its "
        "fastest limb.",
        1, CommandLine::kScene);
    return command;
}

CommandLine simulateCommandLine() {
    CommandLine command(
        "usage: motionfx simulate [SCENE | CHARACTER.glb] [options]\n\nRuns the "
        "scene's trajectories and smoke on the GPU, frame by frame, without drawing, "
        "and prints what ran. Without SCENE, the built-in default scene; a "
        ".gltf/.glb character file in its place gets the default effects on its "
        "fastest limb.",
        1, CommandLine::kDevice | CommandLine::kScene);
    command.option("frames", "N", "simulate N frames (default: the scene's)")
        .option("stats", "FILE", "write per-frame statistics as JSON");
    for (const cli::OptionSpec& o : vdbOptions())
        command.option(o.name, o.valueName, o.help);
    return command;
}

CommandLine viewCommandLine() {
    CommandLine command("usage: motionfx view [SCENE | CHARACTER.glb] [options]\n\nPlays a scene "
                        "file (default: the built-in scene; a .gltf/.glb character file gets the "
                        "default effects on its fastest limb) in a window in real time, looping, "
                        "with the frame number, frame time and state drawn in the corner.\n" +
                            std::string(kViewKeysHelp) + ".",
                        1, CommandLine::kDevice | CommandLine::kScene);
    command
        .option("size", "WxH",
                "the picture's size in pixels (default 960x540); the window starts at this size "
                "and may be resized")
        .samples()
        .option("paused", "", "start paused on the first frame")
        .option("quit-after", "N", "close by itself after presenting N frames")
        .option("no-panel", "", "start with the parameter panel hidden (tab shows it)")
        .option("screenshot-panel", "", "show the parameter panel in screenshots too")
        .option("screenshot", "FILE",
                "on closing (and whenever s is pressed), write the window's picture as PNG");
    return command;
}

std::span<const Command> benchCommands() {
    static const Command table[] = {
        {"solver", "GPU milliseconds per solver stage and per step, by grid size",
         &benchSolverCommandLine, &runBenchSolver},
        {"trajectory",
         "split trajectory against the unsplit baseline: skinning, vertices and GPU ms per "
         "frame, by lifetime",
         &benchTrajectoryCommandLine, &runBenchTrajectory},
        {"frame", "GPU ms per pass and whole-frame time of a scene, simulated and drawn",
         &benchFrameCommandLine, &runBenchFrame},
        {"accuracy", "error against GPU ms of the solver's accuracy options; time to 1e-3",
         &benchAccuracyCommandLine, &runBenchAccuracy},
        {"effects", "extra GPU ms and triangles per frame of each effect technique",
         &benchEffectsCommandLine, &runBenchEffects},
    };
    return table;
}

} // namespace

std::span<const Command> commands() {
    static const Command table[] = {
        {"info", "print the chosen Vulkan device and its capabilities", &infoCommandLine, &runInfo},
        {"render", "render a scene (default: the built-in one) into PNG frames (and MP4)",
         &renderCommandLine, &runRender},
        {"bake", "bake a scene's effects into flipbook sheets (colour, motion vectors, JSON)",
         &bakeCommandLine, &runBake},
        {"compare", "run a solver scenario on GPU and CPU reference, print the differences",
         &compareCommandLine, &runCompare},
        {"bench",
         "benchmarks (bench solver: GPU ms per stage and step; bench trajectory: split vs "
         "unsplit trail by lifetime; bench frame: a scene's passes and frame time; bench "
         "effects: each effect's extra GPU ms and triangles per frame)",
         nullptr, nullptr, &benchCommands, "benchmarks"},
        {"inspect", "load a glTF character and summarise it (meshes, joints, clips, bounds)",
         &inspectCommandLine, &runInspect},
        {"scene", "check a scene file and print what it asks for (effects, bones, vertices)",
         &sceneCommandLine, &runScene},
        {"simulate",
         "run a scene's trajectories and smoke on the GPU without drawing; per-frame --stats",
         &simulateCommandLine, &runSimulate},
        {"view", "play a scene in a window in real time (pause, step, scrub, effect toggles)",
         &viewCommandLine, &runView},
        {"export-fighter", "write the built-in fighter as glTF 2.0 (.glb or .gltf)",
         &exportFighterCommandLine, &runExportFighter},
    };
    return table;
}

} // namespace mfx::app
