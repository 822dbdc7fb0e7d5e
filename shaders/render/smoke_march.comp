// The smoke pass's march as a compute pass (smoke_march.glsl), one invocation a texel of the fluid
// buffer: on a chip whose rasteriser is a small part of it (NVIDIA's H100 and H200 run fragment
// shaders on two of their texture processing clusters) the fragment march (smoke.frag) costs
// several times as much; on lavapipe the fragment march is the faster (render/smoke_pass.h). A
// texel whose ray misses the pigment's box stores nothing-there (0, and MFX_SMOKE_NO_DISTANCE), as
// the fragment march leaves the texels it does not cover in the cleared buffer.
#version 450
#extension GL_GOOGLE_include_directive : require
#define MFX_SMOKE_COMPUTE
#include "smoke_march.glsl"

layout(std430, binding = 2) readonly buffer Bounds {
    PigmentBounds bounds;
};

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 6, rgba16f) uniform writeonly image2D outColor; // premultiplied
// marchedDistance() of the scene distance used, or MFX_SMOKE_NO_DISTANCE where the ray misses
layout(binding = 7, r32f) uniform writeonly image2D outDistance;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(outColor)))) return;
    // The ray through the block's centre; a texel whose ray misses the box (or an empty box) has
    // nothing to march.
    vec3 dir = rayDirection((vec2(texel) + 0.5) * float(kDivisor));
    bool empty = !pigmentBox(draw, bounds, boxLow, boxHigh);
    vec2 box = crossBox(1.0 / dir, boxLow, boxHigh);
    if (empty || !(box.y > box.x)) {
#ifdef MFX_SMOKE_CARTOON // far outside the surface
        imageStore(outColor, texel, vec4(-style.surface.x, 0.0, 0.0, 0.0));
#else
        imageStore(outColor, texel, vec4(0.0));
#endif
        imageStore(outDistance, texel, vec4(MFX_SMOKE_NO_DISTANCE));
        return;
    }
    float marched;
#ifdef MFX_SMOKE_CARTOON // (built as smoke_march_comp_cartoon)
    vec4 colour = marchCartoon(texel, dir, marched);
#else
    vec4 colour = march(texel, dir, marched);
#endif
    imageStore(outColor, texel, colour);
    imageStore(outDistance, texel, vec4(marched));
}
