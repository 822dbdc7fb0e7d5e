// markSolids on the sparse grid: the sub-step's moving solids put into the listed bricks
// (docs/fluid.md, "Solids"; Bridson, "Fluid Simulation for Computer Graphics", 2nd ed., ch. 5:
// u·n = u_solid·n on the faces between fluid and solid; Crane, Llamas, Tariq, GPU Gems 3 ch. 30:
// the obstacle voxelised into the grid every step with its surface's velocity). The dense stage's
// rules (mark_solids.comp) over the stored cells; twin: fluid/reference/mark_solids.cpp with the
// reference's active cells. The first dispatchInfo.target solids are this step's. Two passes
// (kPass, constant id 11):
//   0  each cell's holder (sparse_solids.glsl): the solids whose bounding box reaches the
//      workgroup's cells are gathered first (in shared memory, any order), and the cell takes the
//      lowest index among those holding its centre, so the first in list order wins;
//   1  every stored face beside a solid cell (one beside it below, else above) takes that
//      solid's velocity at the face, except wall-normal faces; a solid cell's pigment is 0.
// In place: pass 1 reads only the holders and writes each face's copies alike.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"
#include "solid_common.glsl"

layout(std140, binding = 13) uniform Solids {
    FluidSolid solids[1024];
};
layout(std430, binding = 3) buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 4) buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 5) buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 6) buffer Pigment {
    vec4 pigment[];
};

layout(constant_id = 11) const uint kPass = 0u;

shared uint nearCount;
shared uint nearSolids[1024];

// The holder of cell q, index + 1 (0: air, outside the domain, or not stored).
uint holderAt(BrickCell at, ivec3 l, ivec3 q) {
    if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, cellCount()))) return 0u;
    int e = nearbyCellElement(at, l, q);
    return e < 0 ? 0u : solidHolders[e];
}

void markFace(BrickCell at, int c, ivec3 l) {
    ivec3 q = at.brick * kBrick + l;
    if (wallNormalFace(c, q)) return; // a wall stays a wall
    ivec3 step = ivec3(0);
    step[c] = 1;
    uint holder = holderAt(at, l - step, q - step);
    if (holder == 0u) holder = holderAt(at, l, q);
    if (holder == 0u) return;
    float v = solidVelocityAt(solids[holder - 1u], facePosition(c, q), c);
    int e = faceElementIn(at.slot, c, l);
    if (c == 0)
        velocityX[e] = v;
    else if (c == 1)
        velocityY[e] = v;
    else
        velocityZ[e] = v;
}

void main() {
    BrickCell at = listedCell();
    ivec3 q = at.brick * kBrick + at.local;
    if (kPass == 0u) {
        if (gl_LocalInvocationIndex == 0u) nearCount = 0u;
        barrier();
        // The workgroup's cell centres' box, a hundredth of a cell wider (fp32's error).
        float h = cellSize();
        ivec3 first = at.brick * kBrick + ivec3(0, 0, at.local.z & ~3);
        vec3 lo = (vec3(first) + 0.49) * h;
        vec3 hi = (vec3(first + ivec3(kBrick - 1, kBrick - 1, 3)) + 0.51) * h;
        uint count = min(dispatchInfo.target, 1024u);
        uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
        for (uint i = gl_LocalInvocationIndex; i < count; i += invocations) {
            FluidSolid s = solids[i];
            vec3 low = min(s.endA.xyz, s.endB.xyz) - s.endA.w;
            vec3 high = max(s.endA.xyz, s.endB.xyz) + s.endA.w;
            if (all(lessThanEqual(low, hi)) && all(greaterThanEqual(high, lo)))
                nearSolids[atomicAdd(nearCount, 1u)] = i;
        }
        barrier();
        uint holder = 0u;
        vec3 x = cellCentre(q);
        for (uint k = 0u; k < nearCount; ++k) {
            uint i = nearSolids[k];
            if ((holder == 0u || i + 1u < holder) && insideSolid(solids[i], x)) holder = i + 1u;
        }
        solidHolders[cellElementIn(at.slot, at.local)] = holder;
        return;
    }
    for (int c = 0; c < 3; ++c) {
        markFace(at, c, at.local);
        if (at.local[c] == kBrick - 1) { // the brick's top layer of faces along c
            ivec3 top = at.local;
            top[c] = kBrick;
            markFace(at, c, top);
        }
    }
    int e = cellElementIn(at.slot, at.local);
    if (solidHolders[e] != 0u) pigment[e] = vec4(0.0);
}
