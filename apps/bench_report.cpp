#include "apps/bench_report.h"

#include "core/gpu/context.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace mfx::app {

std::string MarkdownTable::text() const {
    auto line = [](const std::vector<std::string>& cells) {
        std::string out = "|";
        for (const std::string& cell : cells)
            out += " " + cell + " |";
        return out + "\n";
    };
    std::string out = line(header) + "|";
    for (size_t i = 0; i < header.size(); ++i)
        out += i == 0 ? "---|" : "---:|";
    out += "\n";
    for (const auto& row : rows)
        out += line(row);
    return out;
}

std::string reproduceCommand(const std::string& command, const cli::ParsedArgs& parsed) {
    std::string out = "motionfx " + command;
    for (const std::string& word : parsed.positional)
        out += " " + word;
    for (const auto& [name, value] : parsed.values)
        if (name != "json" && name != "markdown" && name != "plot")
            out += " --" + name + " " +
                   (value.find_first_of(" \t'\"") == std::string::npos ? value : "'" + value + "'");
    for (const std::string& flag : parsed.flags)
        out += " --" + flag;
    return out;
}

std::string todayUtc() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[16];
    std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
    return text;
}

Status checkMarkdownFile(const std::string& path) {
    constexpr std::uintmax_t kMaxBytes = 16u << 20;
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (std::filesystem::exists(status)) {
        if (!std::filesystem::is_regular_file(status))
            return Error{path + ": not a regular file; the Markdown tables need one"};
        const std::uintmax_t size = std::filesystem::file_size(path, error);
        if (error || size > kMaxBytes)
            return Error{path +
                         ": larger than 16 MiB; the Markdown tables rewrite their file whole"};
    }
    // Opened to append: nothing of it changes yet.
    std::ofstream probe(path, std::ios::app);
    if (!probe) return Error{path + ": cannot write the Markdown tables"};
    return Ok{};
}

Status writeMarkdownSection(const std::string& path, const std::string& title,
                            const gpu::Context& ctx, const std::string& command,
                            const std::string& body) {
    if (Status ok = checkMarkdownFile(path); !ok) return ok;
    const std::string key = title + " | " + ctx.info().name + " | " + command;
    const std::string begin = "<!-- begin: " + key + " -->\n";
    const std::string end = "<!-- end: " + key + " -->\n";
    std::string text;
    if (std::ifstream in(path); in) {
        std::stringstream all;
        all << in.rdbuf();
        text = all.str();
    }
    const std::string section = begin + "### " + title + " — " + ctx.info().name + "\n\n" +
                                "Measured " + todayUtc() + " on " + ctx.info().name + " (" +
                                ctx.info().driverInfo + ") by `" + command + "`.\n\n" + body +
                                (body.empty() || body.back() == '\n' ? "" : "\n") + end;
    const size_t first = text.find(begin);
    const size_t last = first == std::string::npos ? first : text.find(end, first);
    if (first != std::string::npos && last != std::string::npos) {
        text.replace(first, last + end.size() - first, section);
    } else {
        if (!text.empty() && text.back() != '\n') text += "\n";
        if (!text.empty()) text += "\n";
        text += section;
    }
    std::ofstream out(path, std::ios::trunc);
    if (!out) return Error{path + ": cannot write the Markdown tables"};
    out << text;
    if (!out) return Error{path + ": writing the Markdown tables failed"};
    return Ok{};
}

std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

} // namespace mfx::app
