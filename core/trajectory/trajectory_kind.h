// How a trajectory queue connects the samples of a segment (core/trajectory/trajectory_queue.h):
// points, lines between consecutive samples, or the side walls of the prisms the triangles sweep.
#pragma once

namespace mfx::trajectory {

enum class Kind { Particles, Lines, Volumes };

} // namespace mfx::trajectory
