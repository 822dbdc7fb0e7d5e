// Motion particles: a square sprite facing the camera, `size` * size_over_life(u) across, or
// without that curve shrinking with alpha: size * (0.5 + 0.5 alpha).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

layout(location = 0) in vec4 vertexColour[];
layout(location = 1) in float vertexLife[];

layout(location = 0) out vec4 spriteColour;
layout(location = 1) out vec2 corner; // -1 .. 1

void main() {
    if (vertexColour[0].a <= 0.0) return;
    vec3 centre = gl_in[0].gl_Position.xyz;
    vec3 view = normalize(frame.cameraPosition.xyz - centre);
    vec3 right = normalize(cross(abs(view.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0), view));
    vec3 up = cross(view, right);
    float r = draw.ribbonFlags.y > 0.5 ? 0.5 * draw.timing.z * widthOverLife(vertexLife[0])
                                       : 0.5 * draw.timing.z * (0.5 + 0.5 * vertexColour[0].a);
    if (r <= 0.0) return;
    for (int j = -1; j <= 1; j += 2)
        for (int i = -1; i <= 1; i += 2) {
            spriteColour = vertexColour[0];
            corner = vec2(i, j);
            gl_Position = frame.viewProjection * vec4(centre + r * (float(i) * right + float(j) * up), 1.0);
            EmitVertex();
        }
    EndPrimitive();
}
