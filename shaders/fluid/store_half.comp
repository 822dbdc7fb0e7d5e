// storeHalf: a whole field written x-fastest into a storage buffer of 32-bit floats (one per
// texel; four with MFX_STORE_RGBA) stored into its binary16 image, each value rounded to nearest
// even first (shaders/fluid/field_formats.glsl). With fp16 storage (docs/fluid.md, "fp16 storage") it replaces the
// buffer-to-image copy that follows every stage writing a whole field: a copy cannot convert.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "field_formats.glsl"
#include "shared/fluid.h"

layout(local_size_x_id = 8, local_size_y_id = 9, local_size_z_id = 10) in;

layout(std430, binding = 1) readonly buffer Values {
    float values[];
};
#ifdef MFX_STORE_RGBA
layout(binding = 2, rgba16f) uniform writeonly image3D field;
#else
layout(binding = 2, r16f) uniform writeonly image3D field;
#endif

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    ivec3 n = imageSize(field);
    if (any(greaterThanEqual(q, n))) return;
    int element = q.x + n.x * (q.y + n.y * q.z);
#ifdef MFX_STORE_RGBA
    int first = 4 * element;
    imageStore(field, q,
               vec4(roundToHalf(values[first]), roundToHalf(values[first + 1]),
                    roundToHalf(values[first + 2]), roundToHalf(values[first + 3])));
#else
    imageStore(field, q, vec4(roundToHalf(values[element])));
#endif
}
