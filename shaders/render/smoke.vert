// The smoke pass's proxy: the faces of the box of cells that hold pigment (smoke_box.glsl), so
// only the pixels whose ray meets pigment run the fragment stage. Only the faces turned away from the eye
// are drawn: every ray that meets the box leaves it through exactly one of them, also from inside
// the box, so each such pixel is shaded once. An empty box draws nothing (every vertex at one
// point). The box goes on to the fragment stage, which lays the fluid buffer over the picture
// (smoke_composite.frag).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "smoke_box.glsl"

layout(push_constant) uniform Draw {
    SmokeDraw draw;
};
layout(std430, binding = 2) readonly buffer Bounds {
    PigmentBounds bounds;
};

layout(location = 0) flat out vec3 boxLow;
layout(location = 1) flat out vec3 boxHigh;

// Two triangles per face, as corners (u, v) of the face's square.
const vec2 kCorners[6] =
    vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

mat4 viewProjection() {
    return inverse(draw.inverseViewProjection);
}

void main() {
    bool filled = pigmentBox(draw, bounds, boxLow, boxHigh);
    // Face f (0..5): axis f / 2, its low (even f) or high (odd f) side.
    int face = gl_VertexIndex / 6;
    int axis = face / 2;
    bool highSide = (face & 1) == 1;
    vec3 eye = draw.eye.xyz;
    bool turnedAway = highSide ? eye[axis] <= boxHigh[axis] : eye[axis] >= boxLow[axis];
    if (!filled || !turnedAway) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // degenerate: nothing rasterised
        return;
    }
    vec2 corner = kCorners[gl_VertexIndex % 6];
    vec3 p;
    p[axis] = highSide ? 1.0 : 0.0;
    p[(axis + 1) % 3] = corner.x;
    p[(axis + 2) % 3] = corner.y;
    vec4 clip = viewProjection() * vec4(mix(boxLow, boxHigh, p), 1.0);
    // Faces beyond the far plane are kept on it (the same pixels; the depth is not used).
    if (clip.w > 0.0) clip.z = min(clip.z, clip.w);
    gl_Position = clip;
}
