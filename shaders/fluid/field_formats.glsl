// The image formats of the smoke solver's stored fields (SolverOptions::storage): 32-bit floats,
// or binary16 in the variants compiled with MFX_HALF_STORAGE (shaders/CMakeLists.txt; docs/fluid.md,
// "fp16 storage"). Divergence, vorticity and the confinement force stay 32-bit in both.
#ifndef MFX_FIELD_FORMATS_GLSL
#define MFX_FIELD_FORMATS_GLSL

#ifdef MFX_HALF_STORAGE
#define MFX_VELOCITY_FORMAT r16f
#define MFX_PRESSURE_FORMAT r16f
#define MFX_PIGMENT_FORMAT rgba16f
#else
#define MFX_VELOCITY_FORMAT r32f
#define MFX_PRESSURE_FORMAT r32f
#define MFX_PIGMENT_FORMAT rgba32f
#endif

// The value a stage stores into a field image. With binary16 images: rounded to the nearest
// binary16 value, ties to even, in fp32 arithmetic (the reference's rounding,
// fluid/reference/half_storage.cpp), so that the store's own conversion is exact. Drivers may
// convert by truncation (lavapipe does), which biases every stored value towards 0 and over 100
// steps of the puff shrank the fields by about 10 % against the reference.
float roundToHalf(float v) {
    if (v == 0.0 || isinf(v) || isnan(v)) return v;
    int e;
    frexp(v, e); // |v| = m 2^e, m in [0.5, 1): binade 2^(e - 1)
    int spacing = max(e - 1, -14) - 10;
    float r = ldexp(roundEven(ldexp(v, -spacing)), spacing); // scalings by 2^k are exact
    return abs(r) > 65504.0 ? sign(v) * uintBitsToFloat(0x7f800000u) : r;
}
#ifdef MFX_HALF_STORAGE
#define MFX_STORED(v) roundToHalf(v)
#define MFX_STORED4(v) \
    vec4(roundToHalf((v).x), roundToHalf((v).y), roundToHalf((v).z), roundToHalf((v).w))
#else
#define MFX_STORED(v) (v)
#define MFX_STORED4(v) (v)
#endif

#endif
