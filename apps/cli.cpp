#include "apps/cli.h"

#include <algorithm>
#include <charconv>

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
