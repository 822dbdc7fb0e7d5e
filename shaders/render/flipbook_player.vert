// flipbookPlayer (vertex): the quad a flipbook is played on (shared/flipbook.h FlipbookPlay.quad),
// two triangles from the vertex index, with the cell's uv: (0, 0) at the quad's top-left corner,
// v growing downward as the sheet's rows do.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/flipbook.h"

layout(push_constant) uniform Play {
    FlipbookPlay play;
};

layout(location = 0) out vec2 uv;

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(1, 0), vec2(1, 1),
                                   vec2(0, 1));
    vec2 c = corners[gl_VertexIndex];
    uv = c;
    vec4 q = play.quad;
    gl_Position = vec4(mix(q.x, q.z, c.x), mix(q.w, q.y, c.y), 0.0, 1.0);
}
