#include "apps/progress.h"

#include <cstdio>
#include <unistd.h>

namespace mfx::app {

Progress::Progress(std::string what, uint32_t total)
    : what_(std::move(what)), total_(total), terminal_(isatty(fileno(stderr)) != 0) {}

void Progress::update(uint32_t done, const std::string& note) {
    if (total_ == 0) return;
    if (terminal_) {
        constexpr int width = 30;
        const int filled = int(uint64_t(width) * done / total_);
        std::fprintf(stderr, "\r%s [%s%s] %u/%u %s\033[K", what_.c_str(),
                     std::string(size_t(filled), '#').c_str(),
                     std::string(size_t(width - filled), '.').c_str(), done, total_, note.c_str());
        std::fflush(stderr);
        return;
    }
    const uint32_t tenth = uint32_t(uint64_t(10) * done / total_);
    if (tenth > lastTenth_ || done == total_) {
        lastTenth_ = tenth;
        std::fprintf(stderr, "%s: %u/%u %s\n", what_.c_str(), done, total_, note.c_str());
    }
}

void Progress::finish(const std::string& note) {
    if (terminal_) std::fprintf(stderr, "\r%s: done %s\033[K\n", what_.c_str(), note.c_str());
}

} // namespace mfx::app
