#include "fluid/smoke_grid.h"

#include "shaders/shared/coupling.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mfx::fluid {

Result<SmokeGrid> SmokeGrid::create(const gpu::Context& ctx, SmokeGridSettings settings) {
    SmokeGrid grid;
    if (settings.sparse && settings.follow)
        return Error{"a sparse grid stands still over its domain; it cannot follow"};
    auto solver = createGridSolver(ctx, settings.options, {settings.sparse, settings.maxBricks});
    if (!solver) return solver.error();
    grid.solver_ = std::move(solver).value();
    // Transfer source for the simulation's emitter capture, destination for the impacts' bursts.
    grid.emitters_ = gpu::createBuffer(
        ctx, VkDeviceSize(settings.emitterCapacity) * sizeof(shared::FluidEmitter),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
            VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        gpu::MemoryUsage::DeviceLocal, "smoke emitters");
    grid.activity_ =
        gpu::createBuffer(ctx, 2 * sizeof(uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::Readback, "smoke activity");
    grid.settings_ = std::move(settings);
    return grid;
}

SettleRules SmokeGrid::rules() const {
    // Settled speed: the alpha threshold in cells per step.
    const SolverOptions& o = solver_->options();
    return {settings_.sleepThreshold, settings_.sleepThreshold * o.grid.cellSize / o.dt,
            settings_.liveSpeed};
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
    if (!settings_.follow) return false;
    const float h = solver_->options().grid.cellSize;
    glm::vec3 moved = root - rootAtPlacement_;
    moved.y = 0.0f;
    const glm::ivec3 cells = glm::ivec3(glm::round((placedOrigin_ + moved - origin_) / h));
    if (cells == glm::ivec3(0)) return false;
    origin_ += glm::vec3(cells) * h;
    if (!awake_) return false;
    return solver_->recordShift(cmd, cells);
}

void SmokeGrid::beginFrame() {
    measured_ = false;
    stepped_ = false;
}

void SmokeGrid::recordStep(VkCommandBuffer cmd, uint32_t emitters, gpu::GpuTimer* timer) {
    if (timer) timer->setPrefix(settings_.name + "/");
    solver_->setEmitterBuffer(emitters_, emitters);
    solver_->recordSceneStep(cmd, rules(), timer);
    stepped_ = true;
    if (timer) timer->setPrefix("");
}

uint32_t SmokeGrid::recordMeasureActivity(VkCommandBuffer cmd, gpu::GpuTimer* timer) {
    measured_ = true;
    if (timer) timer->setPrefix(settings_.name + "/");
    const uint32_t dispatches = solver_->recordMeasureActivity(cmd, activity_, timer);
    if (timer) timer->setPrefix("");
    return dispatches;
}

SmokeGrid::Activity SmokeGrid::finishFrame() {
    Activity a;
    static_cast<SolverActivity&>(a) = solver_->finishFrame(activity_, measured_, stepped_, rules());
    if (!a.budgetError.empty() && !budgetReported_) {
        a.budgetLine = settings_.name + ": " + a.budgetError;
        budgetReported_ = true;
    }
    if (a.settled) awake_ = false;
    return a;
}

uint64_t SmokeGrid::memoryBytes() const {
    return solver_->memoryBytes() + emitters_.size + activity_.size;
}

} // namespace mfx::fluid
