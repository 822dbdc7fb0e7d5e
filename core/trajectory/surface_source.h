// Uniform surface emission (Xu et al., section 3.3.3, eqs. 10-13): where a mesh's vertices are
// sparse, smoke is emitted from points spread evenly over its surface instead. Each triangle is
// scanned in UV space over its bounding rectangle (eq. 10) row by row; a point inside the
// triangle (both interpolation parameters of eqs. 11-12 in [0, 1]) is mapped back to model space
// by the same interpolation of the corners' positions (eq. 13), and of their normals and skin
// influences. The step is a distance on the surface: each triangle's UV step is the user's step
// scaled by the square root of its UV-to-model area ratio, so every triangle gets about one
// point per step² of its own area whatever its UV scale.
//
// Triangles without UVs, or degenerate in UV (no area there) or in model space, are skipped and
// counted. Meshes whose UVs overlap (two triangles, of any of its primitives, covering the centre
// of the same texel of a 1024² raster over the mesh's UV bounds, on more than 0.2% of the covered
// texels) are detected and named: overlapping UVs do not break this
// scan, but they break any emission done through a UV-space buffer.
#pragma once

#include "core/anim/character.h"
#include "core/trajectory/trajectory_source.h"

#include <string>
#include <vector>

namespace mfx::trajectory {

struct SurfaceReport {
    size_t triangles = 0;         // scanned
    size_t samples = 0;           // points made
    size_t withoutUv = 0;         // skipped: the primitive has no UVs
    size_t degenerateInUv = 0;    // skipped: no area in UV space
    size_t degenerateInModel = 0; // skipped: no area in model space
    std::vector<std::string> overlappingMeshes;
    // Per selected triangle (in Source::triangles order... of the original primitives): its
    // model-space area and the points it got; for checking the density.
    std::vector<double> triangleAreas;
    std::vector<size_t> triangleSamples;
};

// Points every `step` world units over the surface of the meshes (and bones) `selection` names,
// as a Source whose vertices are the points (no triangles). Fails like selectSource, or when
// `step` is not a positive finite number, or when it would make more than `maxSamples` points.
Result<Source> selectSurfaceSource(const anim::Character& character, const Selection& selection,
                                   float step, SurfaceReport* report = nullptr,
                                   size_t maxSamples = 2'000'000);

// Whether the triangles of `mesh` overlap in UV space (see above).
bool uvsOverlap(const anim::Mesh& mesh);

} // namespace mfx::trajectory
