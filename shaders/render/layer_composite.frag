// layerComposite: the effects layer (premultiplied linear colour and coverage, HostFrame,
// render/host_frame.h) laid over a host application's colour by the blend stage,
//     out = layer.rgb + (1 - layer.a) host.rgb,
// texel for texel (fullscreen.vert). The blend runs in the host format's own space: linear for
// float and sRGB formats (which decode and encode), as stored for unorm ones.
#version 450

layout(binding = 0) uniform sampler2D layer; // the layer's resolved colour, same size

layout(location = 0) out vec4 outColor;

void main() {
    vec4 colour = texelFetch(layer, ivec2(gl_FragCoord.xy), 0);
    // A NaN or a negative value from an effect never reaches the host's picture.
    bvec4 bad = isnan(colour);
    colour = vec4(bad.x ? 0.0 : colour.x, bad.y ? 0.0 : colour.y, bad.z ? 0.0 : colour.z,
                  bad.w ? 0.0 : colour.w);
    outColor = vec4(clamp(colour.rgb, 0.0, 65504.0), clamp(colour.a, 0.0, 1.0));
}
