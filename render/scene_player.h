// A scene, played frame by frame: the simulation's work and the drawing of each frame recorded
// into one command buffer, submitted, and, once it has finished, the frame finished: its
// statistics read back (the drawing passes among them as "render/<pass>") and the smoke grids'
// sleep decided (sim::SceneSimulation::finishFrame). `motionfx render`, `view`, `bench frame`
// and `bench effects` all play scenes through it (docs/architecture.md "One frame").
#pragma once

#include "core/gpu/timer.h"
#include "render/frame_renderer.h"
#include "sim/scene_simulation.h"

namespace mfx::render {

class ScenePlayer {
public:
    // Draws `simulation` into a target of `width` x `height` with up to `samples` samples per
    // pixel. The simulation may be replaced later (setSimulation) by another of the same scene.
    ScenePlayer(const gpu::Context& ctx, sim::SceneSimulation& simulation, uint32_t width,
                uint32_t height, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT);

    // Plays frame `frame` (frames in order, as the simulation requires): record, submit, wait,
    // finish. With `primitives`, the frame's primitives reaching the clipper are counted too.
    sim::SimulationFrameStats play(uint32_t frame,
                                   const gpu::PrimitiveCounter* primitives = nullptr);

    // The two halves of play() for a caller that submits itself (a window's frame): record the
    // simulation's frame `frame` and its drawing; after that submission finished, finish().
    void record(VkCommandBuffer cmd, uint32_t frame);
    sim::SimulationFrameStats finish();
    // Records the drawing of what the simulation holds at scene time `time` again, advancing
    // nothing (a paused view); needs no finish().
    void recordRedraw(VkCommandBuffer cmd, float time);

    // A new simulation of the same scene and character (a restart) from now on.
    void setSimulation(sim::SceneSimulation& simulation) { simulation_ = &simulation; }
    sim::SceneSimulation& simulation() { return *simulation_; }
    FrameRenderer& renderer() { return renderer_; }

private:
    const gpu::Context& ctx_;
    sim::SceneSimulation* simulation_;
    FrameRenderer renderer_;
    bool pending_ = false; // a recorded frame not yet finished
};

} // namespace mfx::render
