// copyBandwidth: one vec4 of the source buffer to the destination buffer per invocation, the
// bandwidth yardstick of the benchmarks (core/gpu/bandwidth.h): every byte read once and written
// once, consecutive invocations on consecutive vec4s, nothing else.
#version 450

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Source {
    vec4 source[];
};
layout(std430, binding = 1) writeonly buffer Destination {
    vec4 destination[];
};

layout(push_constant) uniform Dispatch {
    uint count;     // vec4s to copy
    uint rowLength; // invocations per row of workgroups (the grid's x extent times 256)
};

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * rowLength;
    if (i < count) destination[i] = source[i];
}
