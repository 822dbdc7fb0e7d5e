// Watching files for a viewer's hot reload, by polling their status (size, modification time,
// inode): no platform notification API, so it behaves the same for every way an editor saves.
//   * a save written in several pieces, or two saves in a row, is reported once, after the files
//     have stayed the same for `settle`, so the reader sees the last, whole file;
//   * a write to a temporary file renamed over the watched one changes the inode: reported;
//   * a deleted file is waited for: nothing is reported until it exists again (an editor that
//     deletes and then re-creates the file), and then its new contents are.
#pragma once

#include <chrono>
#include <filesystem>
#include <vector>

namespace mfx::app {

class FileWatch {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr std::chrono::milliseconds kSettle{150};

    // Watches `files` (the empty paths among them are skipped) as they are now.
    void watch(std::vector<std::filesystem::path> files);
    // True once for each settled change since the last report (or since watch()), checked at
    // `now`; call it as often as convenient (every frame).
    bool poll(Clock::time_point now = Clock::now(), Clock::duration settle = kSettle);
    const std::vector<std::filesystem::path>& files() const { return files_; }

private:
    struct Stamp {
        bool exists = false;
        unsigned long long size = 0, inode = 0, device = 0;
        long long modifiedNs = 0, changedNs = 0;
        bool operator==(const Stamp&) const = default;
    };
    static Stamp stamp(const std::filesystem::path& file);
    std::vector<Stamp> stamps() const;

    std::vector<std::filesystem::path> files_;
    std::vector<Stamp> reported_; // as last reported (or watched)
    std::vector<Stamp> seen_;     // as last seen
    Clock::time_point seenSince_{};
};

} // namespace mfx::app
