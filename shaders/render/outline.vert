// The toon outline, vertex stage: the character's inverted hull. Each skinned vertex (with its
// welded normal, anim::weldedNormals, so seams and hard edges do not split the hull) is moved
// out along its normal's direction on the screen by a fixed number of pixels:
//     clip.xy += normalize(N.xy) * width * (2 / size) * clip.w,
// N the normal in clip space, so the outline is `width` pixels wide at any distance. Drawn with
// front faces culled, only the hull's back faces behind the silhouette show, as a rim of that
// width around the character.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/scene_draw.h"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;

layout(std140, binding = 0) uniform Frame {
    SceneFrame frame;
};
layout(push_constant) uniform Outline {
    OutlineDraw outline;
};

void main() {
    vec4 clip = frame.viewProjection * vec4(position.xyz, 1.0);
    vec2 across = (frame.viewProjection * vec4(normal.xyz, 0.0)).xy;
    float length2 = dot(across, across);
    if (length2 > 1e-12) across *= inversesqrt(length2);
    else across = vec2(0.0); // a normal along the view: no screen direction to grow in
    clip.xy += across * outline.width.x * outline.width.yz * clip.w;
    gl_Position = clip;
}
