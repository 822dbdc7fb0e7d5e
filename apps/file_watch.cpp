#include "apps/file_watch.h"

#include <algorithm>
#include <sys/stat.h>

namespace mfx::app {

FileWatch::Stamp FileWatch::stamp(const std::filesystem::path& file) {
    struct stat info {};
    Stamp s;
    if (::stat(file.c_str(), &info) != 0) return s;
    s.exists = true;
    s.size = static_cast<unsigned long long>(info.st_size);
    s.inode = static_cast<unsigned long long>(info.st_ino);
    s.device = static_cast<unsigned long long>(info.st_dev);
    s.modifiedNs =
        static_cast<long long>(info.st_mtim.tv_sec) * 1000000000LL + info.st_mtim.tv_nsec;
    s.changedNs = static_cast<long long>(info.st_ctim.tv_sec) * 1000000000LL + info.st_ctim.tv_nsec;
    return s;
}

std::vector<FileWatch::Stamp> FileWatch::stamps() const {
    std::vector<Stamp> out;
    out.reserve(files_.size());
    for (const std::filesystem::path& file : files_)
        out.push_back(stamp(file));
    return out;
}

void FileWatch::watch(std::vector<std::filesystem::path> files) {
    files.erase(std::remove_if(files.begin(), files.end(),
                               [](const std::filesystem::path& f) { return f.empty(); }),
                files.end());
    files_ = std::move(files);
    reported_ = seen_ = stamps();
    seenSince_ = Clock::time_point{};
}

bool FileWatch::poll(Clock::time_point now, Clock::duration settle) {
    std::vector<Stamp> current = stamps();
    if (current != seen_) { // still changing: wait until it has been still for `settle`
        seen_ = std::move(current);
        seenSince_ = now;
        return false;
    }
    if (seen_ == reported_ || now - seenSince_ < settle) return false;
    // A missing file is being replaced: wait for it.
    if (std::any_of(seen_.begin(), seen_.end(), [](const Stamp& s) { return !s.exists; }))
        return false;
    reported_ = seen_;
    return true;
}

} // namespace mfx::app
