// What motionfx view plays: a scene, its simulation (which only runs forwards, so going back
// re-simulates from the start) and its drawing, the camera the user moved, and the scene read
// again from its files when they change (hot reload).
#pragma once

#include "apps/commands.h"
#include "render/orbit_camera.h"
#include "render/scene_player.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mfx::app {

class ViewSession {
public:
    // Plays `first`, read from the command line `parsed` (read again on reload()).
    ViewSession(const gpu::Context& ctx, const cli::ParsedArgs& parsed, const char* defaultSize,
                SceneArgument first, VkSampleCountFlagBits samples);

    // Back to before the first frame (the next record() draws frame 0).
    Status start();
    // Brings the simulation to just before frame `target` (simulating without drawing, from the
    // start when going back); the frame itself is simulated by the next record().
    Status seek(uint32_t target);
    // Records frame shown() + 1 when `advance`, else the shown frame again.
    void record(VkCommandBuffer cmd, bool advance);
    sim::SimulationFrameStats finish();

    // Reads the scene (and its character) again through the command line's options. If it is
    // valid, it replaces the one playing: rebuilt and simulated up to the frame shown now, with
    // the camera the user moved and the effects hidden by name kept. If not, the scene playing
    // plays on and the error is returned. `lines` gets the notes of the reading.
    Status reload(std::vector<std::string>* lines = nullptr);
    // As reload(), from `scene` as read (a scene the panel edited) instead of the files.
    Status replace(scene::Scene scene, std::vector<std::string>* lines = nullptr);
    // The files the scene was read from: the scene file, the character files and the ribbon
    // textures it names (none for the built-in default scene and fighter).
    std::vector<std::filesystem::path> files() const;

    // The camera drawn: the scene's, or where the user moved it.
    scene::CameraSpec camera() const;
    bool cameraMoved() const { return orbit_.has_value(); }
    // A drag of (dx, dy) window pixels; a pan in a picture `viewportHeight` pixels tall.
    void orbit(float dx, float dy);
    void pan(float dx, float dy, float viewportHeight);
    void zoom(float steps);
    // Aims at the character's current pose from where the camera looks.
    void frameCharacter();
    // Back to the scene file's camera.
    void useSceneCamera() { orbit_.reset(); }

    int shown() const { return shown_; }
    uint32_t frameCount() const { return sim_->frameCount(); }
    float fps() const { return float(argument_->scene.output.fps); }
    render::FrameRenderer& renderer() { return player_->renderer(); }
    const scene::Scene& scene() const { return argument_->scene; }

private:
    render::OrbitCamera& orbitCamera();
    // Plays `read`, if it was read, from the frame shown (reload() and replace()).
    Status use(Result<SceneArgument> read);

    const gpu::Context& ctx_;
    const cli::ParsedArgs& parsed_;
    const char* defaultSize_;
    VkSampleCountFlagBits samples_;
    // The player's renderer refers to the character, so the three are replaced together.
    std::unique_ptr<SceneArgument> argument_;
    std::unique_ptr<sim::SceneSimulation> sim_;
    std::unique_ptr<render::ScenePlayer> player_;
    std::optional<render::OrbitCamera> orbit_;
    int shown_ = -1;
};

} // namespace mfx::app
