#include "core/json_shape.h"

#include <algorithm>

namespace mfx {

JsonShape measureJson(std::span<const unsigned char> text) {
    JsonShape shape;
    int depth = 0;
    bool inString = false;
    bool escaped = false;
    bool anything = false;
    for (unsigned char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        switch (c) {
        case '"':
            inString = true;
            anything = true;
            break;
        case '[':
        case '{':
            shape.depth = std::max(shape.depth, ++depth);
            ++shape.values;
            break;
        case ']':
        case '}':
            depth = std::max(depth - 1, 0);
            break;
        case ',':
            ++shape.values;
            break;
        case ' ':
        case '\t':
        case '\n':
        case '\r':
            break;
        default:
            anything = true;
        }
    }
    // Each container counts itself and each ',' one member after its first; the one more below
    // stands for the root, so every value is counted once and an empty array or object twice
    // (a bound from above: an empty container still costs a node).
    if (anything || shape.values > 0) ++shape.values;
    return shape;
}

Status checkJsonShape(std::span<const unsigned char> text, const JsonLimits& limits) {
    const JsonShape shape = measureJson(text);
    if (shape.depth > limits.maxDepth)
        return Error{"the JSON nests deeper than " + std::to_string(limits.maxDepth) +
                     " levels of arrays and objects"};
    if (shape.values > limits.maxValues)
        return Error{"the JSON holds more than " + std::to_string(limits.maxValues) +
                     " values (about " + std::to_string(shape.values) + ")"};
    return Ok{};
}

Status checkJsonShape(std::string_view text, const JsonLimits& limits) {
    return checkJsonShape(std::span<const unsigned char>(
                              reinterpret_cast<const unsigned char*>(text.data()), text.size()),
                          limits);
}

} // namespace mfx
