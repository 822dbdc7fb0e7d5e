// Structures of the smoke solver (fluid/), shared by its compute shaders and C++.
// The discretisation they parameterise is written down in docs/fluid.md.
#ifndef MFX_SHARED_FLUID_H
#define MFX_SHARED_FLUID_H

#include "common.h"

// Default workgroup shape of every solver stage (SolverOptions::workgroup): x fastest, matching
// the x-fastest layout of the fields.
#define MFX_FLUID_GROUP_X 8
#define MFX_FLUID_GROUP_Y 8
#define MFX_FLUID_GROUP_Z 4

// Boundary kinds, per domain face (-x, +x, -y, +y, -z, +z).
#define MFX_BOUNDARY_WALL_FREE_SLIP 0u
#define MFX_BOUNDARY_WALL_NO_SLIP 1u
#define MFX_BOUNDARY_OPEN 2u
#define MFX_BOUNDARY_PERIODIC 3u

// Back-trace integrators of the semi-Lagrangian advection.
#define MFX_INTEGRATOR_EULER 0u
#define MFX_INTEGRATOR_RK2 1u

// The passes of one field's advection (docs/fluid.md, "Accuracy options"), a specialization
// constant of advect_velocity and advect_pigment. With A the semi-Lagrangian step over dt and A^R
// the same step over -dt, source the field on entry and work the pass's intermediate field:
//   SEMI_LAGRANGIAN     A(source), faded
//   PREDICT             A(source)                                   (MacCormack, BFECC)
//   MACCORMACK_CORRECT  limit(work + (source - A^R(work)) / 2), faded; work = A(source)
//   BFECC_COMPENSATE    source + (source - A^R(work)) / 2;          work = A(source)
//   BFECC_FINAL         limit(A(work)), faded;                       work = the compensated field
// where limit clamps to the range of the source values A's sample at the same point reads.
#define MFX_ADVECT_SEMI_LAGRANGIAN 0u
#define MFX_ADVECT_PREDICT 1u
#define MFX_ADVECT_MACCORMACK_CORRECT 2u
#define MFX_ADVECT_BFECC_COMPENSATE 3u
#define MFX_ADVECT_BFECC_FINAL 4u

// Which field a dispatch works on (FluidDispatch.target).
#define MFX_TARGET_VELOCITY_X 0u
#define MFX_TARGET_VELOCITY_Y 1u
#define MFX_TARGET_VELOCITY_Z 2u
#define MFX_TARGET_PIGMENT 3u

// The block lists of a solver with solids (shaders/fluid/fluid_solids.glsl): near and away from
// solids, for each of the five extents a stage dispatches over.
#define MFX_SOLID_BLOCK_LISTS 10u
// The entries of one block list (a uniform buffer of 64 KiB; more blocks: the stages not split).
#define MFX_SOLID_LIST_ENTRIES 16384u

MFX_SHARED_BEGIN

// Uniform buffer (std140), written once per sub-step.
struct FluidParameters {
    uvec4 size;           // cells nx, ny, nz; w: number of emitters
    vec4 cell;            // x: cell size h, y: 1/h, z: dt of the sub-step, w: velocity drag per
                          // second
    vec4 rates;           // x: pigment fade per second, y: buoyancy, z: vorticity confinement
                          // strength, w: viscosity coefficient nu*dt/h^2
    uvec4 boundaryLow;    // boundary kind of the -x, -y, -z faces; w: integrator
    uvec4 boundaryHigh;   // boundary kind of the +x, +y, +z faces; w: unused
    vec4 wallVelocity[6]; // xyz: velocity of the wall on face -x, +x, -y, +y, -z, +z
    vec4 turbulence;      // curl noise (curl_noise.glsl): x amplitude, y 1 / scale, z the noise's
                          // time (the step's start time * speed), w scale
};

// One emitter: pulls velocity and pigment towards its own values inside a sphere, at a rate of
// `strength` per second scaled by a smooth falloff (docs/fluid.md, "splatImpulses").
struct FluidEmitter {
    vec4 positionRadius;   // xyz: centre in grid world units; w: radius (> 0)
    vec4 velocityStrength; // xyz: velocity; w: strength per second (>= 0)
    vec4 pigment;          // RGBA, each >= 0
};

// One moving solid: a capsule (a sphere when both ends are one point) where the step ends, and the
// velocity of each end over the step (docs/fluid.md, "Solids"). A point's velocity is its ends'
// blended by where it projects onto the axis.
struct FluidSolid {
    vec4 endA;      // xyz: first end of the axis in grid world units; w: radius (> 0)
    vec4 endB;      // xyz: second end; w: unused
    vec4 velocityA; // xyz: velocity of end A; w: unused
    vec4 velocityB; // xyz: velocity of end B; w: unused
};

// Push constants of every stage.
struct FluidDispatch {
    uint target;  // unused: the target is a specialization constant (kTarget)
    uint originX; // first cell/face of the dispatched region (every stage covers its whole
    uint originY; // field: 0; splatImpulses reads its region from SplatRegion instead)
    uint originZ;
};

// Where splatImpulses runs for one target (velocity x, y, z, pigment), written on the GPU by
// emitterBounds from the emitters' spheres: the first three words are a
// VkDispatchIndirectCommand (workgroups), then the first cell/face of the region.
struct SplatRegion {
    uint groupsX;
    uint groupsY;
    uint groupsZ;
    uint pad0;
    uint originX;
    uint originY;
    uint originZ;
    uint pad1;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(FluidParameters, 192);
MFX_CHECK_LAYOUT(FluidParameters, turbulence, 176);
MFX_CHECK_LAYOUT(FluidParameters, cell, 16);
MFX_CHECK_LAYOUT(FluidParameters, rates, 32);
MFX_CHECK_LAYOUT(FluidParameters, boundaryLow, 48);
MFX_CHECK_LAYOUT(FluidParameters, boundaryHigh, 64);
MFX_CHECK_LAYOUT(FluidParameters, wallVelocity, 80);
MFX_CHECK_SIZE(FluidEmitter, 48);
MFX_CHECK_LAYOUT(FluidEmitter, velocityStrength, 16);
MFX_CHECK_LAYOUT(FluidEmitter, pigment, 32);
MFX_CHECK_SIZE(FluidSolid, 64);
MFX_CHECK_LAYOUT(FluidSolid, endB, 16);
MFX_CHECK_LAYOUT(FluidSolid, velocityA, 32);
MFX_CHECK_LAYOUT(FluidSolid, velocityB, 48);
MFX_CHECK_SIZE(FluidDispatch, 16);
MFX_CHECK_SIZE(SplatRegion, 32);
MFX_CHECK_LAYOUT(SplatRegion, originX, 16);
#endif

#endif
