// The registry of effect kinds (docs/architecture.md, "Adding an effect kind"): every kind a scene
// file's "type" may name, with its own keys and its parser. Adding a kind means one line in
// effect_kinds.cpp; its spec and parser are in their own file (core/scene/kinds/).
#pragma once

#include "core/scene/effect_spec.h"

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mfx::scene {

namespace detail {
class Object;
}

struct EffectKindEntry {
    const char* type;              // the scene file's "type"
    std::vector<std::string> keys; // its own keys, besides those every effect has
    // Reads and checks its keys, over its defaults (throws detail::SceneError naming the key).
    std::unique_ptr<EffectKindSpec> (*parse)(const detail::Object& o);
};

// Every kind, in the order the scene documentation lists them.
std::span<const EffectKindEntry> effectKinds();

// The keys every effect has (the common spec: name, window, source selection).
const std::vector<std::string>& commonEffectKeys();

namespace detail {
// Effect `index` of the file from `o`: its type, the common keys, and its kind's own keys with
// their defaults; a key of another kind, or of none, is refused naming its path.
EffectSpec readEffect(const Object& o, size_t index);
} // namespace detail

} // namespace mfx::scene
