// Command-line parsing for motionfx's subcommands: long options only ("--name value",
// "--name=value", flags), positionals, and one-line errors for anything unexpected.
#pragma once

#include "core/result.h"

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace mfx::cli {

struct OptionSpec {
    std::string name;      // without the leading "--"
    std::string valueName; // empty: a flag without a value
    std::string help;
};

struct ParsedArgs {
    std::map<std::string, std::string> values;
    std::set<std::string> flags;
    std::vector<std::string> positional;

    bool has(const std::string& name) const { return flags.count(name) || values.count(name); }
    std::string value(const std::string& name, const std::string& fallback = {}) const {
        auto it = values.find(name);
        return it == values.end() ? fallback : it->second;
    }
};

// Parses `args` (the words after the subcommand) against `options`; at most `maxPositional`
// positionals. "--help" is always accepted as a flag.
Result<ParsedArgs> parseArgs(std::span<const std::string> args, std::span<const OptionSpec> options,
                             size_t maxPositional);

// "WxH" with 1 ≤ W, H ≤ maxDimension.
Result<std::pair<uint32_t, uint32_t>> parseSize(const std::string& text, uint32_t maxDimension);

// "NXxNYxNZ" with 1 <= each <= maxDimension, e.g. "64x64x64" or "96x64x48".
Result<std::array<uint32_t, 3>> parseGrid(const std::string& text, uint32_t maxDimension);

// A whole number in [minimum, maximum]; `what` names the option in the error.
Result<uint32_t> parseUnsigned(const std::string& text, uint32_t minimum, uint32_t maximum,
                               const std::string& what);

// A finite number in [minimum, maximum] (NaN and infinities are refused).
Result<double> parseNumber(const std::string& text, double minimum, double maximum,
                           const std::string& what);

// The options block of a help text.
std::string describeOptions(std::span<const OptionSpec> options);

} // namespace mfx::cli
