#include "fluid/grid.h"

#include <cmath>

namespace mfx::fluid {

std::string toString(const GridShape& grid) {
    return std::to_string(grid.cellsX) + "x" + std::to_string(grid.cellsY) + "x" +
           std::to_string(grid.cellsZ);
}

Status validateGrid(const GridShape& grid, uint32_t maxDimension) {
    const uint32_t cells[3] = {grid.cellsX, grid.cellsY, grid.cellsZ};
    const char* axes[3] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis) {
        if (cells[axis] < 1)
            return Error{"grid " + toString(grid) + ": the " + axes[axis] +
                         " dimension must be at least 1 cell"};
        if (cells[axis] > maxDimension)
            return Error{"grid " + toString(grid) + ": the " + axes[axis] + " dimension exceeds " +
                         std::to_string(maxDimension) + ", the device's largest 3D image"};
    }
    if (!std::isfinite(grid.cellSize) || grid.cellSize <= 0.0f)
        return Error{"grid cell size must be a positive finite number, got " +
                     std::to_string(grid.cellSize)};
    return Ok{};
}

} // namespace mfx::fluid
