// Hits between characters (core/scene/scene_hits.h): a kick that reaches the other fighter lands
// once, where and when its capsules first touch; one that falls short lands nowhere; an impact's
// window and target are kept; the hit-stop holds every clip for exactly its frames while the scene
// goes on; `motionfx scene` lists the hits; the impact's sparks fly on their ballistic paths.
#include "cli_run.h"
#include "core/anim/body_capsules.h"
#include "core/anim/capsule_contact.h"
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene.h"
#include "core/scene/scene_fit.h"
#include "core/scene/scene_hits.h"
#include "gpu_test.h"
#include "render/image_output.h"
#include "render/kinds/impact_pass.h"
#include "render/render_target.h"
#include "scene_render_util.h"
#include "sim/scene_simulation.h"

#include <gtest/gtest.h>

namespace mfx::test {
namespace {

// "red" kicks at "blue", who stands `apart` metres away facing it; an impact on red's right leg.
std::string duel(float apart, const std::string& impactKeys = "") {
    const float half = 0.5f * apart;
    return R"({"characters": [
        {"name": "red", "clip": "roundhouse_kick", "position": [)" +
           std::to_string(-half) + R"(, 0, 0], "yaw_degrees": 90},
        {"name": "blue", "clip": "idle", "position": [)" +
           std::to_string(half) + R"(, 0, 0], "yaw_degrees": -90}],
      "effects": [{"type": "impact", "name": "kick impact", "bones": ["right_leg"])" +
           impactKeys + "}]}";
}

// A spark's flight, dv/dt = g - k v (g along -y), integrated by fourth-order Runge-Kutta in
// `steps` steps over `seconds`: where it is then.
glm::dvec3 integrateFlight(glm::dvec3 x, glm::dvec3 v, double gravity, double drag, double seconds,
                           int steps) {
    const double dt = seconds / steps;
    auto accel = [&](glm::dvec3 vel) { return glm::dvec3(0.0, -gravity, 0.0) - drag * vel; };
    for (int i = 0; i < steps; ++i) {
        const glm::dvec3 k1v = accel(v), k1x = v;
        const glm::dvec3 k2v = accel(v + 0.5 * dt * k1v), k2x = v + 0.5 * dt * k1v;
        const glm::dvec3 k3v = accel(v + 0.5 * dt * k2v), k3x = v + 0.5 * dt * k2v;
        const glm::dvec3 k4v = accel(v + dt * k3v), k4x = v + dt * k3v;
        x += dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    return x;
}

struct Fitted {
    scene::Scene scene;
    scene::Cast cast;
};

Fitted fitted(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "duel.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    Fitted f;
    if (!s) return f;
    f.scene = std::move(s).value();
    f.cast = {anim::makeFighter(), anim::makeFighter()};
    const Status ok = scene::fitScene(f.scene, f.cast);
    EXPECT_TRUE(ok.ok()) << ok.error().message;
    return f;
}

TEST(SceneHits, AKickThatReachesLandsOnceWhereTheCapsulesFirstTouch) {
    const Fitted f = fitted(duel(1.0f));
    ASSERT_TRUE(f.scene.hitsFound);
    ASSERT_EQ(f.scene.hits.size(), 1u);
    const scene::Hit& h = f.scene.hits[0];
    RecordProperty("hit", std::to_string(h.time) + " s " + h.attackerBone + " on " + h.targetBone +
                              " " + std::to_string(h.speed) + " m/s");
    EXPECT_EQ(h.attacker, 0u);
    EXPECT_EQ(h.target, 1u);
    const std::vector<std::string> leg = {"thigh_r", "shin_r", "foot_r", "toe_r"};
    EXPECT_NE(std::find(leg.begin(), leg.end(), h.attackerBone), leg.end()) << h.attackerBone;
    // The strike of the roundhouse kick (0.25-0.55 s of the clip), at speed.
    EXPECT_GT(h.time, 0.2f);
    EXPECT_LT(h.time, 0.6f);
    EXPECT_EQ(h.frame, uint32_t(std::ceil(h.time * 30.0f - 1e-4f)));
    EXPECT_GT(h.speed, 2.0f);
    // Between the two fighters, on the kicker's leg: the two capsules touch there and then.
    const scene::Scene& s = f.scene;
    auto capsule = [&](size_t c, const std::string& bone) {
        for (const anim::BodyCapsule& b : anim::fitBodyCapsules(f.cast[c]))
            if (f.cast[c].nodes[size_t(b.node)].name == bone) {
                anim::PosedCapsule p =
                    anim::poseCapsule(b, scene::characterPose(s, c, f.cast[c], h.time));
                const glm::mat4 m = scene::characterPlacement(s.characters[c]);
                p.a = glm::vec3(m * glm::vec4(p.a, 1.0f));
                p.b = glm::vec3(m * glm::vec4(p.b, 1.0f));
                return p;
            }
        ADD_FAILURE() << "no capsule on " << bone;
        return anim::PosedCapsule{};
    };
    const anim::PosedCapsule a = capsule(0, h.attackerBone), b = capsule(1, h.targetBone);
    const anim::SegmentPoints closest = anim::closestPoints(a.a, a.b, b.a, b.b);
    const float gap = glm::distance(closest.p, closest.q) - a.radius - b.radius;
    RecordProperty("gapAtHit", std::to_string(gap));
    std::printf("hit at %.4f s, frame %u: %s on %s, %.2f m/s; the capsules' gap there %.2f mm\n",
                double(h.time), h.frame, h.attackerBone.c_str(), h.targetBone.c_str(),
                double(h.speed), double(gap) * 1e3);
    // Within the bisection's millionth of a frame of the leg's travel (a few m/s: micrometres),
    // and the clip sampled at that time rather than blended linearly over the frame: 5 mm.
    EXPECT_LT(std::abs(gap), 5e-3f);
    EXPECT_LT(std::abs(signedDistance(a, h.point)), 5e-3f);
    EXPECT_GT(h.point.x, -0.65f);
    EXPECT_LT(h.point.x, 0.65f);
}

TEST(SceneHits, AKickThatFallsShortLandsNowhere) {
    EXPECT_TRUE(fitted(duel(2.0f)).scene.hits.empty());
}

TEST(SceneHits, AnImpactLandsOnlyInItsWindowAndOnItsTarget) {
    EXPECT_TRUE(fitted(duel(1.0f, R"(, "end": 0.15)")).scene.hits.empty());
    EXPECT_EQ(fitted(duel(1.0f, R"(, "target": "blue")")).scene.hits.size(), 1u);
    Result<scene::Scene> self = scene::parseScene(duel(1.0f, R"(, "target": "red")"), "duel.json");
    ASSERT_FALSE(self.ok());
    EXPECT_EQ(self.error().message,
              "duel.json: effects[0].target: \"red\" is the character the impact follows; a blow "
              "lands on another");
    Result<scene::Scene> nobody =
        scene::parseScene(duel(1.0f, R"(, "target": "green")"), "duel.json");
    ASSERT_FALSE(nobody.ok());
    EXPECT_EQ(nobody.error().message,
              "duel.json: effects[0].target: no character \"green\"; characters are: red, blue");
}

// The hit-stop: the frame the hit lands in and the `hit_stop_frames` frames after it show the
// same poses, for both fighters; the frame after them goes on where the frame after the hit would
// have without the stop; the scene is that many frames longer.
TEST(SceneHits, HitStopHoldsEveryClipForExactlyTheFramesAsked) {
    const Fitted plain = fitted(duel(1.0f));
    const Fitted held = fitted(duel(1.0f, R"(, "hit_stop_frames": 5)"));
    ASSERT_EQ(held.scene.hits.size(), 1u);
    const scene::Hit& h = held.scene.hits[0];
    EXPECT_EQ(h.holdFrames, 5u);
    EXPECT_EQ(h.frame, plain.scene.hits[0].frame); // the first hit is where it was
    EXPECT_FLOAT_EQ(h.time, plain.scene.hits[0].time);
    EXPECT_EQ(scene::frameCount(held.scene, held.cast),
              scene::frameCount(plain.scene, plain.cast) + 5);
    const float fps = held.scene.output.fps;
    for (size_t c = 0; c < 2; ++c) {
        auto pose = [&](const Fitted& f, uint32_t frame) {
            return scene::characterPose(f.scene, c, f.cast[c], float(frame) / fps).world;
        };
        const auto atHit = pose(held, h.frame);
        for (uint32_t k = 1; k <= 5; ++k)
            EXPECT_EQ(pose(held, h.frame + k), atHit) << "frame " << h.frame + k;
        if (c == 0) { // the kicker moves on either side of the stop (blue idles slowly)
            EXPECT_NE(pose(held, h.frame - 1), atHit);
            EXPECT_NE(pose(held, h.frame + 6), atHit);
        }
        for (uint32_t k = 1; k <= 6; ++k) {
            const auto later = pose(held, h.frame + 5 + k), unheld = pose(plain, h.frame + k);
            for (size_t n = 0; n < later.size(); ++n)
                for (int col = 0; col < 4; ++col)
                    for (int row = 0; row < 4; ++row)
                        EXPECT_NEAR(later[n][col][row], unheld[n][col][row], 1e-5f);
        }
    }
}

TEST(SceneHits, TheShakeMovesTheCameraAfterAHitOnlyAndDiesOut) {
    const Fitted f = fitted(duel(1.0f, R"(, "shake": 0.05, "shake_seconds": 0.2)"));
    ASSERT_EQ(f.scene.hits.size(), 1u);
    const float t = f.scene.hits[0].time;
    EXPECT_EQ(scene::cameraShake(f.scene, t - 0.01f), glm::vec3(0.0f));
    EXPECT_EQ(scene::cameraShake(f.scene, t + 0.21f), glm::vec3(0.0f));
    float largest = 0.0f;
    for (int k = 0; k < 20; ++k)
        largest = std::max(largest, glm::length(scene::cameraShake(f.scene, t + 0.005f * k)));
    EXPECT_GT(largest, 0.01f);
    EXPECT_LE(largest, 0.05f * std::sqrt(3.0f));
}

// A scene whose effects were removed after its hits were found (as `bench effects` times the
// characters alone): the hits stay for their hit-stops, but nothing reads the impacts that are gone
// (no shake; the simulation and the frame play past the hit).
TEST(SceneHits, HitsWhoseImpactIsGoneHoldTheClipsAndDoNothingElse) {
    Fitted f = fitted(duel(1.0f, R"(, "shake": 0.05, "hit_stop_frames": 3)"));
    ASSERT_EQ(f.scene.hits.size(), 1u);
    const scene::Hit hit = f.scene.hits[0];
    f.scene.effects.clear();
    EXPECT_EQ(scene::hitImpact(f.scene, hit), nullptr);
    EXPECT_EQ(scene::cameraShake(f.scene, hit.time + 0.01f), glm::vec3(0.0f));
    EXPECT_EQ(scene::characterPose(f.scene, 0, f.cast[0], float(hit.frame) / 30.0f).world,
              scene::characterPose(f.scene, 0, f.cast[0], float(hit.frame + 3) / 30.0f).world);
}

// The sparks' closed form against the equation it solves, dv/dt = g - k v, integrated by fourth-
// order Runge-Kutta in 10,000 steps: within 1e-4 of the distance flown, with and without drag.
TEST(SceneHits, TheSparksClosedFormSolvesItsEquationOfMotion) {
    for (const float drag : {0.0f, 2.5f, 12.0f}) {
        const glm::dvec3 x0(0.1, 1.2, -0.3), v0(4.0, 3.0, -1.5);
        const double g = 9.81, T = 0.6;
        const glm::dvec3 x = integrateFlight(x0, v0, g, drag, T, 10000);
        const glm::vec3 closed =
            scene::sparkPosition(glm::vec3(x0), glm::vec3(v0), float(g), drag, float(T));
        EXPECT_LT(glm::distance(glm::dvec3(closed), x), 1e-4 * glm::distance(x, x0))
            << "drag " << drag;
    }
}

TEST(SceneHits, SparksAreThrownInTheConeAboutTheBlow) {
    scene::ImpactSpec impact;
    impact.sparks = 400;
    impact.sparkSpread = 30.0f;
    const glm::vec3 blow = glm::normalize(glm::vec3(1.0f, 0.2f, 0.0f));
    const auto sparks = scene::impactSparks(impact, glm::vec3(0.0f), blow, 0.5f, 3);
    ASSERT_EQ(sparks.size(), 400u);
    float widest = 0.0f;
    for (const scene::SparkLaunch& s : sparks) {
        const float speed = glm::length(s.velocity);
        EXPECT_GE(speed, 0.5f * impact.sparkSpeed - 1e-4f);
        EXPECT_LE(speed, 1.5f * impact.sparkSpeed + 1e-4f);
        EXPECT_GE(s.life, 0.6f * impact.sparkLife - 1e-6f);
        EXPECT_LE(s.life, impact.sparkLife + 1e-6f);
        EXPECT_FLOAT_EQ(s.time, 0.5f);
        widest = std::max(
            widest,
            glm::degrees(std::acos(std::clamp(glm::dot(s.velocity / speed, blow), -1.0f, 1.0f))));
    }
    EXPECT_LE(widest, 30.01f);
    EXPECT_GT(widest, 25.0f); // the cone is filled out to its edge
    // The same hit throws the same sparks; another hit others.
    EXPECT_EQ(scene::impactSparks(impact, glm::vec3(0.0f), blow, 0.5f, 3)[7].velocity,
              sparks[7].velocity);
    EXPECT_NE(scene::impactSparks(impact, glm::vec3(0.0f), blow, 0.5f, 4)[7].velocity,
              sparks[7].velocity);
}

TEST(Cli, SceneListsTheHits) {
    const std::string file = std::string(MFX_TEST_OUTPUT_DIR) + "/duel.json";
    std::ofstream(file) << duel(1.0f, R"(, "hit_stop_frames": 4)");
    const RunResult r = runMotionfx("scene \"" + file + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("hits         1\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("kick impact"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" on blue."), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("hit-stop 4 frames"), std::string::npos) << r.out;
}

using ImpactGpu = GpuTest;

// The sparks on the GPU (impact_sparks.comp) where the equation of motion puts them: each live
// spark's head against the Runge-Kutta integration of dv/dt = g - k v from its launch, within 1%
// of the distance it flew, some frames after the hit.
TEST_F(ImpactGpu, SparksFollowTheirBallisticPaths) {
    const Fitted f = fitted(duel(1.0f, R"(, "sparks": 64, "drag": 3, "gravity": 9.81)"));
    ASSERT_EQ(f.scene.hits.size(), 1u);
    auto created = sim::SceneSimulation::create(ctx(), f.scene, f.cast);
    ASSERT_TRUE(created) << created.error().message;
    sim::SceneSimulation& simulation = *created.value();
    render::ImpactPass pass(ctx(), simulation.scene(), simulation.cast());
    const uint32_t frame = f.scene.hits[0].frame + 4;
    for (uint32_t k = 0; k <= frame; ++k)
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            simulation.recordFrame(cmd, k);
            pass.advance(cmd, simulation, k);
        });
    simulation.finishFrame();
    const std::vector<shared::ImpactSpark> sparks = pass.sparks(0);
    const std::vector<shared::ImpactStreak> streaks = pass.streaks(0);
    ASSERT_EQ(sparks.size(), 64u);
    ASSERT_EQ(streaks.size(), 64u);
    const double now = simulation.frameTime(frame);
    size_t alive = 0;
    for (size_t i = 0; i < sparks.size(); ++i) {
        const double age = now - double(sparks[i].origin.w);
        ASSERT_GT(age, 0.0);
        const glm::dvec3 x =
            integrateFlight(glm::dvec3(glm::vec3(sparks[i].origin)),
                            glm::dvec3(glm::vec3(sparks[i].velocity)), 9.81, 3.0, age, 2000);
        const double flown = glm::distance(x, glm::dvec3(sparks[i].origin));
        const double error = glm::distance(glm::dvec3(glm::vec3(streaks[i].head)), x);
        EXPECT_LT(error, 0.01 * flown) << "spark " << i;
        EXPECT_NEAR(double(streaks[i].head.w), age / double(sparks[i].velocity.w), 1e-4);
        alive += streaks[i].head.w < 1.0f;
    }
    EXPECT_GT(alive, 0u);
}

// The impact's burst into the smoke: a grid around the kick (smoke from red's foot) holds more
// pigment near the contact point, and its air there moves more along the blow (the sum of the
// cells' velocity along it), after the step of the hit with a burst than without one.
TEST_F(ImpactGpu, AHitBurstsIntoTheSmokeWhereItLands) {
    auto run = [&](float impulse, double& pigmentNear, double& alongNear) {
        const std::string smoke =
            R"(, {"type": "smoke", "name": "foot smoke", "character": "red",
                  "bones": ["foot_r", "toe_r"], "strength": 0.5, "grid": [48, 48, 48]})";
        std::string text = duel(1.0f, R"(, "smoke_impulse": )" + std::to_string(impulse));
        text.insert(text.size() - 2, smoke);
        Fitted f = fitted(text);
        ASSERT_EQ(f.scene.hits.size(), 1u);
        auto created = sim::SceneSimulation::create(ctx(), f.scene, f.cast);
        ASSERT_TRUE(created) << created.error().message;
        sim::SceneSimulation& simulation = *created.value();
        const scene::Hit hit = simulation.scene().hits[0];
        for (uint32_t k = 0; k <= hit.frame; ++k)
            simulation.runFrame(k);
        auto& grid = simulation.smokeGrids()[0];
        const fluid::FieldState state = grid.grid.state(); // in cells' world units
        const fluid::GridShape& g = state.grid;
        const glm::vec3 p = (hit.point - grid.grid.origin()) / g.cellSize;
        pigmentNear = alongNear = 0.0;
        for (int k = -2; k <= 2; ++k)
            for (int j = -2; j <= 2; ++j)
                for (int i = -2; i <= 2; ++i) {
                    const glm::ivec3 c = glm::ivec3(p) + glm::ivec3(i, j, k);
                    if (glm::any(glm::lessThan(c, glm::ivec3(1))) || c.x >= int(g.cellsX) - 1 ||
                        c.y >= int(g.cellsY) - 1 || c.z >= int(g.cellsZ) - 1)
                        continue;
                    pigmentNear += double(state.pigment[g.index(c.x, c.y, c.z) * 4 + 3]);
                    // The cell's velocity: the mean of the faces on either side, per axis.
                    const size_t x0 = c.x + size_t(g.cellsX + 1) * (c.y + size_t(g.cellsY) * c.z);
                    const size_t y0 = c.x + size_t(g.cellsX) * (c.y + size_t(g.cellsY + 1) * c.z);
                    const size_t z0 = g.index(c.x, c.y, c.z);
                    const glm::dvec3 v(
                        0.5 * double(state.velocityX[x0] + state.velocityX[x0 + 1]),
                        0.5 * double(state.velocityY[y0] + state.velocityY[y0 + g.cellsX]),
                        0.5 * double(state.velocityZ[z0] +
                                     state.velocityZ[z0 + size_t(g.cellsX) * g.cellsY]));
                    alongNear += glm::dot(v, glm::dvec3(glm::normalize(hit.direction)));
                }
    };
    double pigmentWith = 0, alongWith = 0, pigmentWithout = 0, alongWithout = 0;
    run(6.0f, pigmentWith, alongWith);
    run(0.0f, pigmentWithout, alongWithout);
    const std::string measured =
        std::to_string(pigmentWith) + " vs " + std::to_string(pigmentWithout) + " alpha, " +
        std::to_string(alongWith) + " vs " + std::to_string(alongWithout) + " m/s along the blow";
    RecordProperty("near", measured);
    std::printf("near the hit: %s\n", measured.c_str());
    EXPECT_GT(pigmentWith, pigmentWithout + 1.0);
    EXPECT_GT(alongWith, alongWithout + 10.0);
}

TEST_F(ImpactGpu, AFrameWithoutTheImpactsOfItsHitsPlaysPastThem) {
    Result<scene::Scene> s =
        scene::parseScene(duel(1.0f, R"(, "shake": 0.05, "hit_stop_frames": 3)"), "duel.json");
    ASSERT_TRUE(s) << s.error().message;
    scene::Scene scene = s.value();
    scene::Cast cast = {anim::makeFighter(), anim::makeFighter()};
    ASSERT_TRUE(scene::fitScene(scene, cast).ok());
    ASSERT_EQ(scene.hits.size(), 1u);
    scene.effects.clear();
    Result<DrawnScene> drawn = drawScene(ctx(), scene, 160, 90, VK_SAMPLE_COUNT_1_BIT);
    ASSERT_TRUE(drawn) << drawn.error().message;
    drawn.value().playTo(ctx(), scene.hits[0].frame + 4);
    EXPECT_EQ(drawn.value().played, scene.hits[0].frame + 5);
}

// The frame draws the impact where the hit lands: the frame after the hit, the pixels around the
// contact point (projected by the scene's camera) are brighter with sparks, flash and ring than
// with an impact that draws none of them; far from it the two frames are the same but for the
// flash's bloom.
TEST_F(ImpactGpu, TheFrameDrawsTheImpactWhereTheHitLands) {
    auto frameAfterHit = [&](const std::string& keys, scene::Hit& hit, glm::vec2& at) {
        Result<scene::Scene> s = scene::parseScene(duel(1.0f, keys), "duel.json");
        EXPECT_TRUE(s) << s.error().message;
        Result<DrawnScene> drawn = drawScene(ctx(), s.value(), 320, 180, VK_SAMPLE_COUNT_1_BIT);
        EXPECT_TRUE(drawn) << drawn.error().message;
        const scene::Scene& fittedScene = drawn.value().simulation->scene();
        EXPECT_EQ(fittedScene.hits.size(), 1u);
        hit = fittedScene.hits.at(0);
        drawn.value().playTo(ctx(), hit.frame + 1);
        const glm::vec4 clip =
            drawn.value().renderer->camera().viewProjection * glm::vec4(hit.point, 1.0f);
        // Pixel rows run down the picture, clip-space y up (the target flips it).
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        at = glm::vec2(0.5f + 0.5f * ndc.x, 0.5f - 0.5f * ndc.y) * glm::vec2(320.0f, 180.0f);
        std::vector<uint8_t> pixels = render::readColor(ctx(), drawn.value().renderer->output());
        (void)render::writePng(std::string(MFX_TEST_OUTPUT_DIR) + "/impact_frame" +
                                   std::to_string(keys.size()) + ".png",
                               320, 180, pixels);
        return pixels;
    };
    scene::Hit hit;
    glm::vec2 at;
    const std::vector<uint8_t> with = frameAfterHit(R"(, "ring": "camera")", hit, at);
    const std::vector<uint8_t> without =
        frameAfterHit(R"(, "sparks": 0, "flash_size": 0, "ring": "none")", hit, at);
    ASSERT_EQ(with.size(), without.size());
    double nearWith = 0, nearWithout = 0, farDifference = 0, farPixels = 0;
    for (int y = 0; y < 180; ++y)
        for (int x = 0; x < 320; ++x) {
            const size_t i = (size_t(y) * 320 + size_t(x)) * 4;
            const double a = with[i] + with[i + 1] + with[i + 2];
            const double b = without[i] + without[i + 1] + without[i + 2];
            if (glm::distance(glm::vec2(x, y), at) < 12.0f) {
                nearWith += a;
                nearWithout += b;
            } else if (glm::distance(glm::vec2(x, y), at) > 90.0f) {
                farDifference += std::abs(a - b);
                ++farPixels;
            }
        }
    RecordProperty("near", std::to_string(nearWith) + " vs " + std::to_string(nearWithout));
    std::printf("hit at pixel (%.1f, %.1f): near %.0f vs %.0f, far difference %.0f\n", double(at.x),
                double(at.y), nearWith, nearWithout, farDifference);
    EXPECT_GT(nearWith, 1.2 * nearWithout);
    // Far from it only the bloom of the flash reaches: under a tenth of a level a pixel.
    EXPECT_LT(farDifference / farPixels, 0.1);
}

} // namespace
} // namespace mfx::test
