// Speed-line sheets: the two lines of a sheet effect (scene "shape": "sheet": the bound part's
// vertex nearest to the joint it hangs from, then the farthest, trajectory::twoEnds) joined into
// one surface, each piece of the two lines a quad of two triangles (render/kinds/speed_lines_pass
// makes the index buffer). The second line is the outer edge, the path of the part's far end; the
// sheet reaches in from it towards the first line by `width` * width_over_life(u) world units
// (never past the first line), so it narrows with age and keeps its outer edge. `across` is 0 on
// the outer edge and 1 on the inner (effect_lines.frag: the outer edge opaque and white-hot with
// the core, the inner fading out). The colour is a speed-line's (effect_lines.vert). Consecutive
// segments weld bit for bit (build_segment.comp), so the outer edge is the far end's path,
// unbroken. The texture's u is the outer line's (ribbon_texture.glsl), v = `across`.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"
#include "ribbon_texture.glsl"
#include "shared/trajectory.h"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 2) in vec4 colour;

layout(location = 0) out vec4 ribbonColour;
layout(location = 1) out float across;
layout(location = 2) out vec3 tubeNormal;
layout(location = 3) out vec2 texCoord;
layout(location = 4) out float lifeOut;

// The ring itself, for the other line's sample (a segment's slot starts at a multiple of its
// 2 (S + 1) vertices; draw.ribbonShape.y = S + 1).
layout(std430, binding = 3) readonly buffer Ring {
    TrajectoryVertex ring[];
};
// Each ring vertex's distance along its line (ribbon_distance.comp); read only with the texture's
// distance mode.
layout(std430, binding = 4) readonly buffer Distances {
    float distances[];
};

void main() {
    float fade = ageFade(normal.w);
    float life = 1.0 - fade;
    if (draw.ribbonFlags.x > 0.5) {
        vec4 c = colourOverLife(life);
        ribbonColour = vec4(c.rgb * draw.tint.rgb, c.a * colour.a * draw.tint.a);
    } else {
        ribbonColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * fade);
    }
    uint perLine = uint(draw.ribbonShape.y + 0.5);
    uint index = uint(gl_VertexIndex);
    bool outer = index % (2u * perLine) >= perLine;
    vec3 p = position.xyz;
    if (!outer) {
        vec3 edge = ring[index + perLine].position.xyz; // the outer line's sample
        float span = length(p - edge);
        float reach = draw.timing.z * (draw.ribbonFlags.y > 0.5 ? widthOverLife(life) : 1.0);
        p = edge + (p - edge) * (span > 1e-9 ? min(reach / span, 1.0) : 0.0);
    }
    across = outer ? 0.0 : 1.0;
    tubeNormal = vec3(0.0);
    // Both lines' samples at one place along the segment share their time and tau.
    uint outerIndex = outer ? index : index + perLine;
    float distance = draw.ribbonTexture.x > 3.5 ? distances[outerIndex] : 0.0;
    texCoord = vec2(ribbonU(normal.w, position.w, distance), across);
    lifeOut = life;
    gl_Position = frame.viewProjection * vec4(p, 1.0);
}
