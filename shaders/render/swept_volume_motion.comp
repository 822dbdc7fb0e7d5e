// sweptVolumeMotion: the bound part's motion vector and trailing transparency, in one workgroup
// (Wloka and Zeleznik 1996):
//   motion:   the mean over the part's vertices of now minus the oldest sample, the sum of the
//             segments' motion vectors (Sec. 4.2); the scene's camera does not move, so this is
//             also the motion relative to the camera, motion_obj - vel_cam (Sec. 3.1);
//   length:   the sum of the segments' lengths (the path, Sec. 4.2);
//   extent:   the part's extent along the motion (Sec. 3.4);
//   trailing: max(floor, 1 - length / extent) (Sec. 3.4).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "swept_volume_common.glsl"

layout(local_size_x = MFX_SWEPT_GROUP_SIZE) in;

shared vec3 sums[MFX_SWEPT_GROUP_SIZE];
shared vec2 ranges[MFX_SWEPT_GROUP_SIZE];

// The workgroup's sum of `value` (every invocation gets it).
vec3 groupSum(vec3 value) {
    uint i = gl_LocalInvocationID.x;
    barrier();
    sums[i] = value;
    barrier();
    for (uint half_ = MFX_SWEPT_GROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
        if (i < half_) sums[i] += sums[i + half_];
        barrier();
    }
    return sums[0];
}

// The mean displacement of the part between `newer` and `older` frames back.
vec3 meanDisplacement(uint newer, uint older) {
    vec3 sum = vec3(0.0);
    for (uint v = gl_LocalInvocationID.x; v < constants.vertexCount; v += MFX_SWEPT_GROUP_SIZE)
        sum += recorded(v, newer) - recorded(v, older);
    return groupSum(sum) / float(max(constants.vertexCount, 1u));
}

void main() {
    uint i = gl_LocalInvocationID.x;
    uint segments = sweptSegments();
    vec3 motion = segments > 0u ? meanDisplacement(0u, segments) : vec3(0.0);
    float pathLength = 0.0;
    for (uint j = 0u; j < segments; ++j)
        pathLength += length(meanDisplacement(j, j + 1u));

    float motionLength = length(motion);
    vec3 axis = motionLength > MFX_SWEPT_STILL ? motion / motionLength : vec3(0.0);
    vec2 range = vec2(1e30, -1e30);
    for (uint v = i; v < constants.vertexCount; v += MFX_SWEPT_GROUP_SIZE) {
        float d = dot(recorded(v, 0u), axis);
        range = vec2(min(range.x, d), max(range.y, d));
    }
    ranges[i] = range;
    barrier();
    for (uint half_ = MFX_SWEPT_GROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
        if (i < half_)
            ranges[i] = vec2(min(ranges[i].x, ranges[i + half_].x),
                             max(ranges[i].y, ranges[i + half_].y));
        barrier();
    }
    if (i != 0u) return;
    float extent = max(ranges[0].y - ranges[0].x, 0.0);
    counters.motion = vec4(motion, pathLength);
    counters.extent = extent;
    // A zero motion leaves the trailing side opaque (Sec. 3.4); a part with no depth along its
    // motion fades to the floor.
    counters.trailingAlpha =
        motionLength <= MFX_SWEPT_STILL ? 1.0
        : extent > 0.0                  ? max(constants.alphaFloor, 1.0 - pathLength / extent)
                                        : constants.alphaFloor;
}
