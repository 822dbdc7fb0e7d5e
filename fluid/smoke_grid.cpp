#include "fluid/smoke_grid.h"

#include "shaders/shared/coupling.h"

#include <cstring>

namespace mfx::fluid {

Result<SmokeGrid> SmokeGrid::create(const gpu::Context& ctx, SmokeGridSettings settings) {
    SmokeGrid grid;
    auto solver = SmokeSolver::create(ctx, settings.options);
    if (!solver) return solver.error();
    grid.solver_ = std::move(solver).value();
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

void SmokeGrid::place(glm::vec3 low, glm::vec3 high, glm::vec3 fallback,
                      std::optional<float> floorHeight, glm::vec3 root) {
    const GridShape& shape = solver_->options().grid;
    const glm::vec3 extent =
        glm::vec3(float(shape.cellsX), float(shape.cellsY), float(shape.cellsZ)) * shape.cellSize;
    if (low.x > high.x) low = high = fallback + glm::vec3(0.0f, 0.5f * extent.y, 0.0f);
    origin_ = 0.5f * (low + high) - 0.5f * extent;
    if (floorHeight && origin_.y < *floorHeight && low.y >= *floorHeight) origin_.y = *floorHeight;
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
    solver_->recordShift(cmd, cells);
    return true;
}

void SmokeGrid::beginFrame() {
    measured_ = false;
}

void SmokeGrid::recordStep(VkCommandBuffer cmd, uint32_t emitters, gpu::GpuTimer* timer) {
    solver_->setEmitterBuffer(emitters_, emitters);
    if (timer) timer->setPrefix(settings_.name + "/");
    solver_->recordStep(cmd, timer);
    if (timer) timer->setPrefix("");
}

void SmokeGrid::recordMeasureActivity(VkCommandBuffer cmd) {
    solver_->recordMeasureActivity(cmd, activity_);
    measured_ = true;
}

SmokeGrid::Activity SmokeGrid::finishFrame() {
    Activity a;
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
    return solver_->memoryBytes() + emitters_.size + activity_.size;
}

} // namespace mfx::fluid
