// The skinning pass on the GPU: dual quaternion skinning with scale of a vertex buffer by a joint
// palette, both in storage buffers (shaders/core/skin_vertices.comp; CPU twin: anim::skinDualQuat).
// Each frame the caller writes a palette for t (and one for t - dt) and records one dispatch per
// palette.
#pragma once

#include "core/anim/skinning.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "shaders/shared/skinning.h"

#include <map>
#include <tuple>
#include <vector>

namespace mfx::anim {

// The palette as the shader reads it.
std::vector<shared::SkinJoint> packPalette(const std::vector<DualQuatJoint>& palette);
// A primitive's bind-pose vertices as the shader reads them (an unskinned primitive gets joint 0
// with weight 1: pair it with a one-joint palette holding its node's world matrix).
std::vector<shared::SkinVertexIn> packVertices(const Primitive& primitive);

class SkinVertices {
public:
    explicit SkinVertices(const gpu::Context& ctx);

    // Records the skinning of `vertexCount` vertices of `input` (SkinVertexIn) with `palette`
    // (`jointCount` SkinJoint) into `output` (SkinVertexOut), then a barrier making the output
    // visible to later compute, vertex and transfer reads.
    void record(VkCommandBuffer cmd, const gpu::Buffer& palette, uint32_t jointCount,
                const gpu::Buffer& input, const gpu::Buffer& output, uint32_t vertexCount);

private:
    gpu::Program program_;
};

} // namespace mfx::anim
