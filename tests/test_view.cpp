// motionfx view under a virtual X server (Xvfb): it opens a window, presents frames with the
// status line drawn on them, answers keys, and closes when the window manager asks it to
// (WM_DELETE_WINDOW, sent by tests/x11_window_tool.cpp) or after --quit-after frames.
#include <chrono>
#include <csignal>
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

} // namespace
