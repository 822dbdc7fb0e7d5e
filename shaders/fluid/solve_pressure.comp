// solvePressure: one Jacobi sweep of sum over counted neighbours of (p_n - p) = h² div,
// p <- (sum of counted neighbour pressures - h² div) / count; walls are not counted, open faces
// count with p = 0, periodic ones wrap (docs/fluid.md). Twin: fluid/reference/solve_pressure.cpp.
//
// Each invocation updates a brick of 4 (x) by kPressureRows (y) by kPressureLayers (z) cells: a
// row of four cells is a vec4, its x neighbours are the row shifted by one, its y neighbours the
// brick's other rows (plus one row either side), and the layers below and above slide along z,
// so that every loaded pressure serves several cells. Between the first and the last sweep of a
// solve, pressure and divergence live packed in storage buffers, four x-consecutive cells per
// vec4 (element X + ceil(nx / 4) * (y + ny * z) holds cells 4X..4X+3 of row (y, z); past the
// last cell it holds padding that no cell reads): on a CPU driver a buffer store costs far less
// than an image store, and a row is one load and one store. kPressureMode says which side is
// packed (bit 0: the input, bit 1: the output; the first sweep also packs the divergence) and
// whether the input is 0 (bit 2: a cold start's first sweep, which then reads no pressure: the
// solver clears no image for it).
// Every cell still sums its neighbours in the reference's order (-x, +x, -y, +y, -z, +z), so the
// result is the same whatever the brick, the packing or the workgroup shape.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"
#include "jacobi_neighbours.glsl"

layout(binding = 1, r32f) uniform readonly image3D divergence;
layout(binding = 2, MFX_PRESSURE_FORMAT) uniform readonly image3D pressureIn;
layout(binding = 3, MFX_PRESSURE_FORMAT) uniform writeonly image3D pressureOut;
layout(std430, binding = 4) buffer PackedDivergence {
    vec4 packedDivergence[];
};
layout(std430, binding = 5) readonly buffer PackedIn {
    vec4 packedIn[];
};
layout(std430, binding = 6) writeonly buffer PackedOut {
    vec4 packedOut[];
};
// The same buffer as PackedIn, cell by cell (the x neighbours at a brick's ends).
layout(std430, binding = 7) readonly buffer PackedInCells {
    float packedInCells[];
};

// With solids: one word per brick (B bricks), nonzero where a cell of the brick has a solid flag
// (mark_solids.comp); the sweep reads the rows' flags only there. Where the sweep is split
// (kBlockList, fluid_solids.glsl: 1 the bricks near solids, 2 those away from them), list L's
// bricks are words [B L, B L + its length) (a brick's coordinates x + 1024 y + 1024² z), its
// indirect dispatch words 3 B + 3 (L - 1) .. + 2 and
// its length word 3 B + 6 + (L - 1); invocation i of the dispatch sweeps the list's brick i.
layout(std430, binding = 8) readonly buffer SolidBricks {
    uint solidBricks[];
};

// Which side is packed (see above), and the brick's rows along y and layers along z
// (SmokeSolver::solvePressure sizes the dispatch by them).
layout(constant_id = 11) const uint kPressureMode = 0;
layout(constant_id = 12) const int kPressureLayers = 4;
layout(constant_id = 13) const int kPressureRows = 4;
const bool kPackedIn = (kPressureMode & 1u) != 0u;
const bool kPackedOut = (kPressureMode & 2u) != 0u;
const bool kZeroIn = (kPressureMode & 4u) != 0u;

// Four cells of a row from an r32f field, at columns x.
vec4 loadRow(ivec4 x, int y, int z) {
    return vec4(
        imageLoad(pressureIn, ivec3(x.x, y, z)).r, imageLoad(pressureIn, ivec3(x.y, y, z)).r,
        imageLoad(pressureIn, ivec3(x.z, y, z)).r, imageLoad(pressureIn, ivec3(x.w, y, z)).r);
}
vec4 loadDivergenceRow(ivec4 x, int y, int z) {
    return vec4(
        imageLoad(divergence, ivec3(x.x, y, z)).r, imageLoad(divergence, ivec3(x.y, y, z)).r,
        imageLoad(divergence, ivec3(x.z, y, z)).r, imageLoad(divergence, ivec3(x.w, y, z)).r);
}

// The brick's row at (y, z): packed element `texel` of the row, or r32f columns `columns`.
vec4 row(int texel, ivec4 columns, int y, int z) {
    if (kZeroIn) return vec4(0.0);
    return kPackedIn ? packedIn[packedIndex(texel, y, z)] : loadRow(columns, y, z);
}

vec4 selectRow(bool use, vec4 value) {
    return use ? value : vec4(0.0); // adding 0.0 leaves a sum exactly as skipping
}

void main() {
    ivec3 n = cellCount();
    ivec3 bricks = (n + ivec3(3, kPressureRows - 1, kPressureLayers - 1)) /
                   ivec3(4, kPressureRows, kPressureLayers);
    ivec3 b = ivec3(gl_GlobalInvocationID);
    if (kBlockList != 0u) {
        uint count = uint(bricks.x * bricks.y * bricks.z);
        uint listed = gl_WorkGroupID.x * (gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z) +
                      gl_LocalInvocationIndex;
        if (listed >= solidBricks[3u * count + 6u + kBlockList - 1u]) return;
        uint entry = solidBricks[count * kBlockList + listed];
        b = ivec3(entry & 0x3ffu, (entry >> 10) & 0x3ffu, entry >> 20);
    }
    ivec3 brick = b * ivec3(1, kPressureRows, kPressureLayers);
    int texel = brick.x;
    int firstX = 4 * texel;
    if (firstX >= n.x || brick.y >= n.y || brick.z >= n.z) return;
    float h = cellSize();
    float h2 = h * h;

    // x: the four cells' columns (wrapped or clamped past the last cell) and the row's ends. A
    // cell's -x neighbour inside the row is always inside the grid; its +x neighbour may be past
    // the last cell.
    ivec4 cellX = firstX + ivec4(0, 1, 2, 3);
    NeighbourRef refX1 = neighbourRef(0, firstX + 1);
    NeighbourRef refX2 = neighbourRef(0, firstX + 2);
    NeighbourRef refX3 = neighbourRef(0, firstX + 3);
    NeighbourRef refLeft = neighbourRef(0, firstX - 1);
    NeighbourRef refRight = neighbourRef(0, firstX + 4);
    ivec4 columns = ivec4(min(firstX, n.x - 1), refX1.index, refX2.index, refX3.index);
    bvec4 plusValue = bvec4(refX1.value, refX2.value, refX3.value, refRight.value);
    ivec4 countX = ivec4(refLeft.counted ? 1 : 0, 1, 1, 1) +
                   ivec4(refX1.counted ? 1 : 0, refX2.counted ? 1 : 0, refX3.counted ? 1 : 0,
                         refRight.counted ? 1 : 0);
    // Packed: the cell right of the brick (wrapped or clamped), and which of the brick's +x
    // neighbours are past the last cell (those of a periodic x are cell 0).
    int rightCell = firstX + 4 < n.x ? firstX + 4 : 0;
    bvec4 plusPast = greaterThanEqual(cellX + 1, ivec4(n.x));

    // y: the window of rows brick.y - 1 .. brick.y + kPressureRows (wrapped or clamped); brick row
    // r is window row r + 1, its -y and +y neighbours are window rows r and r + 2.
    int windowY[kPressureRows + 2];
    for (int i = 0; i < kPressureRows + 2; ++i)
        windowY[i] = neighbourRef(1, brick.y - 1 + i).index;

    bool nearSolids =
        kSolids && (kBlockList == 1u ||
                    (kBlockList == 0u && solidBricks[b.x + bricks.x * (b.y + bricks.y * b.z)] != 0u));
    vec4 below[kPressureRows], centre[kPressureRows + 2], above[kPressureRows + 2];
    int belowZ = neighbourRef(2, brick.z - 1).index;
    for (int r = 0; r < kPressureRows; ++r)
        below[r] = row(texel, columns, windowY[r + 1], belowZ);
    for (int i = 0; i < kPressureRows + 2; ++i)
        centre[i] = row(texel, columns, windowY[i], brick.z);
    for (int layer = 0; layer < kPressureLayers; ++layer) {
        int z = brick.z + layer;
        if (z >= n.z) break;
        NeighbourRef refBelow = neighbourRef(2, z - 1);
        NeighbourRef refAbove = neighbourRef(2, z + 1);
        for (int i = 0; i < kPressureRows + 2; ++i)
            above[i] = row(texel, columns, windowY[i], refAbove.index);

        for (int r = 0; r < kPressureRows; ++r) {
            int y = brick.y + r;
            int rowY = windowY[r + 1];
            NeighbourRef refDown = neighbourRef(1, y - 1);
            NeighbourRef refUp = neighbourRef(1, y + 1);
            vec4 minusX, plusX, divergenceRow;
            if (kPackedIn) {
                int offset = 4 * packedIndex(0, rowY, z);
                float left = packedInCells[offset + refLeft.index];
                float right = packedInCells[offset + rightCell];
                minusX = vec4(left, centre[r + 1].xyz);
                plusX = mix(vec4(centre[r + 1].yzw, right), vec4(right), plusPast);
                divergenceRow = packedDivergence[packedIndex(texel, rowY, z)];
            } else {
                float left = kZeroIn ? 0.0 : imageLoad(pressureIn, ivec3(refLeft.index, rowY, z)).r;
                float right =
                    kZeroIn ? 0.0 : imageLoad(pressureIn, ivec3(refRight.index, rowY, z)).r;
                minusX = vec4(left, centre[r + 1].xyz);
                plusX = vec4(centre[r + 1].yzw, right);
                divergenceRow = loadDivergenceRow(columns, rowY, z);
                if (kPackedOut) packedDivergence[packedIndex(texel, rowY, z)] = divergenceRow;
            }

            // The six sides' terms, in the reference's order.
            vec4 side[6];
            side[0] = vec4(refLeft.value ? minusX.x : 0.0, minusX.yzw);
            side[1] = mix(vec4(0.0), plusX, plusValue);
            side[2] = selectRow(refDown.value, centre[r]);
            side[3] = selectRow(refUp.value, centre[r + 2]);
            side[4] = selectRow(refBelow.value, below[r]);
            side[5] = selectRow(refAbove.value, above[r + 1]);
            ivec4 count = countX + (refDown.counted ? 1 : 0) + (refUp.counted ? 1 : 0) +
                          (refBelow.counted ? 1 : 0) + (refAbove.counted ? 1 : 0);
            // Solids (docs/fluid.md, "Solids"): a solid neighbour is neither summed nor counted
            // (zero normal gradient, as across a wall), and a solid cell holds p = 0.
            // The row's four flag bytes are one word (fluid_solids.glsl); most rows have none.
            bvec4 solid = bvec4(false);
            uint flags = nearSolids ? solidFlags[solidWordIndex(texel, rowY, z)] : 0u;
            if (flags != 0u) {
                uvec4 bytes = (uvec4(flags) >> uvec4(0u, 8u, 16u, 24u)) & 0xffu;
                solid = notEqual(bytes & 1u, uvec4(0u));
                for (int s = 0; s < 6; ++s)
                    side[s] =
                        mix(side[s], vec4(0.0), notEqual(bytes & (2u << uint(s)), uvec4(0u)));
                count -= bitCount((bytes >> 1u) & 63u);
            }
            vec4 sum = vec4(0.0);
            for (int s = 0; s < 6; ++s)
                sum += side[s];
            vec4 p = (sum - h2 * divergenceRow) / vec4(count);
            p = mix(p, vec4(0.0), equal(count, ivec4(0)));
            p = mix(p, vec4(0.0), solid);

            if (y < n.y) {
                if (kPackedOut) {
                    packedOut[packedIndex(texel, y, z)] = p;
                } else {
                    for (int c = 0; c < 4; ++c)
                        if (cellX[c] < n.x)
                            imageStore(pressureOut, ivec3(cellX[c], y, z), vec4(MFX_STORED(p[c])));
                }
            }
        }
        for (int r = 0; r < kPressureRows; ++r)
            below[r] = centre[r + 1];
        for (int i = 0; i < kPressureRows + 2; ++i)
            centre[i] = above[i];
    }
}
