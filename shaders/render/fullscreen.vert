// One triangle that covers the whole target (vertices 0, 1, 2 at clip (-1,-1), (3,-1), (-1,3)),
// for the passes that shade every pixel once: the tone map, and the host frame's depth copy and
// layer composite.
#version 450

void main() {
    vec2 corner = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
