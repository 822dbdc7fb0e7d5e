// The default scene's kick recorded as a solver scenario (sim/scene_scenario.h): the recording
// has impulses, every field is finite and inside the domain, the mapping onto a scenario grid
// does not depend on its size, and the CPU reference runs it to finite fields with pigment.
#include "core/scene/kinds/smoke_effect.h"
#include "fluid/reference/reference_solver.h"
#include "sim/scene_scenario.h"
#include "tests/gpu_test.h"
#include "tests/moving_point.h"

#include <cmath>

namespace mfx::test {
namespace {

// The first 16 steps (the first 8 frames) of the default scene: enough for the tests, and one
// recording for every test of the suite keeps them quick on lavapipe.
constexpr uint32_t kSteps = 16;

class SceneScenarioTest : public GpuTest {
protected:
    static void SetUpTestSuite() {
        GpuTest::SetUpTestSuite();
        if (!hasContext()) return; // SetUp reports why
        const scene::Scene scene = scene::kickScene();
        Result<anim::Character> character = scene::loadCharacter(scene);
        if (!character) {
            recordingError_ = character.error().message;
            return;
        }
        ctx().clearValidationMessages();
        Result<sim::SceneImpulses> recorded =
            sim::recordSceneImpulses(ctx(), scene, character.value(), kSteps);
        ctx().waitIdle();
        if (ctx().validationErrorCount() > 0)
            recordingError_ = "validation errors while recording:\n" + describeMessages();
        else if (!recorded)
            recordingError_ = recorded.error().message;
        else
            impulses_ = std::make_unique<sim::SceneImpulses>(std::move(recorded).value());
    }
    static void TearDownTestSuite() {
        impulses_.reset();
        GpuTest::TearDownTestSuite();
    }
    void SetUp() override {
        GpuTest::SetUp();
        ASSERT_TRUE(impulses_) << "the recording failed: " << recordingError_;
    }

    static fluid::Scenario scenario(glm::uvec3 cells) {
        Result<fluid::Scenario> made = sim::makeSceneScenario(*impulses_, cells);
        EXPECT_TRUE(made.ok()) << made.error().message;
        return made ? std::move(made).value() : fluid::Scenario{};
    }

    static std::unique_ptr<sim::SceneImpulses> impulses_;
    static std::string recordingError_;
};

std::unique_ptr<sim::SceneImpulses> SceneScenarioTest::impulses_;
std::string SceneScenarioTest::recordingError_;

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Two smoke steps a frame (60 per second at 30 frames per second): both are recorded, each with
// its own records, though the grid's emitter buffer holds only the last after the frame.
TEST_F(SceneScenarioTest, EveryStepOfAFrameIsRecorded) {
    EXPECT_EQ(impulses_->stepsPerSecond, 60.0f);
    ASSERT_EQ(impulses_->steps.size(), kSteps); // the kick emits from its first step
    EXPECT_EQ(impulses_->firstStep, 0u);
    for (uint32_t step = 2; step < kSteps; ++step) {
        const auto& a = impulses_->steps[step - 1];
        const auto& b = impulses_->steps[step];
        ASSERT_EQ(a.size(), b.size());
        float apart = 0.0f;
        for (size_t i = 0; i < a.size(); ++i)
            apart = std::max(apart, glm::length(glm::vec3(a[i].positionRadius) -
                                                glm::vec3(b[i].positionRadius)));
        EXPECT_GT(apart, 1e-4f) << "steps " << step - 1 << " and " << step; // the foot moves
    }
}

TEST_F(SceneScenarioTest, KickHasStepsWithEmitters) {
    const fluid::Scenario s = scenario(glm::uvec3(16));
    EXPECT_EQ(s.name, "kick");
    EXPECT_FALSE(s.description.empty());
    EXPECT_LE(impulses_->steps.size(), kSteps);
    EXPECT_EQ(impulses_->dropped, 0u);
    uint32_t nonEmpty = 0;
    size_t most = 0;
    for (uint32_t step = 0; step < kSteps; ++step) {
        const size_t n = s.emitters(step).size();
        nonEmpty += n > 0;
        most = std::max(most, n);
    }
    std::printf("%u of %u steps with emitters, at most %zu per step\n", nonEmpty, kSteps, most);
    EXPECT_GT(nonEmpty, kSteps / 2);
    EXPECT_FALSE(s.emitters(0).empty()); // the recording starts with the first impulses
    EXPECT_TRUE(s.emitters(kSteps + 100).empty());
    // The scene grid's options, on the scenario's grid.
    EXPECT_FLOAT_EQ(s.options.dt, impulses_->options.dt);
    EXPECT_FLOAT_EQ(s.options.fade, impulses_->options.fade);
    EXPECT_EQ(s.options.boundaries[fluid::FaceLowY].kind, fluid::Boundary::WallFreeSlip);
    EXPECT_EQ(s.options.boundaries[fluid::FaceHighY].kind, fluid::Boundary::Open);
    EXPECT_EQ(s.options.grid.cellsX, 16u);
    EXPECT_FLOAT_EQ(s.options.grid.cellSize, 1.0f / 16.0f);
    EXPECT_TRUE(fluid::validateOptions(s.options).ok());
}

TEST_F(SceneScenarioTest, EveryFieldIsFiniteAndInsideTheDomain) {
    const fluid::Scenario s = scenario(glm::uvec3(16));
    const glm::vec3 extent = glm::vec3(16.0f) * s.options.grid.cellSize;
    float fastest = 0.0f;
    for (uint32_t step = 0; step < kSteps; ++step) {
        const std::vector<shared::FluidEmitter> emitters = s.emitters(step);
        EXPECT_TRUE(fluid::validateEmitters(emitters).ok()) << "step " << step;
        for (const shared::FluidEmitter& e : emitters) {
            ASSERT_TRUE(finite(e.positionRadius) && finite(e.velocityStrength) && finite(e.pigment))
                << "step " << step;
            const glm::vec3 p(e.positionRadius);
            const float r = e.positionRadius.w;
            EXPECT_GT(r, 0.0f);
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, glm::vec3(-r))) &&
                        glm::all(glm::lessThanEqual(p, extent + r)))
                << "step " << step << ": (" << p.x << ", " << p.y << ", " << p.z << ") r " << r;
            fastest = std::max(fastest, glm::length(glm::vec3(e.velocityStrength)));
        }
    }
    std::printf("fastest emitter: %.3g domain lengths per second\n", double(fastest));
    EXPECT_GT(fastest, 0.0f); // the foot moves
}

// The mapping is onto the domain: in units of the domain's extent, a 12^3 and a 24^3 grid (and a
// flat 24x12x24 one, axis by axis) get the same emitters.
TEST_F(SceneScenarioTest, TwoGridSizesGetTheSameEmittersInDomainUnits) {
    const fluid::Scenario a = scenario(glm::uvec3(12)), b = scenario(glm::uvec3(24));
    const fluid::Scenario flat = scenario(glm::uvec3(24, 12, 24));
    const glm::vec3 extentA = glm::vec3(12.0f) * a.options.grid.cellSize;
    const glm::vec3 extentB = glm::vec3(24.0f) * b.options.grid.cellSize;
    const glm::vec3 extentFlat = glm::vec3(24.0f, 12.0f, 24.0f) * flat.options.grid.cellSize;
    for (uint32_t step = 0; step < kSteps; ++step) {
        const auto ea = a.emitters(step), eb = b.emitters(step), ef = flat.emitters(step);
        ASSERT_EQ(ea.size(), eb.size());
        ASSERT_EQ(ea.size(), ef.size());
        for (size_t i = 0; i < ea.size(); ++i) {
            const glm::vec3 pa = glm::vec3(ea[i].positionRadius) / extentA;
            const glm::vec3 pb = glm::vec3(eb[i].positionRadius) / extentB;
            const glm::vec3 pf = glm::vec3(ef[i].positionRadius) / extentFlat;
            const glm::vec3 va = glm::vec3(ea[i].velocityStrength) / extentA;
            const glm::vec3 vb = glm::vec3(eb[i].velocityStrength) / extentB;
            const glm::vec3 vf = glm::vec3(ef[i].velocityStrength) / extentFlat;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(pa[c], pb[c], 1e-6f);
                EXPECT_NEAR(pa[c], pf[c], 1e-6f);
                EXPECT_NEAR(va[c], vb[c], 1e-5f * (1.0f + std::abs(va[c])));
                EXPECT_NEAR(va[c], vf[c], 1e-5f * (1.0f + std::abs(va[c])));
            }
            EXPECT_NEAR(ea[i].positionRadius.w / extentA.x, eb[i].positionRadius.w / extentB.x,
                        1e-6f);
            EXPECT_EQ(ea[i].velocityStrength.w, eb[i].velocityStrength.w);
            EXPECT_EQ(ea[i].pigment, eb[i].pigment);
        }
    }
}

TEST_F(SceneScenarioTest, CpuReferenceRunLeavesPigmentAndFiniteFields) {
    const fluid::Scenario s = scenario(glm::uvec3(16));
    fluid::ReferenceSolver ref(s.options);
    ref.setState(s.initial);
    for (uint32_t step = 0; step < 6; ++step) {
        const std::vector<shared::FluidEmitter> emitters = s.emitters(step);
        for (fluid::Stage stage : fluid::stepOrder())
            ref.runStage(stage, emitters);
    }
    const fluid::FieldState state = ref.state();
    double pigment = 0.0, speed = 0.0;
    for (const std::vector<float>* field :
         {&state.velocityX, &state.velocityY, &state.velocityZ, &state.pressure, &state.pigment})
        for (float v : *field)
            ASSERT_TRUE(std::isfinite(v));
    for (size_t i = 3; i < state.pigment.size(); i += 4)
        pigment += double(state.pigment[i]);
    for (float v : state.velocityX)
        speed = std::max(speed, double(std::abs(v)));
    std::printf("total pigment alpha %.4g, largest |u| %.4g\n", pigment, speed);
    EXPECT_GT(pigment, 0.0);
    EXPECT_GT(speed, 0.0);
}

// A grid that follows the character moves by whole cells; its records, moved back by as much,
// are those of a grid that stays where it was placed.
TEST_F(SceneScenarioTest, FollowingGridIsRecordedWhereItWasPlaced) {
    const anim::Character point = movingPoint();
    Result<scene::Scene> parsed = scene::parseScene(R"({
        "character": {"source": "point.gltf"},
        "output": {"fps": 30, "frames": 24},
        "effects": [{"type": "smoke", "grid": [16, 8, 8], "cell_size": 0.1,
                     "steps_per_second": 30, "follow": true}]})",
                                                    "follow.json");
    ASSERT_TRUE(parsed.ok()) << parsed.error().message;
    scene::Scene still = parsed.value();
    still.effects[0].as<scene::SmokeSpec>()->grid.follow = false;
    auto following = sim::recordSceneImpulses(ctx(), parsed.value(), point);
    auto staying = sim::recordSceneImpulses(ctx(), still, point);
    ASSERT_TRUE(following.ok()) << following.error().message;
    ASSERT_TRUE(staying.ok()) << staying.error().message;
    ASSERT_EQ(following.value().steps.size(), staying.value().steps.size());
    EXPECT_EQ(following.value().steps.size(), 24u);
    for (size_t step = 0; step < staying.value().steps.size(); ++step) {
        const auto& a = following.value().steps[step];
        const auto& b = staying.value().steps[step];
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a[i].positionRadius[c], b[i].positionRadius[c], 1e-5f)
                    << "step " << step;
    }
    // The point slides 1.15 m in 23 steps: the following grid moved, the records did not jump.
    const glm::vec3 first(staying.value().steps.front().front().positionRadius);
    const glm::vec3 last(staying.value().steps.back().front().positionRadius);
    EXPECT_NEAR(last.x - first.x, 1.5f * 23.0f / 30.0f, 0.01f);
}

TEST_F(SceneScenarioTest, BadInputsAreErrors) {
    EXPECT_FALSE(sim::makeSceneScenario(*impulses_, glm::uvec3(16, 0, 16)).ok());
    const scene::Scene kick = scene::kickScene();
    Result<anim::Character> fighter = scene::loadCharacter(kick);
    ASSERT_TRUE(fighter.ok());
    EXPECT_FALSE(sim::recordSceneImpulses(ctx(), kick, fighter.value(), 0).ok());
    scene::Scene noSmoke = scene::kickScene();
    std::erase_if(noSmoke.effects,
                  [](const scene::EffectSpec& e) { return e.is<scene::SmokeSpec>(); });
    Result<anim::Character> character = scene::loadCharacter(noSmoke);
    ASSERT_TRUE(character.ok());
    Result<sim::SceneImpulses> none =
        sim::recordSceneImpulses(ctx(), noSmoke, character.value(), 4);
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("no smoke effect"), std::string::npos)
        << none.error().message;
}

} // namespace
} // namespace mfx::test
