// Benchmark tables as Markdown (--markdown FILE): each benchmark run writes one section, headed
// by what was measured, the device and driver, the date and the command that reproduces it, into
// a file such as docs/performance.md. A section is found again by its key (the benchmark, the
// device and the command): a rerun replaces its own section and leaves the others, so tables
// measured on different machines live side by side.
#pragma once

#include "apps/cli.h"
#include "core/result.h"

#include <string>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::app {

struct MarkdownTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::string text() const; // the pipe table, one line a row
};

// "motionfx <command> --option value ..." from the parsed arguments, leaving out the options that
// only name output files (json, markdown, plot).
std::string reproduceCommand(const std::string& command, const cli::ParsedArgs& parsed);

// Today's date (UTC), YYYY-MM-DD.
std::string todayUtc();

// Whether `path` can take the sections: a regular file of at most 16 MiB (read whole, then
// rewritten), or one that can be made. Checked before a benchmark runs, so a bad path is refused at
// once, in one line naming it.
Status checkMarkdownFile(const std::string& path);

// Replaces (or appends) the section of `title` measured on ctx's device by `command` in the file
// at `path` (created if missing) with `body` under a heading of the title, the device, the driver,
// the date and the command. The error names the file.
Status writeMarkdownSection(const std::string& path, const std::string& title,
                            const gpu::Context& ctx, const std::string& command,
                            const std::string& body);

// "%.*f" as a string.
std::string fixed(double value, int decimals);

} // namespace mfx::app
