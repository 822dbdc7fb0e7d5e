// A step's stages and their dispatch counts, as the dense and sparse solvers report them
// (lastStepDispatches): an entry per stage in recording order.
#pragma once

#include "fluid/stage_table.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace mfx::fluid {

using StageDispatches = std::vector<std::pair<std::string, uint32_t>>;

// Adds `count` dispatches to `stage`'s entry, appending the entry the first time.
inline void countStageDispatches(StageDispatches& list, Stage stage, uint32_t count) {
    const std::string name = stageName(stage);
    auto it = std::find_if(list.begin(), list.end(),
                           [&](const auto& entry) { return entry.first == name; });
    if (it == list.end())
        list.emplace_back(name, count);
    else
        it->second += count;
}

} // namespace mfx::fluid
