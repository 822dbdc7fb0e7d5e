#include "fluid/smoke_grid.h"

#include "shaders/shared/coupling.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mfx::fluid {

Result<SmokeGrid> SmokeGrid::create(const gpu::Context& ctx, SmokeGridSettings settings) {
    SmokeGrid grid;
    if (settings.sparse) {
        if (settings.follow)
            return Error{"a sparse grid stands still over its domain; it cannot follow"};
        if (Status valid = validateSparseOptions(settings.options); !valid) return valid.error();
        // Room for the first bricks; the atlas doubles up to the budget as the smoke spreads.
        auto sparse = SparseSmokeSolver::create(ctx, settings.options, settings.maxBricks,
                                                std::min(settings.maxBricks, 64u));
        if (!sparse) return sparse.error();
        grid.sparse_ = std::move(sparse).value();
    } else {
        auto solver = SmokeSolver::create(ctx, settings.options);
        if (!solver) return solver.error();
        grid.solver_ = std::move(solver).value();
    }
    // Transfer source for the simulation's emitter capture.
    grid.emitters_ = gpu::createBuffer(
        ctx, VkDeviceSize(settings.emitterCapacity) * sizeof(shared::FluidEmitter),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        gpu::MemoryUsage::DeviceLocal, "smoke emitters");
    grid.activity_ =
        gpu::createBuffer(ctx, 2 * sizeof(uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::Readback, "smoke activity");
    grid.settings_ = std::move(settings);
    return grid;
}

const SolverOptions& SmokeGrid::options() const {
    return sparse_ ? sparse_->options() : solver_->options();
}

const SmokeSolver& SmokeGrid::solver() const {
    if (!solver_) throw std::logic_error(settings_.name + " is sparse: it has no dense solver");
    return *solver_;
}

SmokeSolver& SmokeGrid::solver() {
    if (!solver_) throw std::logic_error(settings_.name + " is sparse: it has no dense solver");
    return *solver_;
}

FieldState SmokeGrid::state() {
    return sparse_ ? sparse_->state() : solver_->state();
}

std::vector<uint8_t> SmokeGrid::storedCells() const {
    if (sparse_) return sparse_->activeCells();
    return std::vector<uint8_t>(options().grid.cellCount(), 1);
}

std::vector<std::pair<std::string, uint32_t>> SmokeGrid::lastStepDispatches() const {
    if (!sparse_) return solver_->lastStepDispatches();
    std::vector<std::pair<std::string, uint32_t>> passes = {
        {"rebuild_bricks", sparse_->lastRebuildDispatches()}};
    const auto& stages = sparse_->lastStepDispatches();
    passes.insert(passes.end(), stages.begin(), stages.end());
    return passes;
}

void SmokeGrid::place(glm::vec3 low, glm::vec3 high, glm::vec3 fallback,
                      std::optional<float> floorHeight, glm::vec3 root) {
    const GridShape& shape = options().grid;
    const glm::vec3 extent =
        glm::vec3(float(shape.cellsX), float(shape.cellsY), float(shape.cellsZ)) * shape.cellSize;
    if (low.x > high.x) low = high = fallback + glm::vec3(0.0f, 0.5f * extent.y, 0.0f);
    origin_ = 0.5f * (low + high) - 0.5f * extent;
    if (floorHeight && origin_.y < *floorHeight && low.y >= *floorHeight) origin_.y = *floorHeight;
    if (settings_.origin) origin_ = *settings_.origin;
    placedOrigin_ = origin_;
    rootAtPlacement_ = root;
}

bool SmokeGrid::recordFollow(VkCommandBuffer cmd, glm::vec3 root) {
    if (!settings_.follow || !solver_) return false;
    const float h = solver_->options().grid.cellSize;
    glm::vec3 moved = root - rootAtPlacement_;
    moved.y = 0.0f;
    const glm::ivec3 cells = glm::ivec3(glm::round((placedOrigin_ + moved - origin_) / h));
    if (cells == glm::ivec3(0)) return false;
    origin_ += glm::vec3(cells) * h;
    if (!awake_) return false;
    solver_->recordShift(cmd, cells);
    return true;
}

void SmokeGrid::beginFrame() {
    measured_ = false;
    rebuilt_ = false;
}

void SmokeGrid::recordStep(VkCommandBuffer cmd, uint32_t emitters, gpu::GpuTimer* timer) {
    if (timer) timer->setPrefix(settings_.name + "/");
    if (sparse_) {
        // The active set before the step: live cells (pigment alpha above the sleep threshold,
        // or air faster than liveSpeed), the emitters' footprints, and one brick around them,
        // the most the step's advection can carry smoke (8 cells a step: 24 m/s at 5 cm and 60
        // steps a second). Not the dense grid's sleep speed (threshold x cell size / dt, 3e-4
        // m/s at the defaults): the projection leaves air that slow far around the smoke, and
        // bricks kept for it would cost several times the smoke's own (the kick's foot smoke:
        // about 700 bricks against 130).
        sparse_->setEmitterBuffer(emitters_, emitters);
        if (timer) timer->begin(cmd, "rebuild_bricks");
        sparse_->recordRebuild(cmd, settings_.sleepThreshold, settings_.liveSpeed, kBrickSize);
        if (timer) timer->end(cmd);
        sparse_->recordStep(cmd, timer);
        rebuilt_ = true;
    } else {
        solver_->setEmitterBuffer(emitters_, emitters);
        solver_->recordStep(cmd, timer);
    }
    if (timer) timer->setPrefix("");
}

uint32_t SmokeGrid::recordMeasureActivity(VkCommandBuffer cmd, gpu::GpuTimer* timer) {
    measured_ = true;
    if (sparse_) return 0; // its rebuild measures: a grid with no live cell keeps no brick
    if (timer) timer->begin(cmd, settings_.name + "/measure_activity");
    solver_->recordMeasureActivity(cmd, activity_);
    if (timer) timer->end(cmd);
    return 1;
}

SmokeGrid::Activity SmokeGrid::finishFrame() {
    Activity a;
    if (sparse_) {
        if (!rebuilt_) return a;
        const SparseSmokeSolver::RebuildCounts counts = sparse_->finishRebuild();
        a.activeBricks = counts.active;
        a.refusedBricks = counts.refused;
        if (!counts.error.empty() && !budgetReported_) {
            a.budgetLine = settings_.name + ": " + counts.error;
            budgetReported_ = true;
        }
        // Settled: no effect was live this frame (measured_) and no brick holds a live cell.
        if (measured_ && counts.active == 0 && counts.refused == 0) awake_ = false;
        return a;
    }
    if (!measured_) return a;
    a.measured = true;
    uint32_t bits[2];
    std::memcpy(bits, activity_.mapped, sizeof bits);
    std::memcpy(&a.largestAlpha, &bits[0], 4);
    std::memcpy(&a.largestSpeed, &bits[1], 4);
    const float speedThreshold =
        settings_.sleepThreshold * solver_->options().grid.cellSize / solver_->options().dt;
    if (a.largestAlpha < settings_.sleepThreshold && a.largestSpeed < speedThreshold)
        awake_ = false;
    return a;
}

uint64_t SmokeGrid::memoryBytes() const {
    return (sparse_ ? sparse_->memoryBytes() : solver_->memoryBytes()) + emitters_.size +
           activity_.size;
}

} // namespace mfx::fluid
