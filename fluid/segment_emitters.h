// The coupling of motion to smoke: the newest trajectory segment of a smoke effect becomes emitter
// records (position in the grid's frame, impulse velocity, colour as pigment, strength weighted by
// the segment's attenuation) in a GPU buffer the solver's splat reads (SmokeSolver::
// setEmitterBuffer). A compute pass, shaders/fluid/segment_emitters.comp; segmentEmitters is its
// CPU twin.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "shaders/shared/coupling.h"
#include "shaders/shared/fluid.h"
#include "shaders/shared/trajectory.h"

#include <glm/glm.hpp>
#include <map>
#include <span>
#include <utility>
#include <vector>

namespace mfx::fluid {

struct CouplingParameters {
    glm::vec3 gridOrigin{0.0f};    // world position of the grid's low corner
    float radius = 0.06f;          // splat radius, world units
    float strength = 1.0f;         // per second at full alpha
    uint32_t maxEmitters = 256;    // a segment of more vertices is sampled by whole source vertices
    uint32_t samplesPerVertex = 1; // S + 1 of the segment
};

// How many emitters a segment of `vertexCount` vertices gives: all of them, or as many whole
// source vertices (S + 1 samples each) as fit in maxEmitters (at least one).
uint32_t emitterCount(uint32_t vertexCount, const CouplingParameters& parameters);

// The emitters of `segment`, as the GPU pass writes them.
std::vector<shared::FluidEmitter> segmentEmitters(std::span<const shared::TrajectoryVertex> segment,
                                                  const CouplingParameters& parameters);

class SegmentEmitters {
public:
    explicit SegmentEmitters(const gpu::Context& ctx);

    // Records the conversion of vertices [firstVertex, firstVertex + vertexCount) of `ring` into
    // emitterCount() records of `emitters` from `firstEmitter` on, then a barrier making them
    // visible to the splat. Returns the number of records written.
    uint32_t record(VkCommandBuffer cmd, const gpu::Buffer& ring, uint32_t firstVertex,
                    uint32_t vertexCount, const gpu::Buffer& emitters, uint32_t firstEmitter,
                    const CouplingParameters& parameters);

private:
    gpu::Program program_;
};

} // namespace mfx::fluid
