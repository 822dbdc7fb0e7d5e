// OpenVDB export of a smoke grid's fields (Debian's libopenvdb-dev): one .vdb a frame, read by
// Blender's volume import, Houdini and OpenVDB's own tools. What a file holds:
//   "density"  float, the pigment's alpha, a fog volume;
//   "colour"   vec3, the pigment's colour, rgb / alpha as the smoke renderer takes it
//              (shaders/render/smoke_march.glsl);
//   "velocity" vec3, the cell-centred velocity (the mean of each cell's two faces per axis), in
//              world units a second;
//   "solid"    float, 1 in the cells a moving solid fills (a scene's "collide": the character's
//              body), a fog volume Blender and Houdini take as a collider; only when the frame
//              has solids.
// Voxel (i, j, k) is cell (i, j, k) of the grid; the transform takes it to the cell's centre in
// world units (the scene's metres): a scale by the cell size, then the grid's low corner plus half
// a cell, and with VdbUp::Z the turn from the scene's y-up axes to z-up ones (x, y, z) ->
// (x, -z, y), as Blender's glTF import turns the character. The grids are sparse: a voxel is
// active where the cell holds pigment (alpha > 0), in all three grids (the velocity of the smoke,
// not of the clear air around it), and only among the stored cells of a sparse domain.
#pragma once

#include "core/result.h"
#include "fluid/solver_options.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace mfx::fluid {

enum class VdbUp { Y, Z };

struct VdbFrame {
    const FieldState* state = nullptr;
    glm::vec3 origin{0.0f}; // the world position of the grid's low corner
    // One flag per cell (x fastest) of a sparse domain's stored cells; empty: every cell.
    const std::vector<uint8_t>* storedCells = nullptr;
    // One flag per cell (x fastest): the solid cells; null or empty: no "solid" grid.
    const std::vector<uint8_t>* solidCells = nullptr;
    VdbUp up = VdbUp::Y;
};

// Whether this build writes .vdb files (it does when OpenVDB was found at configure time).
bool vdbAvailable();

// Writes `path` (replacing it). Errors name the file and what failed.
Status writeVdb(const std::string& path, const VdbFrame& frame);

} // namespace mfx::fluid
