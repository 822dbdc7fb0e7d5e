// Reading one effect of a scene file (internal to core/scene; effect_keys.cpp).
#pragma once

#include "core/scene/json_object.h"
#include "core/scene/scene.h"

#include <cstddef>

namespace mfx::scene::detail {

// Effect `index` of the file from `o` into `e`: its type, the common keys, and its kind's own
// keys with their defaults; a key of another kind, or of none, is refused naming its path.
void readEffect(const Object& o, size_t index, EffectSpec& e);

} // namespace mfx::scene::detail
