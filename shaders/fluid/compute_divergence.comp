// computeDivergence: div = (u[i+1]-u[i] + v[j+1]-v[j] + w[k+1]-w[k]) / h (docs/fluid.md).
// Twin: fluid/reference/compute_divergence.cpp. Writes a buffer that the solver copies into the
// divergence image, or with kDirectStore the image itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(std430, binding = 4) writeonly buffer Divergence {
    float divergence[];
};
layout(binding = 5, r32f) uniform writeonly image3D divergenceImage; // kDirectStore

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    float sum = (imageLoad(velocityX, q + ivec3(1, 0, 0)).r - imageLoad(velocityX, q).r) +
                (imageLoad(velocityY, q + ivec3(0, 1, 0)).r - imageLoad(velocityY, q).r) +
                (imageLoad(velocityZ, q + ivec3(0, 0, 1)).r - imageLoad(velocityZ, q).r);
    if (kDirectStore)
        imageStore(divergenceImage, q, vec4(sum / cellSize()));
    else
        divergence[cellElement(q)] = sum / cellSize();
}
