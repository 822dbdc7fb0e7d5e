// The shape of untrusted JSON text, measured before it is parsed: how deeply its arrays and objects
// nest and about how many values it holds. Parsers and the code that walks their trees recurse
// once per level (a copy of a value, tinygltf's `extras`), and every value costs a node of memory,
// so a file must be refused on these two numbers before any of that runs: a megabyte of '[' would
// overflow the stack, and a file of empty arrays asks for many times its size.
#pragma once

#include "core/result.h"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace mfx {

struct JsonShape {
    int depth = 0;     // the deepest nesting of arrays and objects (a bare scalar: 0)
    size_t values = 0; // the values, each once (an empty array or object twice): a bound from above
};

// Measures `text` without parsing it; brackets and commas inside strings do not count. Malformed
// text is measured as far as it goes (the parser refuses it afterwards).
JsonShape measureJson(std::span<const unsigned char> text);

struct JsonLimits {
    int maxDepth = 64;
    size_t maxValues = 1u << 20;
};

// Ok, or one reason naming the limit the text passes ("nests deeper than 64 levels").
Status checkJsonShape(std::span<const unsigned char> text, const JsonLimits& limits);
Status checkJsonShape(std::string_view text, const JsonLimits& limits);

} // namespace mfx
