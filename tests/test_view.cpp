// motionfx view under a virtual X server (Xvfb): it opens a window, presents frames with the
// status line drawn on them, answers keys, and closes when the window manager asks it to
// (WM_DELETE_WINDOW, sent by tests/x11_window_tool.cpp) or after --quit-after frames.
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sstream>
#include <stb_image.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace {

using namespace std::chrono_literals;

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string outputDir() {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/view";
    std::filesystem::create_directories(dir);
    return dir;
}

std::string testName() {
    return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// The environment for motionfx view under the sanitizer run (build.sh): that run preloads the
// Vulkan driver and the validation layer so LeakSanitizer can see their memory, but with either
// preloaded GLFW finds no window-surface support in the Vulkan loader. The view keeps
// AddressSanitizer and UBSan (libasan stays preloaded) and runs without the two and without leak
// checking, which needs them.
std::string viewEntry(const std::string& entry) {
    if (entry.rfind("LD_PRELOAD=", 0) == 0) {
        std::stringstream words(entry.substr(11));
        std::string word, kept;
        while (words >> word)
            if (word.find("libVkLayer") == std::string::npos &&
                word.find("libvulkan") == std::string::npos)
                kept += (kept.empty() ? "" : " ") + word;
        return "LD_PRELOAD=" + kept;
    }
    if (entry.rfind("ASAN_OPTIONS=", 0) == 0) return entry + ":detect_leaks=0";
    return entry;
}

// A child process of `argv`, its output into files; killed if still running when destroyed.
// A `helper` (the X server) runs without the sanitizer run's preloaded libraries: only
// motionfx is under test.
class Child {
public:
    Child(std::vector<std::string> argv, const std::string& outPath, const std::string& errPath,
          const std::string& display, bool helper = false) {
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644);
        posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644);
        std::vector<std::string> env;
        for (char** e = environ; *e; ++e)
            if (std::strncmp(*e, "DISPLAY=", 8) != 0 &&
                !(helper && std::strncmp(*e, "LD_PRELOAD=", 11) == 0))
                env.push_back(helper ? std::string(*e) : viewEntry(*e));
        env.push_back("DISPLAY=" + display);
        std::vector<char*> args, envp;
        for (std::string& a : argv)
            args.push_back(a.data());
        args.push_back(nullptr);
        for (std::string& e : env)
            envp.push_back(e.data());
        envp.push_back(nullptr);
        if (posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), envp.data()) != 0)
            pid_ = -1;
        posix_spawn_file_actions_destroy(&actions);
    }
    ~Child() {
        if (pid_ > 0 && !exited_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    bool started() const { return pid_ > 0; }
    // The exit status, or -1 if still running after `limit`.
    int waitFor(std::chrono::seconds limit) {
        const auto end = std::chrono::steady_clock::now() + limit;
        for (;;) { // checked at least once, so waitFor(0s) polls
            int status = 0;
            if (::waitpid(pid_, &status, WNOHANG) == pid_) {
                exited_ = true;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            if (std::chrono::steady_clock::now() >= end) return -1;
            std::this_thread::sleep_for(50ms);
        }
    }

private:
    pid_t pid_ = -1;
    bool exited_ = false;
};

// One Xvfb server for the suite, on the first free display from :91.
class ViewTest : public ::testing::Test {
protected:
    // ctest runs each test in a process of its own, in parallel: each process tries displays
    // from one of its own (by process id), and a server that cannot take its display exits.
    static void SetUpTestSuite() {
        const int first = 100 + int(::getpid() % 800);
        for (int n = first; n < first + 40 && !server_; ++n) {
            if (std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock") ||
                std::filesystem::exists("/tmp/.X11-unix/X" + std::to_string(n)))
                continue;
            display_ = ":" + std::to_string(n);
            const std::string log = outputDir() + "/xvfb_" + std::to_string(n) + ".log";
            server_ = std::make_unique<Child>(
                std::vector<std::string>{"/usr/bin/Xvfb", display_, "-screen", "0", "1024x768x24",
                                         "-nolisten", "tcp"},
                log, log, display_, true);
            const auto end = std::chrono::steady_clock::now() + 20s;
            bool up = false;
            while (!up && server_->waitFor(0s) == -1 && std::chrono::steady_clock::now() < end) {
                up = std::filesystem::exists("/tmp/.X11-unix/X" + std::to_string(n));
                if (!up) std::this_thread::sleep_for(50ms);
            }
            if (!up) server_.reset();
        }
    }
    static void TearDownTestSuite() { server_.reset(); }
    void SetUp() override {
        ASSERT_TRUE(std::filesystem::exists("/usr/bin/Xvfb"))
            << "Xvfb is not installed (Debian package xvfb; ./build.sh installs it)";
        ASSERT_TRUE(server_) << "Xvfb did not start; see " << outputDir() << "/xvfb_*.log";
    }

    // motionfx view with `arguments`, its stdout and stderr in files named after the test.
    std::unique_ptr<Child> startView(std::vector<std::string> arguments) {
        std::vector<std::string> argv{MFX_MOTIONFX_PATH, "view"};
        argv.insert(argv.end(), arguments.begin(), arguments.end());
        return std::make_unique<Child>(argv, outPath(), errPath(), display_);
    }
    std::string outPath() const { return outputDir() + "/" + testName() + ".stdout"; }
    std::string errPath() const { return outputDir() + "/" + testName() + ".stderr"; }
    // Waits until the view's stdout has `text` after its first `from` characters.
    bool waitForOutput(const std::string& text, std::chrono::seconds limit, size_t from = 0) const {
        const auto end = std::chrono::steady_clock::now() + limit;
        while (std::chrono::steady_clock::now() < end) {
            const std::string out = readFile(outPath());
            if (out.size() > from && out.find(text, from) != std::string::npos) return true;
            std::this_thread::sleep_for(100ms);
        }
        return false;
    }
    size_t outputSoFar() const { return readFile(outPath()).size(); }
    int windowTool(const std::string& words) const {
        const std::string command = "env -u LD_PRELOAD DISPLAY=" + display_ + " \"" +
                                    MFX_X11_WINDOW_TOOL + "\" " + words + " 2>>\"" + errPath() +
                                    ".tool\"";
        const int status = std::system(command.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    static inline std::unique_ptr<Child> server_;
    static inline std::string display_;
};

TEST_F(ViewTest, OpensAWindowPresentsFramesAndQuits) {
    const std::string shot = outputDir() + "/quit_after.png";
    std::filesystem::remove(shot);
    auto view = startView({"--size", "320x180", "--quit-after", "6", "--screenshot", shot});
    ASSERT_TRUE(view->started());
    const int status = view->waitFor(300s);
    ASSERT_EQ(status, 0) << readFile(errPath());
    const std::string out = readFile(outPath());
    EXPECT_NE(out.find("first frame presented"), std::string::npos) << out;
    EXPECT_NE(out.find("closed after 6 frames"), std::string::npos) << out;
    int w = 0, h = 0, channels = 0;
    stbi_uc* pixels = stbi_load(shot.c_str(), &w, &h, &channels, 4);
    ASSERT_NE(pixels, nullptr) << "no screenshot at " << shot;
    EXPECT_EQ(w, 320);
    EXPECT_EQ(h, 180);
    // The status line: white text on a black box in the top-left corner; below it the scene,
    // which has neither pure white nor pure black.
    size_t white = 0, black = 0, sceneWhite = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const stbi_uc* p = pixels + (size_t(y) * w + x) * 4;
            const bool isWhite = p[0] == 255 && p[1] == 255 && p[2] == 255;
            const bool isBlack = p[0] == 0 && p[1] == 0 && p[2] == 0;
            if (y < 10 && x < 160) {
                white += isWhite;
                black += isBlack;
            } else if (y > 60) {
                sceneWhite += isWhite;
            }
        }
    stbi_image_free(pixels);
    EXPECT_GT(white, 100u) << "no status text";
    EXPECT_GT(black, 100u) << "no status box";
    EXPECT_LT(sceneWhite, size_t(w * h / 100)) << "the scene looks wrong";
}

TEST_F(ViewTest, ClosesWhenTheWindowManagerAsks) {
    auto view = startView({"--size", "160x90", "--samples", "1"});
    ASSERT_TRUE(view->started());
    ASSERT_TRUE(waitForOutput("first frame presented", 300s)) << readFile(errPath());
    ASSERT_EQ(windowTool("close \"motionfx view\""), 0) << readFile(errPath() + ".tool");
    const int status = view->waitFor(60s);
    EXPECT_EQ(status, 0) << "still running (-1) or failed; stderr: " << readFile(errPath());
    EXPECT_NE(readFile(outPath()).find("closed after"), std::string::npos);
}

TEST_F(ViewTest, KeysPauseStepToggleAndQuit) {
    auto view = startView({"--size", "160x90", "--samples", "1"});
    ASSERT_TRUE(view->started());
    ASSERT_TRUE(waitForOutput("first frame presented", 300s)) << readFile(errPath());
    // Each key, then its answer on stdout (looked for after what was there before the key).
    auto press = [&](const std::string& keys, const std::string& answer) {
        const size_t before = outputSoFar();
        EXPECT_EQ(windowTool("keys \"motionfx view\" " + keys), 0);
        return waitForOutput(answer, 60s, before);
    };
    ASSERT_TRUE(press("space", "paused at frame")) << readFile(outPath());
    // Home restarts on frame 1; steps forward and back (back re-simulates from the start).
    ASSERT_TRUE(press("Home", "restarted")) << readFile(outPath());
    ASSERT_TRUE(press("Right", "paused at frame 2")) << readFile(outPath());
    ASSERT_TRUE(press("Right", "paused at frame 3")) << readFile(outPath());
    ASSERT_TRUE(press("Left", "paused at frame 2")) << readFile(outPath());
    ASSERT_TRUE(press("2", "effect 2 (slash arc) hidden")) << readFile(outPath());
    ASSERT_TRUE(press("2", "effect 2 (slash arc) shown")) << readFile(outPath());
    ASSERT_TRUE(press("space", "playing at frame 2")) << readFile(outPath());
    ASSERT_EQ(windowTool("keys \"motionfx view\" Escape"), 0);
    EXPECT_EQ(view->waitFor(60s), 0) << readFile(errPath());
}

// The camera block `p` printed last after the first `from` characters of `out`: position and
// target; false when there is none.
struct PrintedCamera {
    double position[3], target[3], fov;
    double distance() const {
        return std::sqrt(std::pow(position[0] - target[0], 2) +
                         std::pow(position[1] - target[1], 2) +
                         std::pow(position[2] - target[2], 2));
    }
    double yaw() const { return std::atan2(position[0] - target[0], position[2] - target[2]); }
    double pitch() const { return std::asin((position[1] - target[1]) / distance()); }
};
bool lastCamera(const std::string& out, size_t from, PrintedCamera& c) {
    const size_t at = out.rfind("\"camera\": {\"position\": [");
    if (at == std::string::npos || at < from) return false;
    return std::sscanf(out.c_str() + at,
                       "\"camera\": {\"position\": [%lf, %lf, %lf], \"target\": [%lf, %lf, %lf], "
                       "\"fov_degrees\": %lf}",
                       &c.position[0], &c.position[1], &c.position[2], &c.target[0], &c.target[1],
                       &c.target[2], &c.fov) == 7;
}

TEST_F(ViewTest, DragOrbitsWheelZoomsAndShiftDragPansTheCamera) {
    auto view = startView({"--size", "320x180", "--samples", "1", "--paused"});
    ASSERT_TRUE(view->started());
    ASSERT_TRUE(waitForOutput("first frame presented", 300s)) << readFile(errPath());
    const std::string title = "\"motionfx view\"";
    // Sends `words` to the window, then `p`, and reads the camera block printed after them.
    auto cameraAfter = [&](const std::string& words, PrintedCamera& camera) {
        const size_t before = outputSoFar();
        if (!words.empty()) {
            EXPECT_EQ(windowTool(words), 0);
        }
        EXPECT_EQ(windowTool("keys " + title + " p"), 0);
        return waitForOutput("\"fov_degrees\"", 60s, before) &&
               lastCamera(readFile(outPath()), before, camera);
    };
    PrintedCamera start{}, orbited{}, zoomed{}, panned{}, back{};
    ASSERT_TRUE(cameraAfter("", start)) << readFile(outPath());
    // 60 pixels right and 20 down: 0.3 radians of yaw the other way, 0.1 of pitch up.
    ASSERT_TRUE(cameraAfter("drag " + title + " 1 100 80 160 100", orbited)) << readFile(outPath());
    constexpr double perPixel = 0.005;
    EXPECT_NEAR(orbited.yaw(), start.yaw() - 60 * perPixel, 1e-3);
    EXPECT_NEAR(orbited.pitch(), start.pitch() + 20 * perPixel, 1e-3);
    EXPECT_NEAR(orbited.distance(), start.distance(), 1e-3) << "orbiting keeps the distance";
    // Three wheel steps towards the target: 0.9^3 of the distance.
    ASSERT_TRUE(cameraAfter("wheel " + title + " 3", zoomed)) << readFile(outPath());
    EXPECT_NEAR(zoomed.distance(), start.distance() * 0.729, 2e-3);
    EXPECT_NEAR(zoomed.yaw(), orbited.yaw(), 1e-3);
    // A shift drag of 40 pixels moves the target by 40 pixels' world size at its distance, in a
    // picture 180 pixels tall, and keeps the direction.
    ASSERT_TRUE(cameraAfter("drag " + title + " 1 100 80 140 80 shift", panned))
        << readFile(outPath());
    const double moved = std::sqrt(std::pow(panned.target[0] - zoomed.target[0], 2) +
                                   std::pow(panned.target[1] - zoomed.target[1], 2) +
                                   std::pow(panned.target[2] - zoomed.target[2], 2));
    const double expected =
        40.0 * 2.0 * zoomed.distance() * std::tan(zoomed.fov * 3.14159265358979 / 360.0) / 180.0;
    EXPECT_NEAR(moved, expected, 2e-3 + 0.01 * expected);
    EXPECT_NEAR(panned.yaw(), zoomed.yaw(), 1e-3);
    EXPECT_NEAR(panned.distance(), zoomed.distance(), 1e-3);
    // c: the scene's camera again; f: framed on the character (target in its middle).
    ASSERT_TRUE(cameraAfter("keys " + title + " c", back)) << readFile(outPath());
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(back.position[i], start.position[i], 1e-4);
        EXPECT_NEAR(back.target[i], start.target[i], 1e-4);
    }
    PrintedCamera framed{};
    ASSERT_TRUE(cameraAfter("keys " + title + " f", framed)) << readFile(outPath());
    EXPECT_NE(readFile(outPath()).find("framed the character"), std::string::npos);
    EXPECT_GT(framed.target[1], 0.5) << "the middle of a standing fighter is above the floor";
    EXPECT_LT(framed.target[1], 1.4);
    EXPECT_NEAR(framed.yaw(), start.yaw(), 1e-3) << "framing keeps the direction";
    ASSERT_EQ(windowTool("keys " + title + " Escape"), 0);
    EXPECT_EQ(view->waitFor(60s), 0) << readFile(errPath());
}

// A scene of the kick with one wide speed-line effect of colour `colour` ("[r, g, b, a]").
std::string kickLinesScene(const std::string& colour) {
    return R"({
  "character": {"source": "fighter", "clip": "roundhouse_kick"},
  "camera": {"position": [2.0, 1.35, 2.7], "target": [0.05, 0.88, 0], "fov_degrees": 40},
  "output": {"width": 320, "height": 180, "fps": 30, "frames": 21},
  "post": {"bloom": 0, "tone_map": "none"},
  "effects": [
    {"type": "speed_lines", "name": "kick lines", "meshes": ["body"],
     "bones": ["shin_r", "foot_r", "toe_r"], "stride": 4, "lifetime": 12, "width": 0.05,
     "colour": )" +
           colour + R"(}
  ]
}
)";
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

// Pixels of the screenshot at `path` whose colour leans to `lean` (0 red, 1 green, 2 blue: that
// channel over each other one by 60), in rows [y0, y1).
size_t leaning(const std::string& path, int lean, int y0 = 0, int y1 = 100000) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!pixels) return 0;
    size_t count = 0;
    for (int y = std::max(0, y0); y < std::min(h, y1); ++y)
        for (int x = 0; x < w; ++x) {
            const stbi_uc* p = pixels + (size_t(y) * w + x) * 4;
            count += p[lean] > p[(lean + 1) % 3] + 60 && p[lean] > p[(lean + 2) % 3] + 60;
        }
    stbi_image_free(pixels);
    return count;
}
TEST_F(ViewTest, ASavedSceneChangePlaysAtOnceAndABrokenOneKeepsTheLastGoodScene) {
    const std::string dir = outputDir() + "/" + testName();
    std::filesystem::create_directories(dir);
    const std::string file = dir + "/scene.json", shot = dir + "/shot.png";
    const std::string green = "[0.05, 1, 0.05, 1]", blue = "[0.05, 0.2, 1, 1]";
    constexpr int kRed = 0, kGreen = 1, kBlue = 2;
    writeText(file, kickLinesScene(green));
    auto view =
        startView({file, "--size", "320x180", "--samples", "1", "--paused", "--screenshot", shot});
    ASSERT_TRUE(view->started());
    ASSERT_TRUE(waitForOutput("first frame presented", 300s)) << readFile(errPath());
    const std::string title = "\"motionfx view\"";
    auto send = [&](const std::string& words, const std::string& answer) {
        const size_t before = outputSoFar();
        EXPECT_EQ(windowTool(words), 0);
        return waitForOutput(answer, 120s, before);
    };
    auto screenshot = [&] { return send("keys " + title + " s", "screenshot of the window"); };
    // The error line's rows, at the bottom of the window (font scale 1 below 400 pixels).
    constexpr int kErrorTop = 180 - 16;
    // Frame 13, in the middle of the kick, where the lines are long.
    ASSERT_TRUE(send("keys " + title + " Next", "paused at frame 11")) << readFile(outPath());
    ASSERT_TRUE(send("keys " + title + " Right Right", "paused at frame 13"));
    ASSERT_TRUE(screenshot()) << readFile(outPath());
    const size_t green0 = leaning(shot, kGreen);
    EXPECT_GT(green0, 200u) << "green lines drawn";
    EXPECT_LT(leaning(shot, kBlue), green0 / 10) << "and no blue ones";
    const size_t redBottom0 = leaning(shot, kRed, kErrorTop, 180);

    // Saved in place, blue: the next screenshot has blue lines and no green ones, at frame 13.
    size_t before = outputSoFar();
    writeText(file, kickLinesScene(blue));
    ASSERT_TRUE(waitForOutput("reloaded", 120s, before)) << readFile(outPath());
    EXPECT_NE(readFile(outPath()).find("at frame 13", before), std::string::npos)
        << readFile(outPath());
    ASSERT_TRUE(screenshot());
    const size_t blue1 = leaning(shot, kBlue);
    EXPECT_GT(blue1, green0 / 2) << "blue lines where the green ones were";
    EXPECT_LT(leaning(shot, kGreen), blue1 / 10);

    // Broken: the error on stdout and in red at the bottom of the window; the blue scene plays on.
    before = outputSoFar();
    writeText(file, "{\"effects\": [");
    ASSERT_TRUE(waitForOutput("reload failed, playing the last good scene: ", 120s, before))
        << readFile(outPath());
    EXPECT_NE(readFile(outPath()).find(file + ": not valid JSON", before), std::string::npos)
        << "names the file and what is wrong";
    ASSERT_TRUE(screenshot());
    const size_t redBottom = leaning(shot, kRed, kErrorTop, 180);
    EXPECT_GT(redBottom, redBottom0 + 50) << "the error line";
    EXPECT_GT(leaning(shot, kBlue), blue1 / 2) << "still the blue scene";
    EXPECT_EQ(view->waitFor(0s), -1) << "still running";

    // Mended by an editor's save: written to a temporary file and renamed over it.
    before = outputSoFar();
    writeText(dir + "/.scene.json.tmp", kickLinesScene(green));
    std::filesystem::rename(dir + "/.scene.json.tmp", file);
    ASSERT_TRUE(waitForOutput("reloaded", 120s, before)) << readFile(outPath());
    ASSERT_TRUE(screenshot());
    EXPECT_GT(leaning(shot, kGreen), green0 / 2) << "green again";
    EXPECT_LE(leaning(shot, kRed, kErrorTop, 180), redBottom0 + 5) << "the error line is gone";

    // Deleted, then written again: the new file is read.
    before = outputSoFar();
    std::filesystem::remove(file);
    std::this_thread::sleep_for(500ms);
    writeText(file, kickLinesScene(blue));
    ASSERT_TRUE(waitForOutput("reloaded", 120s, before)) << readFile(outPath());
    EXPECT_EQ(readFile(outPath()).find("reload failed", before), std::string::npos)
        << "a file being replaced is waited for";
    ASSERT_TRUE(send("keys " + title + " Escape", "closed after"));
    EXPECT_EQ(view->waitFor(60s), 0) << readFile(errPath());
    EXPECT_GT(leaning(shot, kBlue), blue1 / 2) << "blue again, in the screenshot on closing";
}

// The mean absolute difference per channel between two screenshots over columns [x0, w).
double meanDifference(const std::string& a, const std::string& b, int x0) {
    int w = 0, h = 0, c = 0, w2 = 0, h2 = 0;
    stbi_uc* p = stbi_load(a.c_str(), &w, &h, &c, 4);
    stbi_uc* q = stbi_load(b.c_str(), &w2, &h2, &c, 4);
    double sum = 0.0;
    size_t n = 0;
    if (p && q && w == w2 && h == h2)
        for (int y = 40; y < h; ++y) // below the status lines
            for (int x = x0; x < w; ++x)
                for (int k = 0; k < 3; ++k, ++n)
                    sum += std::abs(int(p[(size_t(y) * w + x) * 4 + k]) -
                                    int(q[(size_t(y) * w + x) * 4 + k]));
    stbi_image_free(p);
    stbi_image_free(q);
    return n ? sum / double(n) : 1e9;
}

TEST_F(ViewTest, ThePanelHidesWithTabAndIsInScreenshotsOnlyWhenAsked) {
    const std::string dir = outputDir() + "/" + testName();
    std::filesystem::create_directories(dir);
    const std::string title = "\"motionfx view\"";
    auto shotOf = [&](std::vector<std::string> extra, const std::string& shot, bool hide) {
        std::vector<std::string> args{"--size",   "800x450",      "--samples", "1",
                                      "--paused", "--screenshot", shot};
        args.insert(args.end(), extra.begin(), extra.end());
        auto view = startView(args);
        EXPECT_TRUE(waitForOutput("first frame presented", 300s)) << readFile(errPath());
        if (hide) {
            const size_t before = outputSoFar();
            EXPECT_EQ(windowTool("keys " + title + " Tab"), 0);
            EXPECT_TRUE(waitForOutput("panel hidden", 60s, before)) << readFile(outPath());
        }
        EXPECT_EQ(windowTool("keys " + title + " Escape"), 0);
        EXPECT_EQ(view->waitFor(60s), 0) << readFile(errPath());
    };
    const std::string withPanel = dir + "/with_panel.png", hidden = dir + "/hidden.png",
                      plain = dir + "/plain.png";
    shotOf({"--screenshot-panel"}, withPanel, false);
    shotOf({"--screenshot-panel"}, hidden, true);
    shotOf({}, plain, false);
    // The panel covers the right of the window (400 pixels): there the picture with it differs
    // from the one without; a screenshot not asked to show it is the picture without it.
    EXPECT_GT(meanDifference(withPanel, hidden, 800 - 380), 10.0) << "no panel drawn";
    EXPECT_LT(meanDifference(plain, hidden, 800 - 380), 1.0) << "the panel is in the screenshot";
}

} // namespace
