// The cartoon look's march (scene::CartoonSmoke), after S. Selle, A. Mohr and S. Chenney,
// "Cartoon rendering of smoke animations" (NPAR 2004), and M. McGuire and A. Fein, "Real-time
// rendering of cartoon smoke and clouds" (NPAR 2006): the smoke drawn as the surface where the
// live density crosses a threshold, shaded in flat bands from a lighting ramp (quantised in the
// composite, smoke_cartoon_composite.frag), with ink at its silhouette and depth steps. Both papers
// draw particles; here the surface is the threshold's level set of the solver's pigment volume,
// found by the march (smoke_march.glsl's samples, at the same places), so it is whatever shape the
// Navier-Stokes smoke has this frame.
//
// The field marched is f(p) = alpha(p) - T(p), alpha the pigment's trilinear alpha and
//   T(p) = threshold (1 + billow w b(p)),  b(p) = 1 - 2 |n(p)|,
// n two octaves of value noise at p / billow_scale (in [-1, 1]; each octave sliding by the
// billows' phase, so the outline boils like a hand-drawn one). |n|'s creases, where T is highest,
// pinch the surface in between round lobes: the silhouette reads as puffs. w = smoothstep(
// threshold (1 - 2 billow), threshold (1 - billow), alpha) turns the noise off where alpha is too
// low for any T to reach (f stays negative there and continuous), so the noise costs only near the
// surface.
//
// Per texel of the fluid buffer the march writes:
//   r: the margin m, the largest f along the ray (refined by a parabola through the samples around
//      it): > 0 where the ray meets the surface. m is continuous across the silhouette, so the
//      composite's bilinear m has its zero where the silhouette lies between the texels, at the
//      picture's resolution, and m / |grad m| is the distance to it in pixels (the outline's
//      width, the edge's coverage);
//   g: the light at the surface, 0..1 before quantising: the key light's diffuse share
//      (wrapped Lambert, (n.l + kCartoonWrap) / (1 + kCartoonWrap), clamped), times its
//      transmittance to the surface point (the self-shadow, light_transmittance.comp, quantised
//      into the same bands by the composite), plus rim (1 - n.v)^2 towards the silhouette;
//   b: 1 where the ray met the surface (the surface's light and distance are valid), else 0;
// and the distance image the surface's distance from the eye (MFX_SMOKE_NO_DISTANCE where none).
// The normal is -grad f / |grad f| by central differences (surfaceNormal).
#ifndef MFX_SMOKE_CARTOON_GLSL
#define MFX_SMOKE_CARTOON_GLSL

// A hash of a lattice point to [-1, 1] (M. Jarzynski and M. Olano, "Hash Functions for GPU
// Rendering", JCGT 2020: the pcg3d permutation).
float latticeValue(ivec3 q) {
    uvec3 v = uvec3(q) * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return float(v.x >> 8u) * (2.0 / 16777215.0) - 1.0;
}

// Value noise in [-1, 1]: the lattice's values blended by the quintic fade (smooth to the second
// derivative, so the normals have no creases of their own).
float valueNoise(vec3 p) {
    vec3 cell = floor(p);
    vec3 f = p - cell;
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    ivec3 q = ivec3(cell);
    float x00 = mix(latticeValue(q), latticeValue(q + ivec3(1, 0, 0)), u.x);
    float x10 = mix(latticeValue(q + ivec3(0, 1, 0)), latticeValue(q + ivec3(1, 1, 0)), u.x);
    float x01 = mix(latticeValue(q + ivec3(0, 0, 1)), latticeValue(q + ivec3(1, 0, 1)), u.x);
    float x11 = mix(latticeValue(q + ivec3(0, 1, 1)), latticeValue(q + ivec3(1, 1, 1)), u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

// n(p): one or two octaves (the second half the size, 0.4 of the weight), normalised to [-1, 1];
// each slides along its own direction by the billows' phase. More octaves make the outline
// ragged (torn paper) rather than puffed.
float billowNoise(vec3 p, int octaves) {
    float phase = style.surface.w;
    vec3 q = p / style.surface.z;
    float n = valueNoise(q + phase * vec3(0.0, -1.0, 0.35));
    if (octaves == 1) return n;
    n += 0.4 * valueNoise(2.03 * q + phase * vec3(0.8, -1.3, -0.6) + 17.0);
    return n / 1.4;
}

// f at p, whose pigment alpha is `alpha`, with `octaves` of billow noise.
float surfaceField(vec3 p, float alpha, int octaves) {
    float threshold = style.surface.x, billow = style.surface.y;
    float w = billow > 0.0 ? smoothstep(threshold * (1.0 - 2.0 * billow),
                                        threshold * (1.0 - billow), alpha)
                           : 0.0;
    float lobes = w > 0.0 ? 1.0 - 2.0 * abs(billowNoise(p, octaves)) : 0.0;
    return alpha - threshold * (1.0 + billow * w * lobes);
}

float surfaceField(vec3 p) {
    return surfaceField(p, sampleGrid(p).a, 2);
}

// The outward normal of the surface at p for its shading: -grad f, by central differences a cell
// wide, over the puffs' largest octave alone (the finer ones shape the silhouette; in the light
// they would only speckle the bands).
vec3 surfaceNormal(vec3 p) {
    float h = draw.gridOrigin.w;
    vec3 g;
    for (int axis = 0; axis < 3; ++axis) {
        vec3 e = vec3(0.0);
        e[axis] = h;
        g[axis] = surfaceField(p + e, sampleGrid(p + e).a, 1) -
                  surfaceField(p - e, sampleGrid(p - e).a, 1);
    }
    float len = length(g);
    return len > 1e-12 ? -g / len : vec3(0.0, 1.0, 0.0);
}

// How far the light wraps round past the terminator (Lambert: 0; half-Lambert: 1).
const float kCartoonWrap = 0.25;

// The ray through `texel`'s centre against the surface: (m, light, met, 0) and the surface's
// distance (MFX_SMOKE_NO_DISTANCE where the ray does not meet it).
vec4 marchCartoon(ivec2 texel, vec3 dir, out float surfaceDistance) {
    surfaceDistance = MFX_SMOKE_NO_DISTANCE;
    float threshold = style.surface.x;
    // Every texel marches to its block's farthest scene surface: the composite then cuts the
    // surface at each pixel's own depth, so a fighter in front of the smoke leaves no false
    // silhouette along its edge.
    float sceneDistance = sceneDistanceAt(blockPixel(texel, false));
    vec3 eye = draw.eye.xyz;
    vec3 inv = 1.0 / dir;
    vec2 box = crossBox(inv, boxLow, boxHigh);
    vec3 gridLow = draw.gridOrigin.xyz;
    float gridEnter = crossBox(inv, gridLow, gridLow + draw.gridOrigin.w * draw.gridSize.xyz).x;
    float tExit = min(box.y, sceneDistance + fadeDistance());
    if (tExit <= box.x) return vec4(-threshold, 0.0, 0.0, 0.0);
    float step = draw.gridOrigin.w / max(draw.gridSize.w, 0.25);
    int first = max(int((box.x - gridEnter) / step), 0);
    int end = min(int((tExit - gridEnter) / step) + 1, first + 512);
    // The largest f so far, its sample, and the samples' f on either side of it.
    float best = -threshold, before = -threshold, after = -threshold;
    int bestAt = -1;
    bool afterTaken = false; // whether `after` is the sample after the best one
    float previous = -threshold;
    int hitAt = -1; // the first sample inside the surface
    int afterHit = 0;
    for (int i = first; i < end; ++i) {
        float t = gridEnter + (float(i) + 0.5) * step;
        vec3 p = eye + t * dir;
#ifdef MFX_SPARSE_PIGMENT
        int last = lastEmptySample(i, p, inv, gridEnter, step);
        if (last > i) { // samples i..last read an empty brick alone: f = -threshold
            if (bestAt == i - 1) {
                after = -threshold;
                afterTaken = true;
            }
            previous = -threshold;
            i = last;
            continue;
        }
#endif
        float f = surfaceField(p);
        if (bestAt == i - 1) {
            after = f;
            afterTaken = true;
        }
        if (f > best) {
            best = f;
            bestAt = i;
            before = previous;
            afterTaken = false;
        }
        if (hitAt < 0 && f > 0.0) hitAt = i;
        // Past the surface, only the margin's peak is still wanted: a few samples on, or until f
        // falls.
        if (hitAt >= 0 && (++afterHit > 4 || f < previous)) break;
        previous = f;
    }
    if (bestAt < 0) return vec4(-threshold, 0.0, 0.0, 0.0);
    // The peak of the parabola through the best sample and its neighbours.
    float margin = best;
    float bestT = gridEnter + (float(bestAt) + 0.5) * step;
    float curvature = before - 2.0 * best + after;
    if (bestAt > first && afterTaken && curvature < 0.0) {
        float offset = clamp(0.5 * (before - after) / curvature, -0.5, 0.5);
        margin = max(best, best - 0.25 * (before - after) * offset);
        bestT += offset * step;
    }
    if (margin <= 0.0) return vec4(margin, 0.0, 0.0, 0.0);
    // The crossing between the first sample inside and the one before it (f <= 0), by bisection
    // (after the loop, so that on a SIMD device the lanes bisect together, not each at its own
    // step of the march); a grazing ray whose samples all fell outside meets it at the peak.
    float hitT = bestT;
    if (hitAt >= 0) {
        float high = gridEnter + (float(hitAt) + 0.5) * step, low = high - step;
        for (int k = 0; k < 5; ++k) {
            float mid = 0.5 * (low + high);
            if (surfaceField(eye + mid * dir) > 0.0)
                high = mid;
            else
                low = mid;
        }
        hitT = 0.5 * (low + high);
    }
    vec3 p = eye + hitT * dir;
    vec3 n = surfaceNormal(p);
    vec3 light = normalize(draw.light.xyz);
    float diffuse = clamp((dot(n, light) + kCartoonWrap) / (1.0 + kCartoonWrap), 0.0, 1.0);
    float facing = 1.0 - max(dot(n, -dir), 0.0);
    float lit = diffuse * lightTransmittance(p) + style.params.x * facing * facing;
    surfaceDistance = hitT;
    return vec4(margin, clamp(lit, 0.0, 1.0), 1.0, 0.0);
}

#endif
