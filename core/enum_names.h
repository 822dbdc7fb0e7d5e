// An enum's names as one table of {value, name} pairs (the command line, the statistics and the
// file formats spell values by name): nameOf finds a value's name, valueOf the value of a name.
// One table serves both directions, so they cannot disagree.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

namespace mfx {

template <class E>
using NamedValue = std::pair<E, const char*>;

template <class E, size_t N>
const char* nameOf(E value, const NamedValue<E> (&table)[N], const char* unknown = "?") {
    for (const auto& [v, name] : table)
        if (v == value) return name;
    return unknown;
}

template <class E, size_t N>
std::optional<E> valueOf(std::string_view name, const NamedValue<E> (&table)[N]) {
    for (const auto& [v, n] : table)
        if (name == n) return v;
    return std::nullopt;
}

} // namespace mfx
