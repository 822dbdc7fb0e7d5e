// hostDepth: a host application's depth image copied into the effects layer's depth (HostFrame,
// render/host_frame.h), texel for texel, so the effects are hidden and faded by the host's own
// surfaces. Drawn over the whole layer by one triangle (fullscreen.vert) with the depth test
// always passing; the host's format (16-bit unorm, 24-bit unorm, 32-bit float) reads as a float
// in [0, 1] through a view of its depth aspect.
#version 450

layout(binding = 0) uniform sampler2D hostDepth; // same size as the layer

void main() {
    gl_FragDepth = texelFetch(hostDepth, ivec2(gl_FragCoord.xy), 0).r;
}
