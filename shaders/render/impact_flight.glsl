// A spark's flight: thrown from x0 with velocity v0 under gravity g (along -y) and linear drag k,
//   dv/dt = g - k v,
// whose solution is
//   v(t) = g/k + (v0 - g/k) e^(-kt),
//   x(t) = x0 + (g/k) t + (v0 - g/k) (1 - e^(-kt)) / k,
// and without drag (k -> 0) x0 + v0 t + g t^2 / 2. The closed form, not a step-by-step
// integration: a spark is where its path says at any frame rate. For small kt the two terms that
// cancel are expanded in series (the host's twin: core/scene/kinds/impact_effect.cpp sparkPosition).
#ifndef MFX_IMPACT_FLIGHT_GLSL
#define MFX_IMPACT_FLIGHT_GLSL

vec3 sparkPosition(vec3 x0, vec3 v0, float gravity, float drag, float t) {
    vec3 g = vec3(0.0, -gravity, 0.0);
    float kt = drag * t;
    // (1 - e^(-kt)) / k and (kt - 1 + e^(-kt)) / k^2, by series where kt is small.
    float reach = kt < 1e-3 ? t * (1.0 - 0.5 * kt + kt * kt / 6.0) : (1.0 - exp(-kt)) / drag;
    float fall = kt < 1e-3 ? t * t * (0.5 - kt / 6.0 + kt * kt / 24.0)
                           : (kt - 1.0 + exp(-kt)) / (drag * drag);
    return x0 + v0 * reach + g * fall;
}

#endif
