// Structures of the self-test shaders (selftest_*), which check the GPU layer itself: compute
// dispatch and readback, 3D storage images, and the geometry stage.
#ifndef MFX_SHARED_SELFTEST_H
#define MFX_SHARED_SELFTEST_H

#include "common.h"

// Workgroup size of selftest_saxpy.comp.
#define MFX_SAXPY_GROUP_SIZE 64
// Workgroup size of selftest_fill_volume.comp in each dimension.
#define MFX_FILL_VOLUME_GROUP_SIZE 4

MFX_SHARED_BEGIN

// y[i] = a * x[i] + y[i], repeated `iterations` times (a longer dispatch for timer tests).
struct SaxpyConstants {
    float a;
    uint count;
    uint iterations;
    uint padding;
};

// volume(x, y, z) = x + 1000 y + 1000000 z + offset, for every texel of a size.xyz volume.
struct FillVolumeConstants {
    uvec4 size;
    float offset;
    float padding0;
    float padding1;
    float padding2;
};

// Each point becomes a screen-aligned quad of the given half size (in NDC), in one colour.
struct PointsToQuadsConstants {
    vec4 color;
    vec2 halfSize;
    vec2 padding;
};

// result[i] = texture(volume, coordinates[i].xyz) for i < count (normalised coordinates).
struct SampleVolumeConstants {
    uint count;
    uint padding0;
    uint padding1;
    uint padding2;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SaxpyConstants, 16);
MFX_CHECK_LAYOUT(SaxpyConstants, iterations, 8);
MFX_CHECK_SIZE(FillVolumeConstants, 32);
MFX_CHECK_LAYOUT(FillVolumeConstants, offset, 16);
MFX_CHECK_SIZE(PointsToQuadsConstants, 32);
MFX_CHECK_SIZE(SampleVolumeConstants, 16);
MFX_CHECK_LAYOUT(PointsToQuadsConstants, halfSize, 16);
#endif

#endif
