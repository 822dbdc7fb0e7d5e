// Soft (depth) fade of the thin effects, speed-lines and particles (the "soft particles" of
// real-time renderers): a fragment's alpha is scaled by how far in front of the scene's surface
// at its pixel it is, over `fade` world units along the view,
//   fade factor = clamp((z_scene - z_fragment) / fade, 0, 1),
// with view depths from the perspective depth d of a [0, 1] depth range (glm::perspectiveRH_ZO):
//   z = near * far / (far - d (far - near)).
// The scene's depth is a single-sampled copy made before the effects draw (render_target.h
// copyFadeDepth), or a 1x1 image at the far plane when no effect of the frame fades.
#ifndef MFX_DEPTH_FADE_GLSL
#define MFX_DEPTH_FADE_GLSL

layout(binding = 2) uniform sampler2D sceneDepth;

float viewDepth(float d) {
    float n = frame.depthRange.x, f = frame.depthRange.y;
    return n * f / (f - d * (f - n));
}

float depthFade(float fade) {
    if (fade <= 0.0) return 1.0;
    ivec2 pixel = min(ivec2(gl_FragCoord.xy), textureSize(sceneDepth, 0) - 1);
    float behind = viewDepth(texelFetch(sceneDepth, pixel, 0).r) - viewDepth(gl_FragCoord.z);
    return clamp(behind / fade, 0.0, 1.0);
}

#endif
