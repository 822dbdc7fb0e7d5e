// For the tests of the scene's parameter table: the contexts that describe every key of an effect
// kind (the keys some kinds read depend on a choice, as an afterimage's on its variant).
#pragma once

#include "core/scene/scene_params.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mfx::test {

// {} and, for each choice key of `type` but "type", one object per choice giving it.
inline std::vector<nlohmann::json> choiceContexts(const std::string& type) {
    std::vector<nlohmann::json> contexts{nlohmann::json::object()};
    for (const scene::ParamInfo& p : scene::effectParams(type))
        if (p.type == scene::ParamInfo::Type::Choice && p.key != "type")
            for (const std::string& c : p.choices)
                contexts.push_back(nlohmann::json{{p.key, c}});
    return contexts;
}

} // namespace mfx::test
