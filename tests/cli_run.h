// Running the motionfx program from a test, as a user would: its exit code, stdout and stderr
// (kept under the test output folder, named after the test).
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace mfx::test {

struct RunResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

inline std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Runs motionfx with `arguments` (shell words) and optional environment assignments before it.
inline RunResult runMotionfx(const std::string& arguments, const std::string& environment = "") {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli";
    std::filesystem::create_directories(dir);
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_'); // parameterised tests: "Test/param"
    const std::string outPath = dir + "/" + name + ".stdout";
    const std::string errPath = dir + "/" + name + ".stderr";
    const std::string command = environment + " \"" + MFX_MOTIONFX_PATH + "\" " + arguments +
                                " >\"" + outPath + "\" 2>\"" + errPath + "\"";
    const int status = std::system(command.c_str());
    RunResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = readFile(outPath);
    result.err = readFile(errPath);
    return result;
}

inline size_t lineCount(const std::string& text) {
    size_t lines = 0;
    for (char c : text)
        lines += c == '\n';
    return lines + (!text.empty() && text.back() != '\n');
}

} // namespace mfx::test
