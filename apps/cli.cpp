#include "apps/cli.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace mfx::cli {

Result<ParsedArgs> parseArgs(std::span<const std::string> args, std::span<const OptionSpec> options,
                             size_t maxPositional) {
    ParsedArgs parsed;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& word = args[i];
        if (word.rfind("--", 0) != 0 || word == "--") {
            if (word.size() > 1 && word[0] == '-' && word != "-")
                return Error{"unknown option '" + word + "' (options are long: --name)"};
            if (parsed.positional.size() >= maxPositional)
                return Error{"unexpected argument '" + word + "'"};
            parsed.positional.push_back(word);
            continue;
        }
        std::string name = word.substr(2);
        std::string value;
        bool inlineValue = false;
        if (const size_t eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            inlineValue = true;
        }
        if (name == "help") {
            parsed.flags.insert("help");
            continue;
        }
        auto spec = std::find_if(options.begin(), options.end(),
                                 [&](const OptionSpec& o) { return o.name == name; });
        if (spec == options.end()) return Error{"unknown option '--" + name + "'"};
        if (spec->valueName.empty()) {
            if (inlineValue) return Error{"option '--" + name + "' takes no value"};
            parsed.flags.insert(name);
            continue;
        }
        if (!inlineValue) {
            if (i + 1 >= args.size())
                return Error{"option '--" + name + "' needs a value (" + spec->valueName + ")"};
            value = args[++i];
        }
        if (value.empty())
            return Error{"option '--" + name + "' needs a non-empty value (" + spec->valueName +
                         ")"};
        if (parsed.values.count(name)) return Error{"option '--" + name + "' is given twice"};
        parsed.values[name] = value;
    }
    return parsed;
}

Result<std::pair<uint32_t, uint32_t>> parseSize(const std::string& text, uint32_t maxDimension) {
    const size_t x = text.find('x');
    auto parse = [&](std::string_view part, uint32_t& out) {
        if (part.empty()) return false;
        auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), out);
        return error == std::errc() && end == part.data() + part.size();
    };
    uint32_t width = 0;
    uint32_t height = 0;
    if (x == std::string::npos || !parse(std::string_view(text).substr(0, x), width) ||
        !parse(std::string_view(text).substr(x + 1), height))
        return Error{"size '" + text + "' is not of the form WIDTHxHEIGHT, e.g. 1280x720"};
    if (width == 0 || height == 0 || width > maxDimension || height > maxDimension)
        return Error{"size '" + text + "': width and height must be between 1 and " +
                     std::to_string(maxDimension)};
    return std::pair{width, height};
}

Result<std::array<uint32_t, 3>> parseGrid(const std::string& text, uint32_t maxDimension) {
    std::array<uint32_t, 3> cells{};
    size_t start = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const size_t end = axis < 2 ? text.find('x', start) : text.size();
        if (end == std::string::npos) break;
        const std::string_view part = std::string_view(text).substr(start, end - start);
        auto [ptr, error] = std::from_chars(part.data(), part.data() + part.size(), cells[axis]);
        if (part.empty() || error != std::errc() || ptr != part.data() + part.size())
            return Error{"grid '" + text + "' is not of the form NXxNYxNZ, e.g. 64x64x64"};
        start = end + 1;
        if (axis == 2) {
            for (uint32_t n : cells)
                if (n < 1 || n > maxDimension)
                    return Error{"grid '" + text + "': each dimension must be between 1 and " +
                                 std::to_string(maxDimension)};
            return cells;
        }
    }
    return Error{"grid '" + text + "' is not of the form NXxNYxNZ, e.g. 64x64x64"};
}

Result<uint32_t> parseUnsigned(const std::string& text, uint32_t minimum, uint32_t maximum,
                               const std::string& what) {
    uint32_t value = 0;
    auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || ptr != text.data() + text.size() ||
        value < minimum || value > maximum)
        return Error{what + " '" + text + "' must be a whole number from " +
                     std::to_string(minimum) + " to " + std::to_string(maximum)};
    return value;
}

Result<double> parseNumber(const std::string& text, double minimum, double maximum,
                           const std::string& what) {
    double value = 0.0;
    auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || ptr != text.data() + text.size())
        return Error{what + " '" + text + "' is not a number"};
    if (!std::isfinite(value)) return Error{what + " '" + text + "' must be finite"};
    if (value < minimum || value > maximum)
        return Error{what + " '" + text + "' must be between " + std::to_string(minimum) + " and " +
                     std::to_string(maximum)};
    return value;
}

std::string describeOptions(std::span<const OptionSpec> options) {
    std::string text = "options:\n";
    size_t width = 6;
    for (const OptionSpec& o : options)
        width = std::max(width, o.name.size() + (o.valueName.empty() ? 0 : o.valueName.size() + 1));
    auto line = [&](const std::string& left, const std::string& help) {
        text += "  --" + left + std::string(width + 2 - left.size(), ' ') + help + "\n";
    };
    for (const OptionSpec& o : options)
        line(o.name + (o.valueName.empty() ? "" : " " + o.valueName), o.help);
    line("help", "show this help");
    return text;
}

} // namespace mfx::cli
