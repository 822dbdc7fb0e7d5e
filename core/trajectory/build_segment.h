// The CPU twin of the trajectory shaders (shaders/core/trajectory_segment.glsl, build_segment.comp,
// build_trail.comp): the same segment, computed the same way, for tests and for anyone who wants
// to see what the GPU writes. Xu et al., "Real-time Character Motion Effect Enhancement Based on
// Fluid Simulation", section 3.2 (split trajectory, eq. 3 for the sub-samples, Algorithm 1 for the
// attenuation).
#pragma once

#include "core/anim/skinning.h"
#include "core/trajectory/trajectory_source.h"
#include "shaders/shared/trajectory.h"

#include <cstdint>
#include <vector>

namespace mfx::trajectory {

struct SegmentParameters {
    uint32_t subSamples = 4;   // S: S pieces, S + 1 vertices per source vertex (1..16)
    float impulseScale = 1.0f; // k: loss coefficient of the impulse velocity
    // Attenuation along the segment: alphaStart + (alphaEnd - alphaStart) * tau^alphaPower.
    float alphaStart = 1.0f;
    float alphaEnd = 0.0f;
    float alphaPower = 1.0f;
};

// Checks the parameters (S in 1..16, finite k, alphas in [0, 1], power > 0); the error names the
// parameter and its range.
Status checkParameters(const SegmentParameters& parameters);

float attenuation(float tau, const SegmentParameters& parameters);

// (1 - tau) a + tau b with the sign rule (b negated when the rotation parts point apart),
// normalised; scales blended linearly. Eq. 3 of Xu et al.; the GPU twin is interpolateTransform
// in shaders/core/dual_quat.glsl.
anim::DualQuatJoint interpolateTransform(const anim::DualQuatJoint& a, const anim::DualQuatJoint& b,
                                         float tau);

// Each source vertex's skinning transform under `palette` (blendJoints per vertex).
std::vector<anim::DualQuatJoint> vertexTransforms(const Source& source,
                                                  const std::vector<anim::DualQuatJoint>& palette);

// The segment born at `time` of every source vertex, between its transforms `now` (tau = 0) and
// `previous` (tau = 1, dt seconds earlier): S + 1 vertices per source vertex, source-major.
std::vector<shared::TrajectoryVertex> buildSegment(const Source& source,
                                                   const std::vector<anim::DualQuatJoint>& now,
                                                   const std::vector<anim::DualQuatJoint>& previous,
                                                   float time, float dt,
                                                   const SegmentParameters& parameters);

} // namespace mfx::trajectory
