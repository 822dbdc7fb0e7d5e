// The viewer's file watch (apps/file_watch.h): a change is reported once, after the file has
// stayed the same for the settling time, whatever way it was saved: in place, twice in a row,
// written to a temporary file and renamed over, or deleted and written again. The clock is
// passed in, so nothing here sleeps.
#include "apps/file_watch.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace mfx::test {
namespace {

using namespace std::chrono_literals;
using app::FileWatch;

std::filesystem::path watchDir() {
    const std::filesystem::path dir =
        std::filesystem::path(MFX_TEST_OUTPUT_DIR) / "file_watch" /
        ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

void write(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
}

// Polls at `t` and returns how many reports the polls at t, t + 100 ms, ... t + 500 ms gave.
int reportsOver(FileWatch& watch, FileWatch::Clock::time_point t) {
    int reports = 0;
    for (int i = 0; i <= 5; ++i)
        reports += watch.poll(t + i * 100ms) ? 1 : 0;
    return reports;
}

TEST(FileWatch, ReportsNothingWhileTheFileIsUnchanged) {
    const auto file = watchDir() / "scene.json";
    write(file, "{}");
    FileWatch watch;
    watch.watch({file, {}});
    EXPECT_EQ(watch.files().size(), 1u) << "the empty path is not watched";
    EXPECT_EQ(reportsOver(watch, FileWatch::Clock::now()), 0);
}

TEST(FileWatch, ReportsASaveOnceAfterItSettles) {
    const auto file = watchDir() / "scene.json";
    write(file, "{}");
    FileWatch watch;
    watch.watch({file});
    const auto t = FileWatch::Clock::now();
    write(file, "{\"effects\": []}");
    EXPECT_FALSE(watch.poll(t)) << "just seen: not settled";
    EXPECT_FALSE(watch.poll(t + 100ms)) << "inside the settling time";
    EXPECT_TRUE(watch.poll(t + 200ms));
    EXPECT_EQ(reportsOver(watch, t + 300ms), 0) << "reported once";
}

TEST(FileWatch, TwoSavesInARowAreReportedOnceForTheLast) {
    const auto file = watchDir() / "scene.json";
    write(file, "{}");
    FileWatch watch;
    watch.watch({file});
    const auto t = FileWatch::Clock::now();
    write(file, "{\"a\": 1}");
    EXPECT_FALSE(watch.poll(t));
    write(file, "{\"a\": 12}");
    EXPECT_FALSE(watch.poll(t + 100ms)) << "changed again: the settling time starts again";
    EXPECT_FALSE(watch.poll(t + 200ms));
    EXPECT_TRUE(watch.poll(t + 300ms));
    EXPECT_EQ(reportsOver(watch, t + 400ms), 0);
}

TEST(FileWatch, ARenameOverTheFileIsReported) {
    const auto dir = watchDir();
    const auto file = dir / "scene.json";
    write(file, "{\"a\": 1}");
    FileWatch watch;
    watch.watch({file});
    write(dir / ".scene.json.tmp", "{\"a\": 2}"); // the same size
    std::filesystem::rename(dir / ".scene.json.tmp", file);
    EXPECT_EQ(reportsOver(watch, FileWatch::Clock::now()), 1);
}

TEST(FileWatch, ADeletedFileIsWaitedForAndItsNewContentsReported) {
    const auto file = watchDir() / "scene.json";
    write(file, "{}");
    FileWatch watch;
    watch.watch({file});
    std::filesystem::remove(file);
    const auto t = FileWatch::Clock::now();
    EXPECT_EQ(reportsOver(watch, t), 0) << "gone: nothing to read yet";
    write(file, "{\"b\": 2}");
    EXPECT_EQ(reportsOver(watch, t + 1s), 1);
}

TEST(FileWatch, AChangeToAnyWatchedFileIsReported) {
    const auto dir = watchDir();
    write(dir / "scene.json", "{}");
    write(dir / "character.gltf", "{}");
    FileWatch watch;
    watch.watch({dir / "scene.json", dir / "character.gltf"});
    write(dir / "character.gltf", "{\"asset\": {}}");
    EXPECT_EQ(reportsOver(watch, FileWatch::Clock::now()), 1);
}

} // namespace
} // namespace mfx::test
