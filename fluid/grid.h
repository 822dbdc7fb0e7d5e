// The simulation grid's shape: cell counts per axis and the cell size in world units. Velocity
// lives on the faces of a staggered (MAC) grid, pressure and pigment at cell centres
// (docs/architecture.md "Numerics"); this header only describes and checks the shape.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <string>

namespace mfx::fluid {

struct GridShape {
    uint32_t cellsX = 64;
    uint32_t cellsY = 64;
    uint32_t cellsZ = 64;
    float cellSize = 1.0f / 64.0f; // world units per cell

    uint64_t cellCount() const { return uint64_t(cellsX) * cellsY * cellsZ; }
    // Linear index of cell (x, y, z), x fastest.
    uint64_t index(uint32_t x, uint32_t y, uint32_t z) const {
        return x + uint64_t(cellsX) * (y + uint64_t(cellsY) * z);
    }
};

// "64x64x64"
std::string toString(const GridShape& grid);

// Checks that every dimension is at least 1 and at most `maxDimension` (the device's
// maxImageDimension3D), and that the cell size is finite and positive. The error names the
// offending value.
Status validateGrid(const GridShape& grid, uint32_t maxDimension);

} // namespace mfx::fluid
