// The motionfx program as a user meets it: exit codes, one-line errors, help, outputs.
#include "tests/cli_run.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stb_image.h>
#include <string>
#include <sys/wait.h>

namespace {

using mfx::test::lineCount;
using mfx::test::readFile;
using mfx::test::runMotionfx;
using mfx::test::RunResult;

TEST(Cli, InfoNamesTheDeviceAndItsCapabilities) {
    const RunResult r = runMotionfx("info --device llvmpipe");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("llvmpipe"), std::string::npos) << r.out;
    for (const char* key : {"CPU implementation              yes", "geometryShader",
                            "transformFeedback", "shaderFloat16", "maxComputeWorkGroupInvocations",
                            "maxImageDimension3D", "timestampPeriod", "Vulkan version"})
        EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing from:\n" << r.out;
}

TEST(Cli, NoVulkanDriverIsOneClearSentence) {
    const RunResult r =
        runMotionfx("info", "VK_DRIVER_FILES=/nonexistent VK_ICD_FILENAMES=/nonexistent");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("motionfx: error: no Vulkan ", 0), 0u) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Cli, UnknownDeviceIsOneLine) {
    const RunResult r = runMotionfx("info --device no-such-gpu-9000");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("no-such-gpu-9000"), std::string::npos) << r.err;
}

TEST(Cli, NoCommandPrintsUsageAndFails) {
    const RunResult r = runMotionfx("");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("usage: motionfx"), std::string::npos) << r.err;
}

TEST(Cli, UnknownCommandIsOneLine) {
    const RunResult r = runMotionfx("explode");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("unknown command 'explode'"), std::string::npos) << r.err;
}

TEST(Cli, UnknownOptionIsOneLine) {
    const RunResult r = runMotionfx("render --colour red");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--colour"), std::string::npos) << r.err;
}

TEST(Cli, MissingOptionValueIsOneLine) {
    const RunResult r = runMotionfx("render --size");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
}

TEST(Cli, BadSizeIsOneLine) {
    for (const char* size : {"12x", "x9", "0x10", "10x-3", "99999x10", "abc", "1e3x10"}) {
        const RunResult r = runMotionfx(std::string("render --size ") + size);
        EXPECT_EQ(r.exitCode, 2) << size;
        EXPECT_EQ(lineCount(r.err), 1u) << size << ": " << r.err;
    }
}

TEST(Cli, BenchSolverPrintsATableAndWritesJson) {
    const std::string json = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/bench_solver.json";
    std::filesystem::remove(json);
    const RunResult r = runMotionfx("bench solver --grids 8,6x5x4 --steps 2 --jacobi 3 "
                                    "--workgroups 8x8x4,4x4x4 --json \"" +
                                    json + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("solve_pressure"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("whole step (GPU)"), std::string::npos) << r.out;
    const std::string text = readFile(json);
    for (const char* key :
         {"\"device\"", "\"results\"", "\"grid\"", "\"jacobi\": 3", "\"step_ms\"", "\"stages\"",
          "\"workgroup\"", "\"solve_pressure\"", "\"first_sweep_in_divergence\": true"})
        EXPECT_NE(text.find(key), std::string::npos) << key << " missing from " << text;
}

// --solids both: a solver without the body and one with it, stepped by turns: two columns, the
// steps' ratio, and the split or whole stages as asked.
TEST(Cli, BenchSolverComparesTheBodyWithoutAndWith) {
    const std::string json = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/bench_solver_body.json";
    std::filesystem::remove(json);
    for (const char* lists : {"on", "off"}) {
        const RunResult r =
            runMotionfx(std::string("bench solver --grids 16 --steps 2 --jacobi 3 --solids both "
                                    "--solid-lists ") +
                        lists + " --json \"" + json + "\"");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find("16x16x16 body ms"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("the step with the body over the step without"), std::string::npos)
            << r.out;
        EXPECT_NE(
            r.out.find(std::string(lists) == "on" ? "split into the blocks" : "dispatched whole"),
            std::string::npos)
            << r.out;
        const nlohmann::json doc = nlohmann::json::parse(readFile(json));
        ASSERT_EQ(doc["results"].size(), 2u);
        EXPECT_FALSE(doc["results"][0]["body"].get<bool>());
        EXPECT_TRUE(doc["results"][1]["body"].get<bool>());
        EXPECT_GT(doc["results"][1]["stages"]["mark_solids"]["ms"].get<double>(), 0.0);
        ASSERT_EQ(doc["body_step_ratios"].size(), 1u);
        EXPECT_GT(doc["body_step_ratios"][0].get<double>(), 0.0);
        EXPECT_EQ(doc["solid_lists"].get<bool>(), std::string(lists) == "on");
    }
}

TEST(Cli, BenchTrajectoryPrintsATableWritesJsonAndAPlot) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli";
    const std::string json = dir + "/bench_trajectory.json", plot = dir + "/bench_trajectory.svg",
                      stats = dir + "/bench_trajectory_stats.json";
    for (const std::string& f : {json, plot, stats})
        std::filesystem::remove(f);
    const RunResult r = runMotionfx("bench trajectory --lifetimes 1,3 --frames 2 --sub-samples 2 "
                                    "--json \"" +
                                    json + "\" --plot \"" + plot + "\" --stats \"" + stats + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("skinning/frame"), std::string::npos) << r.out;
    const nlohmann::json doc = nlohmann::json::parse(readFile(json));
    EXPECT_TRUE(doc.contains("device"));
    // split and unsplit, and split-xfb where the device has geometry shaders and transform
    // feedback (lavapipe does): two lifetimes each.
    const size_t rowCount = doc["rows"].size();
    ASSERT_TRUE(rowCount == 4u || rowCount == 6u) << rowCount;
    std::map<std::string, double> skinning, vertices; // by "method L"
    for (const nlohmann::json& row : doc["rows"]) {
        for (const char* key :
             {"method", "lifetime", "skinning_per_frame", "vertices_per_frame", "gpu_ms"})
            ASSERT_TRUE(row.contains(key)) << key;
        const std::string name =
            row["method"].get<std::string>() + " " + std::to_string(row["lifetime"].get<int>());
        skinning[name] = row["skinning_per_frame"].get<double>();
        vertices[name] = row["vertices_per_frame"].get<double>();
    }
    // Split: skinning per frame does not depend on L; unsplit: it grows with L.
    EXPECT_EQ(skinning["split 1"], skinning["split 3"]);
    EXPECT_EQ(skinning["unsplit 3"], 3.0 * skinning["unsplit 1"]);
    EXPECT_EQ(vertices["unsplit 3"], 3.0 * vertices["split 3"]);
    if (rowCount == 6u) {
        EXPECT_EQ(vertices["split-xfb 3"], vertices["split 3"]);
        EXPECT_EQ(skinning["split-xfb 3"], 2.0 * skinning["split 3"]); // both ends, every frame
    }
    EXPECT_NE(readFile(plot).find("<svg"), std::string::npos);
    EXPECT_EQ(nlohmann::json::parse(readFile(stats)).size(), 2u * rowCount); // 2 frames a row
}

TEST(Cli, BenchTrajectoryBadValuesAreOneLine) {
    for (const char* args : {"--lifetimes 0", "--lifetimes 1,x", "--sub-samples 17", "--frames 0",
                             "--clip moonwalk"}) {
        const RunResult r = runMotionfx(std::string("bench trajectory ") + args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    }
}

TEST(Cli, BenchFramePrintsPassesAndWritesJson) {
    const std::string json = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/bench_frame.json";
    std::filesystem::remove(json);
    const RunResult r = runMotionfx("bench frame --size 160x90 --frames 3 --warmup 1 --samples 1 "
                                    "--json \"" +
                                    json + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* row :
         {"render/scene", "render/effects", "render/smoke", "smoke/solve_pressure", "trajectories",
          "wall, whole frame", "frames per second"})
        EXPECT_NE(r.out.find(row), std::string::npos) << row << " missing from " << r.out;
    const nlohmann::json doc = nlohmann::json::parse(readFile(json));
    EXPECT_EQ(doc["size"], nlohmann::json({160, 90}));
    EXPECT_EQ(doc["grid"], nlohmann::json({48, 48, 48})); // the built-in scene's smoke grid
    EXPECT_GT(doc["frame_ms"].get<double>(), 0.0);
    EXPECT_NEAR(doc["fps"].get<double>(), 1000.0 / doc["frame_ms"].get<double>(), 1e-6);
    for (const char* pass : {"render/skin", "render/shadow", "render/scene", "render/effects",
                             "render/smoke", "smoke/advect_velocity"})
        EXPECT_TRUE(doc["passes"].contains(pass)) << pass;
    EXPECT_TRUE(doc.contains("device"));
}

// bench effects on two demo scenes at a small size: extra triangles are exact counts (the blur's
// volumes and the shell's strips add primitives; the character alone is the same in both scenes'
// baselines), the extra milliseconds are whatever the run measured.
TEST(Cli, BenchEffectsWritesExtraCostPerEffect) {
    const std::string json = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/bench_effects.json";
    std::filesystem::remove(json);
    const std::string scenes = std::string(MFX_SOURCE_DIR) + "/docs/scenes/";
    const RunResult r =
        runMotionfx("bench effects \"" + scenes + "blur.json\" \"" + scenes +
                    "shell.json\" --size 64x36 --samples 1 --json \"" + json + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("extra tris"), std::string::npos) << r.out;
    const nlohmann::json doc = nlohmann::json::parse(readFile(json));
    EXPECT_TRUE(doc.contains("device"));
    for (const char* effect : {"motion_blur", "silhouette_shell"}) {
        ASSERT_TRUE(doc["effects"].contains(effect)) << effect;
        const nlohmann::json& e = doc["effects"][effect];
        EXPECT_TRUE(e["extra_ms"].is_number()) << effect;
        EXPECT_GT(e["extra_triangles"].get<double>(), 0.0) << effect;
        EXPECT_GT(e["alone_triangles"].get<double>(), 0.0) << effect;
    }
    EXPECT_EQ(doc["effects"]["motion_blur"]["alone_triangles"],
              doc["effects"]["silhouette_shell"]["alone_triangles"]);
}

TEST(Cli, BenchEffectsRefusesASceneWithoutEffects) {
    const RunResult r =
        runMotionfx("bench effects \"" + std::string(MFX_SOURCE_DIR) + "/docs/scenes/none.json\"");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("no effect to measure"), std::string::npos) << r.err;
}

TEST(Cli, BenchAccuracyWritesTableCsvPlotAndJson) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli";
    const std::string json = dir + "/bench_accuracy.json", csv = dir + "/bench_accuracy.csv",
                      plot = dir + "/bench_accuracy.svg";
    for (const std::string& f : {json, csv, plot})
        std::filesystem::remove(f);
    const RunResult r = runMotionfx("bench accuracy --grid 8 --steps 3 --scenarios puff "
                                    "--target-grid 8 --json \"" +
                                    json + "\" --csv \"" + csv + "\" --plot \"" + plot + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("jacobi 20"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("time to a relative residual of 1e-3"), std::string::npos) << r.out;
    const nlohmann::json doc = nlohmann::json::parse(readFile(json));
    EXPECT_TRUE(doc.contains("device"));
    ASSERT_TRUE(doc.contains("time_to_1e-3"));
    const nlohmann::json& t = doc["time_to_1e-3"];
    EXPECT_EQ(t["grid"], nlohmann::json({8, 8, 8}));
    EXPECT_GT(t["jacobi_ms"].get<double>(), 0.0);
    EXPECT_GT(t["best_ms"].get<double>(), 0.0);
    EXPECT_LE(t["best_ms"].get<double>(), t["jacobi_ms"].get<double>());
    EXPECT_FALSE(t["best_option"].get<std::string>().empty());
    // More effort, less divergence left: jacobi 10 leaves more than jacobi 160.
    double left10 = -1.0, left160 = -1.0;
    for (const nlohmann::json& row : doc["results"]) {
        if (row["configuration"] == "jacobi 10") left10 = row["divergence_left"].get<double>();
        if (row["configuration"] == "jacobi 160") left160 = row["divergence_left"].get<double>();
    }
    EXPECT_GT(left10, left160);
    EXPECT_GT(left160, -0.5);
    EXPECT_NE(readFile(csv).find("scenario,configuration,gpu,step_ms"), std::string::npos);
    EXPECT_NE(readFile(plot).find("<svg"), std::string::npos);
}

TEST(Cli, BenchSolverBadValuesAreOneLine) {
    for (const char* args :
         {"--grids 0", "--grids 8x8", "--workgroups 8x8", "--workgroups 0x8x4", "--jacobi -1",
          "--steps 0", "--scenario nope", "--residual-in-restriction yes",
          "--first-sweep-in-divergence 1", "--solids legs", "--solid-lists maybe"}) {
        const RunResult r = runMotionfx(std::string("bench solver ") + args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    }
    // A shape the device cannot run is refused when the solver is made.
    const RunResult r = runMotionfx("bench solver --grids 8 --workgroups 64x64x64");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("workgroup"), std::string::npos) << r.err;
}

// A Markdown file the tables cannot go into is refused before anything runs, in one line naming it.
TEST(Cli, BenchMarkdownFileThatCannotBeWrittenIsOneLine) {
    for (const char* args : {"bench solver --grids 8 --markdown /dev/null",
                             "bench solver --grids 8 --markdown /nonexistent/folder/perf.md",
                             "bench frame --frames 1 --markdown /dev/null"}) {
        const RunResult r = runMotionfx(args);
        EXPECT_EQ(r.exitCode, 1) << args;
        EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
        EXPECT_NE(r.err.find("Markdown"), std::string::npos) << r.err;
    }
}

TEST(Cli, BenchSolverSparsePrintsATableWritesJsonAndAPlot) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli";
    const std::string json = dir + "/bench_sparse.json", plot = dir + "/bench_sparse.svg";
    for (const std::string& f : {json, plot})
        std::filesystem::remove(f);
    const RunResult r = runMotionfx("bench solver --domain sparse --virtual 32 --bricks 1,8 "
                                    "--steps 1 --jacobi 2 --json \"" +
                                    json + "\" --plot \"" + plot + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("linear fit"), std::string::npos) << r.out;
    const nlohmann::json doc = nlohmann::json::parse(readFile(json));
    ASSERT_EQ(doc["results"].size(), 2u);
    EXPECT_EQ(doc["results"][0]["bricks"], 1);
    EXPECT_EQ(doc["results"][1]["bricks"], 8);
    for (const auto& result : doc["results"]) {
        EXPECT_GT(result["step_ms"].get<double>(), 0.0);
        EXPECT_GT(result["dense_step_ms"].get<double>(), 0.0);
        EXPECT_GT(result["bytes"].get<double>(), 0.0);
        EXPECT_TRUE(result["stages"].contains("advect_velocity"));
    }
    EXPECT_NE(readFile(plot).find("<svg"), std::string::npos);
}

TEST(Cli, BenchSolverSparseBadValuesAreOneLine) {
    for (const char* args :
         {"--domain bogus", "--domain sparse --virtual 20",
          "--domain sparse --virtual 32 --bricks 65", "--domain sparse --bricks 0", "--virtual 64",
          "--domain sparse --first-sweep-in-divergence off"}) {
        const RunResult r = runMotionfx(std::string("bench solver ") + args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    }
}

TEST(Cli, UnwritableOutputIsOneLine) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli";
    std::filesystem::create_directories(dir);
    const std::string file = dir + "/a_file";
    { std::ofstream(file) << "not a directory"; }
    const RunResult r = runMotionfx("render --size 32x32 --out " + file + "/frames");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("a_file/frames"), std::string::npos) << r.err;
}

TEST(Cli, EveryCommandHasHelp) {
    for (const char* command : {"info", "render"}) {
        const RunResult r = runMotionfx(std::string(command) + " --help");
        EXPECT_EQ(r.exitCode, 0) << command;
        EXPECT_NE(r.out.find(std::string("usage: motionfx ") + command), std::string::npos)
            << r.out;
        EXPECT_NE(r.out.find("--device"), std::string::npos) << r.out;
    }
    const RunResult top = runMotionfx("--help");
    EXPECT_EQ(top.exitCode, 0);
    EXPECT_NE(top.out.find("render"), std::string::npos);
}

// The default scene's first frames, with validation on; and a speed-lines scene to the end.
TEST(Cli, RenderWritesNumberedFramesWithValidationClean) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli_render";
    std::filesystem::remove_all(dir);
    const std::string stats = dir + "_stats.json";
    const RunResult r =
        runMotionfx("render --size 64x36 --frames 2 --validate --out " + dir + " --stats " + stats);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("rendered (built-in default scene"), std::string::npos) << r.out;
    for (const char* frame : {"/frame_0000.png", "/frame_0001.png"}) {
        int w = 0, h = 0, channels = 0;
        stbi_uc* pixels = stbi_load((dir + frame).c_str(), &w, &h, &channels, 4);
        ASSERT_NE(pixels, nullptr) << "no PNG at " << dir << frame;
        EXPECT_EQ(w, 64);
        EXPECT_EQ(h, 36);
        stbi_image_free(pixels);
    }
    const nlohmann::json doc = nlohmann::json::parse(readFile(stats));
    ASSERT_EQ(doc["frames"].size(), 2u);
    EXPECT_GT(doc["frames"][1]["fluid_bytes"].get<double>(), 0.0); // the default has smoke
    EXPECT_TRUE(doc["frames"][1]["passes"].is_array());
}

TEST(Cli, RenderOfASpeedLinesSceneRunsToItsEnd) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli_render_lines";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string scene = dir + "/lines.json";
    std::ofstream(scene) << R"({"output": {"width": 96, "height": 54},
                                "effects": [{"type": "speed_lines"}]})";
    const RunResult r = runMotionfx("render \"" + scene + "\" --out " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/frame_0026.png")); // 0.9 s at 30 fps
    EXPECT_FALSE(std::filesystem::exists(dir + "/frame_0027.png"));
}

// What ffprobe reads of the first video stream of `file`: key=value pairs (frames counted by
// decoding).
std::map<std::string, std::string> probeVideo(const std::string& file) {
    const std::string listing = file + ".probe";
    const std::string command =
        "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
        "stream=codec_name,pix_fmt,width,height,nb_read_frames,r_frame_rate "
        "-of default=noprint_wrappers=1 \"" +
        file + "\" >\"" + listing + "\"";
    std::map<std::string, std::string> values;
    if (std::system(command.c_str()) != 0) return values;
    std::istringstream lines(readFile(listing));
    for (std::string line; std::getline(lines, line);)
        if (const size_t eq = line.find('='); eq != std::string::npos)
            values[line.substr(0, eq)] = line.substr(eq + 1);
    return values;
}

// The video (./build.sh installs ffmpeg): H.264 in yuv420p, which browsers play, one frame per
// frame rendered at --fps, an odd size padded to even. --fps sets the simulation's rate too: the
// default scene's 1.7 s is 17 frames at 10 fps. The folder holds 34 frames of an earlier run at
// 20 fps, which the video must not pick up.
TEST(Cli, RenderWritesAnH264VideoOfItsFramesAtItsFps) {
    ASSERT_EQ(std::system("command -v ffprobe >/dev/null 2>&1"), 0)
        << "ffprobe is not installed (./build.sh deps installs ffmpeg)";
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli_render_video";
    std::filesystem::remove_all(dir);
    const RunResult earlier = runMotionfx("render --size 65x37 --fps 20 --out " + dir);
    ASSERT_EQ(earlier.exitCode, 0) << earlier.err;
    ASSERT_TRUE(std::filesystem::exists(dir + "/frame_0033.png"));
    const RunResult r = runMotionfx("render --size 65x37 --fps 10 --out " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("17 frames of 65x37"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(dir + "/scene.mp4"), std::string::npos) << r.out;
    const std::map<std::string, std::string> video = probeVideo(dir + "/scene.mp4");
    EXPECT_EQ(video.count("codec_name") ? video.at("codec_name") : "", "h264");
    EXPECT_EQ(video.count("pix_fmt") ? video.at("pix_fmt") : "", "yuv420p");
    EXPECT_EQ(video.count("width") ? video.at("width") : "", "66");
    EXPECT_EQ(video.count("height") ? video.at("height") : "", "38");
    EXPECT_EQ(video.count("r_frame_rate") ? video.at("r_frame_rate") : "", "10/1");
    EXPECT_EQ(video.count("nb_read_frames") ? video.at("nb_read_frames") : "", "17");
}

TEST(Cli, RenderRefusesAnFpsOutOfRange) {
    for (const char* fps : {"0", "241", "nan", "fast"}) {
        const RunResult r = runMotionfx(std::string("render --fps ") + fps);
        EXPECT_EQ(r.exitCode, 2) << fps;
        EXPECT_EQ(lineCount(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find("--fps"), std::string::npos) << r.err;
    }
}

TEST(Cli, RenderOfABadSceneIsOneLine) {
    const RunResult r = runMotionfx("render /nonexistent/scene.json");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
}

// motionfx inspect on the third-party characters and on broken files.
const std::string kSharedDir = std::string(MFX_SOURCE_DIR) + "/../shared";

TEST(CliInspect, RiggedFigureHas19Joints) {
    const RunResult r = runMotionfx("inspect \"" + kSharedDir + "/assets/RiggedFigure.gltf\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    for (const char* line : {"joints       19 in 1 skins", "Proxy: 1 primitives, 370 vertices",
                             "clips        1", "57 channels", "bounds"})
        EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing from:\n" << r.out;
}

TEST(CliInspect, BadFileIsOneLine) {
    const std::string file = kSharedDir + "/gltf-bad/skin/ibm_invalid_count.gltf";
    const RunResult r = runMotionfx("inspect \"" + file + "\"");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("motionfx: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("ibm_invalid_count.gltf: skins[0]"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(CliInspect, MissingFileIsOneLineNamingIt) {
    const RunResult r = runMotionfx("inspect /nonexistent/dancer.glb");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("/nonexistent/dancer.glb"), std::string::npos) << r.err;
}

TEST(CliInspect, BufferOutsideTheFolderIsOneLineAndNotRead) {
    // Before, inspect printed the size of the system file this names, and a matching
    // byteLength loaded its bytes as vertices.
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli_outside";
    std::filesystem::create_directories(dir);
    const std::string file = dir + "/system.gltf";
    std::ofstream(file) << R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": "../../../../../../../../etc/passwd"}]})";
    const RunResult r = runMotionfx("inspect \"" + file + "\"");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("system.gltf: buffers[0].uri: \"../../../../../../../../etc/passwd\" "
                         "leads outside the glTF file's folder"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(CliInspect, NoFileIsABadUsage) {
    const RunResult r = runMotionfx("inspect");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    const RunResult two = runMotionfx("inspect a.gltf b.gltf");
    EXPECT_EQ(two.exitCode, 2);
}

// motionfx export-fighter: the file it writes is one inspect reads back.
TEST(CliExportFighter, WritesAGlbThatInspectReads) {
    const std::string file = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/fighter.glb";
    std::filesystem::remove(file);
    const RunResult r = runMotionfx("export-fighter \"" + file + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("2 meshes, 21 joints, 7 clips"), std::string::npos) << r.out;
    const RunResult inspected = runMotionfx("inspect \"" + file + "\"");
    ASSERT_EQ(inspected.exitCode, 0) << inspected.err;
    for (const char* line : {"joints       21 in 1 skins", "sword: ", "roundhouse_kick: 0.9 s"})
        EXPECT_NE(inspected.out.find(line), std::string::npos) << line << " missing from:\n"
                                                               << inspected.out;
}

TEST(CliExportFighter, WrongExtensionIsABadUsage) {
    const RunResult r = runMotionfx("export-fighter fighter.obj");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("fighter.obj"), std::string::npos) << r.err;
    const RunResult none = runMotionfx("export-fighter");
    EXPECT_EQ(none.exitCode, 2);
}

TEST(CliExportFighter, UnwritablePathIsOneLineNamingIt) {
    const RunResult r = runMotionfx("export-fighter /nonexistent/dir/fighter.glb");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("/nonexistent/dir/fighter.glb"), std::string::npos) << r.err;
}

// motionfx scene: the default scene, a good file and a bad one.
TEST(CliScene, DefaultSceneIsSummarised) {
    const RunResult r = runMotionfx("scene");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* line :
         {"clip kick_slash", "51 frames", "kick lines", "slash arc", "energy smoke"})
        EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing from:\n" << r.out;
}

TEST(CliScene, UnknownBoneIsOneLineNamingTheKey) {
    const std::string file = std::string(MFX_TEST_OUTPUT_DIR) + "/cli/bad_bone.json";
    std::ofstream(file) << R"({"effects": [{"type": "smoke", "bones": ["hand_X"]}]})";
    const RunResult r = runMotionfx("scene \"" + file + "\"");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("bad_bone.json: effects[0].bones[0]: no bone or bone group \"hand_X\"; "
                         "groups are: right_leg, left_leg, right_arm"),
              std::string::npos)
        << r.err;
}

TEST(CliScene, MissingFileIsOneLine) {
    const RunResult r = runMotionfx("scene /nonexistent/kick.json");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("/nonexistent/kick.json"), std::string::npos) << r.err;
}

} // namespace
