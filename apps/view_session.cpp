#include "apps/view_session.h"

#include "core/scene/kinds/trail_effects.h"
#include "core/scene/ribbon_texture.h"
#include "core/scene/scene_fit.h"

#include <algorithm>

namespace mfx::app {

ViewSession::ViewSession(const gpu::Context& ctx, const cli::ParsedArgs& parsed,
                         const char* defaultSize, SceneArgument first,
                         VkSampleCountFlagBits samples)
    : ctx_(ctx), parsed_(parsed), defaultSize_(defaultSize), samples_(samples),
      argument_(std::make_unique<SceneArgument>(std::move(first))) {}

Status ViewSession::start() {
    auto created = sim::SceneSimulation::create(ctx_, argument_->scene, argument_->cast);
    if (!created) return created.error();
    sim_ = std::move(created).value();
    if (!player_)
        player_ = std::make_unique<render::ScenePlayer>(ctx_, *sim_, argument_->scene.output.width,
                                                        argument_->scene.output.height, samples_);
    else
        player_->setSimulation(*sim_);
    shown_ = -1;
    return Ok{};
}

Status ViewSession::seek(uint32_t target) {
    target = std::min(target, sim_->frameCount() - 1);
    if (shown_ >= 0 && target <= uint32_t(shown_)) {
        if (Status ok = start(); !ok) return ok;
    }
    for (uint32_t f = uint32_t(shown_ + 1); f < target; ++f)
        sim_->runFrame(f);
    shown_ = int(target) - 1;
    return Ok{};
}

void ViewSession::record(VkCommandBuffer cmd, bool advance) {
    player_->renderer().setCamera(camera());
    if (advance || shown_ < 0) {
        ++shown_;
        player_->record(cmd, uint32_t(shown_));
    } else {
        player_->recordRedraw(cmd, sim_->frameTime(uint32_t(shown_)));
    }
}

sim::SimulationFrameStats ViewSession::finish() {
    return player_->finish();
}

Status ViewSession::reload(std::vector<std::string>* lines) {
    return use(readSceneArgument(parsed_, defaultSize_, lines));
}

Status ViewSession::replace(scene::Scene scene, std::vector<std::string>* lines) {
    // The textures: a scene the panel edited, or a document read again, was parsed, not loaded
    // (loadScene checks them for every other scene).
    if (Status textures = scene::checkTextures(scene); !textures) return textures.error();
    return use(prepareSceneArgument(parsed_, defaultSize_, std::move(scene), lines));
}

Status ViewSession::use(Result<SceneArgument> read) {
    if (!read) return read.error();
    auto argument = std::make_unique<SceneArgument>(std::move(read).value());
    auto created = sim::SceneSimulation::create(ctx_, argument->scene, argument->cast);
    if (!created) return created.error();
    std::unique_ptr<sim::SceneSimulation> sim = std::move(created).value();
    // The effects hidden now stay hidden, by name.
    std::vector<std::string> hidden;
    for (size_t e = 0; e < scene().effects.size(); ++e)
        if (!player_->renderer().shown(e)) hidden.push_back(scene().effects[e].name);
    auto player = std::make_unique<render::ScenePlayer>(ctx_, *sim, argument->scene.output.width,
                                                        argument->scene.output.height, samples_);
    for (size_t e = 0; e < argument->scene.effects.size(); ++e)
        if (std::find(hidden.begin(), hidden.end(), argument->scene.effects[e].name) !=
            hidden.end())
            player->renderer().setShown(e, false);
    // Replaced in the order that keeps every reference valid: the player refers to the
    // simulation and the character, the simulation to the scene.
    const int at = shown_;
    player_ = std::move(player);
    sim_ = std::move(sim);
    argument_ = std::move(argument);
    shown_ = -1;
    if (at >= 0) return seek(uint32_t(at));
    return Ok{};
}

std::vector<std::filesystem::path> ViewSession::files() const {
    std::vector<std::filesystem::path> out;
    const scene::Scene& s = scene();
    if (!s.file.empty() && s.file[0] != '(') out.emplace_back(s.file);
    for (const scene::CharacterSpec& c : s.characters)
        if (std::filesystem::path character = scene::characterFile(s, c); !character.empty())
            out.push_back(character);
    // The ribbons' textures: a texture painted again is seen at once.
    for (const scene::EffectSpec& e : s.effects)
        if (const auto* lines = e.as<scene::SpeedLinesSpec>();
            lines && !lines->ribbon.texture.file.empty())
            out.push_back(scene::textureFile(s, lines->ribbon.texture.file));
    return out;
}

scene::CameraSpec ViewSession::camera() const {
    return orbit_ ? orbit_->apply(scene().camera) : scene().camera;
}

render::OrbitCamera& ViewSession::orbitCamera() {
    if (!orbit_) orbit_ = render::OrbitCamera::from(scene().camera);
    return *orbit_;
}

void ViewSession::orbit(float dx, float dy) {
    orbitCamera().orbit(dx, dy);
}

void ViewSession::pan(float dx, float dy, float viewportHeight) {
    orbitCamera().pan(dx, dy, scene().camera.fovDegrees, viewportHeight);
}

void ViewSession::zoom(float steps) {
    orbitCamera().zoom(steps);
}

void ViewSession::frameCharacter() {
    scene::Bounds world{glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (size_t c = 0; c < argument_->cast.size(); ++c) {
        const scene::Bounds pose = scene::poseBounds(argument_->cast[c], sim_->framePose(c));
        if (pose.empty()) continue;
        const glm::mat4 placement = sim_->placement(c);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? pose.high.x : pose.low.x,
                              (corner & 2) ? pose.high.y : pose.low.y,
                              (corner & 4) ? pose.high.z : pose.low.z);
            const glm::vec3 w = glm::vec3(placement * glm::vec4(p, 1.0f));
            world.low = glm::min(world.low, w);
            world.high = glm::max(world.high, w);
        }
    }
    if (world.empty()) return;
    orbitCamera().frame(world.centre(), 0.5f * glm::length(world.size()),
                        scene().camera.fovDegrees);
}

} // namespace mfx::app
