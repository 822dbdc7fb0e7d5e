// Progress of long runs on stderr: a bar redrawn in place on a terminal, plain lines (every tenth
// of the way) otherwise, so logs stay readable.
#pragma once

#include <cstdint>
#include <string>

namespace mfx::app {

class Progress {
public:
    Progress(std::string what, uint32_t total);
    void update(uint32_t done, const std::string& note = {}); // done of total
    void finish(const std::string& note = {});

private:
    std::string what_;
    uint32_t total_ = 0;
    bool terminal_ = false;
    uint32_t lastTenth_ = 0;
};

} // namespace mfx::app
