// afterimageSmear: per bound vertex, whether it is on the rear of its motion and how far it is
// pushed back (Smith 2016, Sec. 4.1.2-4.1.3 and 4.3):
//   rear:   n . m < 0, m its motion this frame;
//   push:   T = R * taper * (f^U * -m^U + f^V * -m^V)  (Sec. 4.3, the uniform/non-uniform split),
//           m^U the character's root travel, m^V = m - m^U the animation's own motion;
//   R:      in [min, max] from a hash of the index of the vertex's first copy (the copies of a
//           seam vertex draw the same), 0 below the threshold;
//   taper:  (-n . m/|m|)^k, so the vertex facing straight back is pushed furthest;
//   speed:  |m| at least an absolute bound and a fraction of the fastest bound vertex's |m|
//           (Sec. 5.3 "Thresholding": only the blade smears, not the hilt).
// The speed-lines variant appends a line from each pushed vertex to its pushed position
// (Sec. 4.3 "Speedlines"). The decision goes to Decided; afterimage_weld.comp then moves the
// copies of a seam vertex together (Sec. 5.4).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "afterimage_common.glsl"

layout(local_size_x = MFX_AFTERIMAGE_GROUP_SIZE) in;

TrajectoryVertex makeVertex(vec3 position, vec3 normal, vec4 colour, float s) {
    TrajectoryVertex v;
    v.position = vec4(position, s); // w: tau, 0 at the live mesh (the ribbon's taper)
    v.normal = vec4(normal, 0.0);   // w: sample time 0, drawn at time 0: no age fade
    v.color = vec4(colour.rgb, colour.a * alphaAt(s));
    v.velocity = vec4(0.0);
    return v;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.vertexCount) return;
    vec3 p = skinned[i].position.xyz;
    vec3 n = skinned[i].normal.xyz;
    vec3 m = frameMotion(i);
    float speed = length(m);
    float fastest = uintBitsToFloat(counters.fastestBits);
    bool moving = speed > MFX_AFTERIMAGE_STILL;
    float facing = moving ? dot(n, m / speed) : 0.0;

    float r = mix(constants.randomMin, constants.randomMax, vertexRandom(firstCopy(i)));
    if (r < constants.randomThreshold) r = 0.0;
    float taper = constants.taper > 0.0 ? pow(max(-facing, 0.0), constants.taper) : 1.0;
    bool pushedBack = moving && facing < 0.0 && speed >= constants.minSpeed &&
                  speed >= constants.relativeSpeed * fastest && r * taper > 0.0;

    vec3 characterMotion = constants.characterMotion.xyz;
    vec3 ownMotion = m - characterMotion;
    vec3 push = r * taper *
                (constants.strengthCharacter * -characterMotion +
                 constants.strengthAnimation * -ownMotion);
    if (constants.variant != MFX_AFTERIMAGE_MULTI && length(push) <= MFX_AFTERIMAGE_STILL)
        pushedBack = false;
    if (!pushedBack) push = vec3(0.0);

    vec4 colour = colours[i];
    bool moved = constants.variant == MFX_AFTERIMAGE_SMEAR;
    TrajectoryVertex v = makeVertex(p + (moved ? push : vec3(0.0)), n, colour, pushedBack ? 1.0 : 0.0);
    v.position.w = pushedBack ? 1.0 : 0.0;
    v.velocity = vec4(push, pushedBack ? r * taper : 0.0);
    decided[i] = v;
    if (!pushedBack) return;

    if (constants.variant == MFX_AFTERIMAGE_SPEED_LINES && i % constants.stride == 0u) {
        uint base = atomicAdd(counters.vertexCount, 2u);
        outputVertices[base] = makeVertex(p, n, colour, 0.0);
        outputVertices[base + 1u] = makeVertex(p + push, n, colour, 1.0);
        // Sample time -1 at the pushed end: the ribbon's life runs along the line
        // (render/kinds/afterimage_pass.cpp draws it with a lifetime of 1 when it has a look).
        outputVertices[base + 1u].normal.w = -1.0;
    }
}
