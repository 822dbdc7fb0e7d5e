// Non-finite emitters: validateEmitters and SmokeSolver::setEmitters refuse NaN and Inf in every
// field, naming the emitter and the field, and the refusal leaves the GPU solver as it was.
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_stability_util.h"
#include "tests/gpu_test.h"

#include <limits>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using stability::Boundaries;
using stability::GpuSimulation;
using stability::kGrid;
using stability::usualEmitters;
using stability::usualOptions;

struct EmitterField {
    const char* name; // for messages
    const char* word; // what the error must name
    int vector;       // 0 positionRadius, 1 velocityStrength, 2 pigment
    int component;
};

constexpr EmitterField kEmitterFields[] = {
    {"position.x", "position", 0, 0}, {"position.y", "position", 0, 1},
    {"position.z", "position", 0, 2}, {"radius", "radius", 0, 3},
    {"velocity.x", "velocity", 1, 0}, {"velocity.y", "velocity", 1, 1},
    {"velocity.z", "velocity", 1, 2}, {"strength", "strength", 1, 3},
    {"pigment.r", "pigment", 2, 0},   {"pigment.g", "pigment", 2, 1},
    {"pigment.b", "pigment", 2, 2},   {"pigment.a", "pigment", 2, 3},
};

const float kNonFinite[] = {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()};

shared::FluidEmitter spoiled(shared::FluidEmitter e, const EmitterField& field, float value) {
    glm::vec4* vectors[3] = {&e.positionRadius, &e.velocityStrength, &e.pigment};
    (*vectors[field.vector])[field.component] = value;
    return e;
}

// The error names the emitter (by index) and the field.
void expectRefusal(const Status& status, size_t index, const EmitterField& field, float value,
                   const char* api) {
    const std::string what = std::string(api) + ", " + field.name + " = " + std::to_string(value);
    ASSERT_FALSE(status.ok()) << what << ": accepted";
    const std::string& message = status.error().message;
    EXPECT_NE(message.find("emitter " + std::to_string(index)), std::string::npos)
        << what << ": the error does not name emitter " << index << ": " << message;
    EXPECT_NE(message.find(field.word), std::string::npos)
        << what << ": the error does not name the " << field.word << ": " << message;
}

TEST(FluidStabilityEmitterValidation, ValidateEmittersRefusesNanAndInfNamingEmitterAndField) {
    const auto good = usualEmitters(kGrid, 1.0f);
    ASSERT_TRUE(fluid::validateEmitters(good).ok());
    for (const EmitterField& field : kEmitterFields)
        for (float value : kNonFinite) {
            // Alone (index 0) and behind a valid emitter (index 1).
            const std::vector<shared::FluidEmitter> alone{spoiled(good[0], field, value)};
            expectRefusal(fluid::validateEmitters(alone), 0, field, value, "validateEmitters");
            const std::vector<shared::FluidEmitter> second{good[0], spoiled(good[1], field, value)};
            expectRefusal(fluid::validateEmitters(second), 1, field, value, "validateEmitters");
        }
}

using FluidStabilityEmitterRefusal = GpuTest;

// setEmitters refuses every spoiled list, and the refusal leaves the solver as it was: a solver
// that was offered all of them steps exactly like one that only ever saw the valid emitters, and
// stays finite (a NaN that reached the emitter buffer would spread through the grid).
TEST_F(FluidStabilityEmitterRefusal, SetEmittersRefusesNanAndInfBeforeTheGpu) {
    const fluid::SolverOptions options = usualOptions(kGrid, Boundaries::Mixed);
    const auto good = usualEmitters(kGrid, 1.0f);
    auto offered = fluid::SmokeSolver::create(ctx(), options);
    auto clean = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(offered.ok() && clean.ok());
    fluid::SmokeSolver& a = *offered.value();
    fluid::SmokeSolver& b = *clean.value();
    ASSERT_TRUE(a.setEmitters(good).ok());
    ASSERT_TRUE(b.setEmitters(good).ok());
    GpuSimulation runA(ctx(), std::move(offered).value());
    GpuSimulation runB(ctx(), std::move(clean).value());
    runA.advance(5);
    runB.advance(5);
    for (const EmitterField& field : kEmitterFields)
        for (float value : kNonFinite) {
            const std::vector<shared::FluidEmitter> second{good[0], spoiled(good[1], field, value)};
            expectRefusal(a.setEmitters(second), 1, field, value, "SmokeSolver::setEmitters");
            const std::vector<shared::FluidEmitter> alone{spoiled(good[0], field, value)};
            expectRefusal(a.setEmitters(alone), 0, field, value, "SmokeSolver::setEmitters");
        }
    runA.advance(15);
    runB.advance(15);
    const fluid::FieldState sa = runA.state();
    const fluid::FieldState sb = runB.state();
    EXPECT_EQ(fluid::computeDiagnostics(options, sa).nonFinite, 0u);
    EXPECT_GT(fluid::computeDiagnostics(options, sb).maxPigment, 0.0) << "emitters had no effect";
    // Same device, same commands, no atomics: the two runs agree bit for bit.
    EXPECT_EQ(sa.velocityX, sb.velocityX);
    EXPECT_EQ(sa.velocityY, sb.velocityY);
    EXPECT_EQ(sa.velocityZ, sb.velocityZ);
    EXPECT_EQ(sa.pressure, sb.pressure);
    EXPECT_EQ(sa.pigment, sb.pigment);
}

} // namespace
} // namespace mfx::test
