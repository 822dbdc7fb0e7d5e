// motionfx bake: a scene's effects baked into flipbook sheets for game engines (render/flipbook.h,
// docs/flipbook.md): DIR/colour.png (premultiplied RGBA), DIR/motion.png (motion vectors) and
// DIR/flipbook.json (the layout, timing, encodings and camera), with a progress bar; with
// --evaluate, how well the sheets play at a fraction of their rate.
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/commands.h"
#include "render/bake_renderer.h"
#include "render/exr_output.h"
#include "render/flipbook.h"
#include "render/frame_renderer.h"
#include "render/image_output.h"
#include "render/optical_flow.h"
#include "render/six_way.h"
#include "render/smoke_motion.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace mfx::app {

namespace {

enum class MotionSource { Flow, Velocity, None };

struct BakeOptions {
    render::FlipbookLayout layout;
    uint32_t first = 0, last = 0; // scene frames, inclusive
    uint32_t loop = 0;            // cells cross-faded into the first
    std::vector<size_t> effects;  // indices into scene.effects
    bool holdout = false;
    bool frameOnEffect = true;
    float margin = 0.06f;
    MotionSource motion = MotionSource::Flow;
    bool sixWay = false;
    bool hdr = false;
    uint32_t evaluate = 0;
    std::string out;
};

// The options that need no scene: layout, loop, margin, motion, evaluation.
Status readLayoutOptions(const cli::ParsedArgs& parsed, BakeOptions& options) {
    if (Status s = render::parseFlipbookGrid(parsed.value("grid", "8x8"), options.layout); !s)
        return s;
    if (Status s = render::parseFlipbookCell(parsed.value("cell", "256"), render::kMaxSheetSide,
                                             options.layout);
        !s)
        return s;
    const uint32_t cells = options.layout.cells();
    if (parsed.has("loop")) {
        const Result<uint32_t> loop =
            cli::parseUnsigned(parsed.value("loop"), 1, std::max(cells - 1, 1u), "--loop");
        if (!loop) return loop.error();
        if (cells < 2) return Error{"--loop needs a grid of at least 2 cells"};
        options.loop = loop.value();
    }
    if (parsed.has("margin")) {
        const Result<double> margin =
            cli::parseNumber(parsed.value("margin"), 0.0, 0.4, "--margin");
        if (!margin) return margin.error();
        options.margin = float(margin.value());
    }
    const std::string camera = parsed.value("camera", "effect");
    if (camera != "effect" && camera != "scene")
        return Error{"--camera '" + camera + "' is not effect or scene"};
    options.frameOnEffect = camera == "effect";
    const std::string motion = parsed.value("motion", "flow");
    if (motion != "flow" && motion != "velocity" && motion != "none")
        return Error{"--motion '" + motion + "' is not flow, velocity or none"};
    options.motion = motion == "flow"       ? MotionSource::Flow
                     : motion == "velocity" ? MotionSource::Velocity
                                            : MotionSource::None;
    if (parsed.has("evaluate")) {
        const Result<uint32_t> rate =
            cli::parseUnsigned(parsed.value("evaluate"), 2, 64, "--evaluate");
        if (!rate) return rate.error();
        if (rate.value() >= cells)
            return Error{"--evaluate " + std::to_string(rate.value()) + " needs more than " +
                         std::to_string(rate.value()) + " cells; the grid has " +
                         std::to_string(cells)};
        options.evaluate = rate.value();
    }
    options.holdout = parsed.has("holdout");
    options.sixWay = parsed.has("six-way");
    options.hdr = parsed.has("hdr");
    options.out = parsed.value("out", "bake");
    return Ok{};
}

bool bakesSmoke(const scene::Scene& scene, const BakeOptions& options) {
    return std::any_of(options.effects.begin(), options.effects.end(),
                       [&](size_t e) { return scene.effects[e].is<scene::SmokeSpec>(); });
}

// The options that name parts of the scene: --effects and --range.
Status readSceneOptions(const cli::ParsedArgs& parsed, const scene::Scene& scene,
                        uint32_t frameCount, BakeOptions& options) {
    if (parsed.has("effects")) {
        const std::string list = parsed.value("effects");
        size_t start = 0;
        while (start <= list.size()) {
            size_t end = list.find(',', start);
            if (end == std::string::npos) end = list.size();
            const std::string name = list.substr(start, end - start);
            size_t found = scene.effects.size();
            for (size_t e = 0; e < scene.effects.size(); ++e)
                if (scene.effects[e].name == name) found = e;
            if (found == scene.effects.size()) {
                std::string names;
                for (const scene::EffectSpec& e : scene.effects)
                    names += (names.empty() ? "\"" : ", \"") + e.name + "\"";
                return Error{"--effects: the scene has no effect named \"" + name + "\" (it has " +
                             (names.empty() ? "none" : names) + ")"};
            }
            if (std::find(options.effects.begin(), options.effects.end(), found) ==
                options.effects.end())
                options.effects.push_back(found);
            start = end + 1;
        }
    } else {
        for (size_t e = 0; e < scene.effects.size(); ++e)
            options.effects.push_back(e);
    }
    if (options.effects.empty()) return Error{"the scene has no effects to bake"};
    if (options.sixWay && !bakesSmoke(scene, options))
        return Error{"--six-way lights smoke, and none of the effects baked is smoke"};
    if (options.motion == MotionSource::Velocity && !bakesSmoke(scene, options))
        return Error{"--motion velocity follows the smoke's velocity, and none of the effects "
                     "baked is smoke"};
    options.first = 0;
    options.last = frameCount - 1;
    if (parsed.has("range")) {
        const std::string text = parsed.value("range");
        const size_t colon = text.find(':');
        auto number = [](std::string_view part, uint32_t& out) {
            auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), out);
            return !part.empty() && error == std::errc() && end == part.data() + part.size();
        };
        uint32_t first = 0, last = 0;
        if (colon == std::string::npos || !number(std::string_view(text).substr(0, colon), first) ||
            !number(std::string_view(text).substr(colon + 1), last))
            return Error{"--range '" + text + "' is not FIRST:LAST (scene frames), e.g. 10:73"};
        if (first > last || last >= frameCount)
            return Error{"--range '" + text + "': frames must satisfy FIRST <= LAST < " +
                         std::to_string(frameCount) + " (the scene's frames)"};
        options.first = first;
        options.last = last;
    }
    return Ok{};
}

// Plays a new simulation of the scene through the last of `capture`, drawing each frame with
// `renderer`, and hands each captured frame's layer (linear RGBA, top row first) to `take`.
template <class Take>
void playCaptured(const gpu::Context& ctx, sim::SceneSimulation& sim,
                  render::BakeRenderer& renderer, const std::vector<uint32_t>& capture,
                  const char* what, Take take) {
    Progress progress(what, capture.back() + 1);
    size_t next = 0;
    for (uint32_t f = 0; f <= capture.back(); ++f) {
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) { renderer.record(cmd, sim, f); });
        reportBudget(sim.finishFrame());
        while (next < capture.size() && capture[next] == f) {
            take(next, render::readLinearColor(ctx, renderer.layer()));
            ++next;
        }
        progress.update(f + 1);
    }
    progress.finish();
}

std::unique_ptr<render::BakeRenderer>
makeRenderer(const gpu::Context& ctx, const sim::SceneSimulation& sim, const BakeOptions& options) {
    auto renderer = std::make_unique<render::BakeRenderer>(
        ctx, sim, options.layout.cellWidth, options.layout.cellHeight, options.holdout);
    for (size_t e = 0; e < sim.scene().effects.size(); ++e)
        renderer->setShown(e, std::find(options.effects.begin(), options.effects.end(), e) !=
                                  options.effects.end());
    return renderer;
}

// Whether a pixel of a layer shows anything (1/255 of coverage or light).
bool visible(const float* rgba) {
    return std::max({rgba[0], rgba[1], rgba[2], rgba[3]}) > 1.0f / 255.0f;
}

// The crop of the scene's camera (its normalised device coordinates) that frames what the effects
// draw over the captured frames with `margin` of the cell to spare on every side: found by drawing
// them first through a camera that sees twice as far each way. Nothing (after printing why, with
// `exitCode` set) when it cannot.
std::optional<glm::vec4> frameEffects(const gpu::Context& ctx, const SceneArgument& argument,
                                      const BakeOptions& options,
                                      const std::vector<uint32_t>& capture, int& exitCode) {
    const std::unique_ptr<sim::SceneSimulation> sim =
        createSceneSimulation(ctx, argument, exitCode);
    if (!sim) return std::nullopt;
    const std::unique_ptr<render::BakeRenderer> renderer = makeRenderer(ctx, *sim, options);
    renderer->setCamera(render::cropCamera(renderer->camera(), {-2.0f, -2.0f, 2.0f, 2.0f}));
    const uint32_t w = options.layout.cellWidth, h = options.layout.cellHeight;
    uint32_t x0 = w, y0 = h, x1 = 0, y1 = 0;
    playCaptured(ctx, *sim, *renderer, capture, "framing",
                 [&](size_t, const std::vector<float>& layer) {
                     for (uint32_t y = 0; y < h; ++y)
                         for (uint32_t x = 0; x < w; ++x)
                             if (visible(&layer[(size_t(y) * w + x) * 4])) {
                                 x0 = std::min(x0, x);
                                 x1 = std::max(x1, x);
                                 y0 = std::min(y0, y);
                                 y1 = std::max(y1, y);
                             }
                 });
    if (x0 > x1) {
        printError("the effects baked draw nothing in frames " + std::to_string(options.first) +
                   " to " + std::to_string(options.last) +
                   " within twice the scene camera's view; choose other --effects or --range");
        exitCode = kExitFailure;
        return std::nullopt;
    }
    if (x0 == 0 || y0 == 0 || x1 + 1 == w || y1 + 1 == h)
        std::fprintf(stderr,
                     "motionfx: warning: the effects reach beyond twice the scene camera's view "
                     "and may be cut at the cells' edges; move the scene's camera back\n");
    // Pixel edges, one pixel out (the wide view is coarse), to the wide camera's device
    // coordinates (+y up), then to the scene camera's (twice as large).
    const float left = 2.0f * (2.0f * (float(x0) - 1.0f) / float(w) - 1.0f);
    const float right = 2.0f * (2.0f * float(x1 + 2) / float(w) - 1.0f);
    const float top = 2.0f * (1.0f - 2.0f * (float(y0) - 1.0f) / float(h));
    const float bottom = 2.0f * (1.0f - 2.0f * float(y1 + 2) / float(h));
    const glm::vec2 centre{0.5f * (left + right), 0.5f * (top + bottom)};
    const float half = 0.5f * std::max(right - left, top - bottom) / (1.0f - 2.0f * options.margin);
    return glm::vec4(centre.x - half, centre.y - half, centre.x + half, centre.y + half);
}

nlohmann::json matrixJson(const glm::mat4& m) {
    nlohmann::json out = nlohmann::json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            out.push_back(m[c][r]);
    return out;
}

// A field through the motion sheet's 8-bit encoding at its own scale (what a player gets).
render::MotionField throughEncoding(const render::MotionField& field) {
    const float scale = render::motionScale(std::span(&field, 1));
    return render::decodeMotion(render::encodeMotion(field, scale), field.width, field.height,
                                scale);
}

// The sheets played at 1/rate of their cells' rate: every rate-th cell kept, its motion toward the
// next kept one measured by the optical flow and, with `velocity` (each cell's smoke motion over
// `rate` cells' time), taken from the simulation, the cells between them blended (cross-fade and
// motion vectors, the motion through its 8-bit encoding) and compared with the cells baked there.
nlohmann::json evaluateRate(const std::vector<render::CellImage>& cells, uint32_t rate,
                            const std::vector<render::MotionField>* velocity) {
    double crossFade = 0.0, flow = 0.0, simulated = 0.0;
    uint32_t between = 0;
    Progress progress("evaluating", uint32_t((cells.size() - 1) / rate));
    for (size_t j = 0; (j + 1) * rate < cells.size(); ++j) {
        const render::CellImage& a = cells[j * rate];
        const render::CellImage& b = cells[(j + 1) * rate];
        const render::MotionField measured = throughEncoding(render::opticalFlow(a, b));
        render::MotionField projected;
        if (velocity) projected = throughEncoding((*velocity)[j * rate]);
        for (uint32_t i = 1; i < rate; ++i) {
            const render::CellImage& truth = cells[j * rate + i];
            const float t = float(i) / float(rate);
            const render::CellImage* cover[] = {&a, &b, &truth};
            crossFade +=
                render::coveredMeanError(render::blendCells(a, b, nullptr, t), truth, cover);
            flow += render::coveredMeanError(render::blendCells(a, b, &measured, t), truth, cover);
            if (velocity)
                simulated +=
                    render::coveredMeanError(render::blendCells(a, b, &projected, t), truth, cover);
            ++between;
        }
        progress.update(uint32_t(j + 1));
    }
    progress.finish();
    const double n = std::max(between, 1u);
    crossFade /= n;
    flow /= n;
    simulated /= n;
    auto ratio = [&](double e) { return crossFade > 0.0 ? e / crossFade : 1.0; };
    std::printf("played at 1/%u of the baked rate (every %u%s cell): mean error over %u in-between "
                "cells (covered pixels, channels in [0, 1]): cross-fade %.5f, motion vectors by "
                "optical flow %.5f (%.2fx)",
                rate, rate,
                rate == 2   ? "nd"
                : rate == 3 ? "rd"
                            : "th",
                between, crossFade, flow, ratio(flow));
    if (velocity)
        std::printf(", by the smoke's velocity %.5f (%.2fx)", simulated, ratio(simulated));
    std::printf("\n");
    nlohmann::json out = {{"rate", rate},
                          {"in_between_cells", between},
                          {"cross_fade_error", crossFade},
                          {"flow_error", flow},
                          {"error", "mean absolute difference of the 8-bit sheet's values over "
                                    "255, over the pixels either kept cell or the baked one "
                                    "covers"}};
    if (velocity) out["velocity_error"] = simulated;
    return out;
}

// One captured frame's six-way maps (render/six_way.h) and, when evaluating, the smoke lit directly
// from the diagonal directions of kDiagonals (premultiplied luminance in channel 0, opacity in 3).
struct SixWayFrame {
    render::SixWayCell maps;
    std::vector<render::CellImage> direct;
};

// Directions toward the light that are none of the six axes, as (right, up, front) in the bake
// camera's frame, for the six-way blend's check, with their names.
struct Diagonal {
    glm::vec3 frame;
    const char* name;
};
constexpr Diagonal kDiagonals[] = {{{1.0f, 1.0f, 1.0f}, "upper right, in front"},
                                   {{-1.0f, 0.5f, -1.0f}, "upper left, behind"},
                                   {{0.7f, -1.0f, -0.4f}, "lower right, behind"}};

glm::vec3 diagonalDirection(const render::SceneCamera& camera, const Diagonal& d) {
    const std::array<glm::vec3, 6> axes = render::sixWayDirections(camera);
    return glm::normalize(d.frame.x * axes[0] + d.frame.y * axes[1] + d.frame.z * axes[5]);
}

// The layer's smoke drawn again, lit by one white light from `towardLight` (intensity 1, no glow),
// or with `emission` by its glow alone; its premultiplied luminance into `out`'s channel
// `channel`, and with `alpha`, its opacity into channel 3.
void captureLit(const gpu::Context& ctx, render::BakeRenderer& renderer,
                const sim::SceneSimulation& sim, glm::vec3 towardLight, bool emission,
                render::CellImage& out, int channel, bool alpha) {
    render::SmokeRelight relight;
    relight.key.direction = -towardLight;
    relight.key.colour = glm::vec3(1.0f);
    relight.key.intensity = emission ? 0.0f : 1.0f;
    relight.glowScale = emission ? 1.0f : 0.0f;
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) { renderer.recordSmoke(cmd, sim, relight); });
    const std::vector<float> layer = render::readLinearColor(ctx, renderer.layer());
    for (size_t p = 0; p < size_t(out.width) * out.height; ++p) {
        out.rgba[p * 4 + size_t(channel)] = render::luminance(&layer[p * 4]);
        if (alpha) out.rgba[p * 4 + 3] = layer[p * 4 + 3];
    }
}

SixWayFrame captureSixWay(const gpu::Context& ctx, render::BakeRenderer& renderer,
                          const sim::SceneSimulation& sim, bool evaluate) {
    const uint32_t w = renderer.layer().width, h = renderer.layer().height;
    SixWayFrame frame{{render::CellImage(w, h), render::CellImage(w, h)}, {}};
    const std::array<glm::vec3, 6> axes = render::sixWayDirections(renderer.camera());
    for (int i = 0; i < 6; ++i)
        captureLit(ctx, renderer, sim, axes[size_t(i)], false, i < 3 ? frame.maps.a : frame.maps.b,
                   i % 3, i == 0);
    captureLit(ctx, renderer, sim, axes[0], true, frame.maps.b, 3, false);
    if (evaluate)
        for (const Diagonal& d : kDiagonals) {
            frame.direct.emplace_back(w, h);
            captureLit(ctx, renderer, sim, diagonalDirection(renderer.camera(), d), false,
                       frame.direct.back(), 0, true);
        }
    return frame;
}

// A strip of grey panels (each `width` x `height`, values in [0, 1] as linear light, NaN-free)
// side by side, sRGB-encoded, for a preview picture: panel i's value at pixel p is
// panels[i][p], laid over the preview's dark background by its coverage covers[i][p].
std::vector<uint8_t> greyStrip(const std::vector<std::vector<float>>& panels,
                               const std::vector<std::vector<float>>& covers, uint32_t width,
                               uint32_t height) {
    const size_t columns = panels.size();
    std::vector<uint8_t> strip(columns * width * height * 4);
    for (size_t i = 0; i < columns; ++i)
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) {
                const size_t p = size_t(y) * width + x;
                const float cover = std::clamp(covers[i][p], 0.0f, 1.0f);
                uint8_t* out = &strip[((size_t(y) * columns * width) + i * width + x) * 4];
                for (int c = 0; c < 3; ++c)
                    out[c] = render::encodeSrgb8(std::clamp(
                        panels[i][p] + (1.0f - cover) * render::kClearColour[c], 0.0f, 1.0f));
                out[3] = 255;
            }
    return strip;
}

// The six-way sheets (cross-faded into a loop as the colour is) and their metadata; with
// `evaluation`, the blend checked against the smoke lit directly from kDiagonals, on the cells
// that are not cross-faded (the direct pictures are of one frame each).
Result<nlohmann::json> writeSixWay(std::vector<SixWayFrame> frames, const BakeOptions& options,
                                   const render::SceneCamera& camera, nlohmann::json& evaluation) {
    const render::FlipbookLayout& layout = options.layout;
    std::vector<render::CellImage> a, b;
    for (SixWayFrame& f : frames) {
        a.push_back(std::move(f.maps.a));
        b.push_back(std::move(f.maps.b));
    }
    a = render::crossFadeLoop(std::move(a), options.loop);
    b = render::crossFadeLoop(std::move(b), options.loop);
    std::vector<render::SixWayCell> cells;
    for (size_t i = 0; i < a.size(); ++i)
        cells.push_back({std::move(a[i]), std::move(b[i])});
    const render::SixWayScales scales = render::sixWayScales(cells);
    const size_t sheetBytes = size_t(layout.sheetWidth()) * layout.sheetHeight() * 4;
    std::array<std::vector<uint8_t>, 2> sheets{std::vector<uint8_t>(sheetBytes, 0),
                                               std::vector<uint8_t>(sheetBytes, 0)};
    std::vector<std::array<std::vector<uint8_t>, 2>> stored;
    for (uint32_t i = 0; i < layout.cells(); ++i) {
        stored.push_back(render::encodeSixWay(cells[i], scales));
        for (int s = 0; s < 2; ++s)
            render::placeCell(sheets[size_t(s)], layout, i, stored.back()[size_t(s)]);
    }
    const char* files[2] = {"six_way_right_top_back.png", "six_way_left_bottom_front.png"};
    for (int s = 0; s < 2; ++s)
        if (Status written = render::writePng(options.out + "/" + files[s], layout.sheetWidth(),
                                              layout.sheetHeight(), sheets[size_t(s)]);
            !written)
            return written.error();

    // A preview of the middle cell's maps: right, top, back, left, bottom, front and emission,
    // each as light over the opacity (premultiplied, over the dark background).
    const uint32_t w = layout.cellWidth, h = layout.cellHeight;
    const size_t pixels = size_t(w) * h;
    {
        const uint32_t middle = layout.cells() / 2;
        std::vector<std::vector<float>> panels(7, std::vector<float>(pixels)),
            covers(7, std::vector<float>(pixels));
        for (size_t p = 0; p < pixels; ++p) {
            const float alpha = float(stored[middle][0][p * 4 + 3]) / 255.0f;
            for (int m = 0; m < 7; ++m) {
                const std::vector<uint8_t>& sheet = stored[middle][m < 3 ? 0 : 1];
                const int channel = m < 6 ? m % 3 : 3;
                const float scale = m < 6 ? scales.light : scales.emission;
                // Shown at up to 1 for the brightest light in the sheet.
                panels[size_t(m)][p] = alpha * float(sheet[p * 4 + size_t(channel)]) / 255.0f *
                                       scale / std::max(scales.light, scales.emission);
                covers[size_t(m)][p] = alpha;
            }
        }
        if (Status written = render::writePng(options.out + "/six_way_preview.png", 7 * w, h,
                                              greyStrip(panels, covers, w, h));
            !written)
            return written.error();
    }

    const std::array<glm::vec3, 6> axes = render::sixWayDirections(camera);
    auto vec = [](glm::vec3 v) { return nlohmann::json{v.x, v.y, v.z}; };
    nlohmann::json meta = {
        {"files", {files[0], files[1]}},
        {"channels", {"right, top, back, opacity", "left, bottom, front, emission"}},
        {"light_scale", scales.light},
        {"emission_scale", scales.emission},
        {"encoding", "linear 8-bit (import without sRGB); maps straight, not premultiplied: "
                     "light = byte / 255 * light_scale, emission = byte / 255 * emission_scale; "
                     "opacity linear"},
        {"axes_world", {{"right", vec(axes[0])}, {"top", vec(axes[1])}, {"back", vec(axes[2])}}},
        {"lit_by", "a white directional light of intensity 1 from each axis, the glow left out; "
                   "emission: the glow alone"},
        {"blend", "light = sum over axes a of max(0, dot(l, a))^2 * map_a, l the unit direction "
                  "toward the light"}};

    if (!frames.empty() && !frames.front().direct.empty()) {
        nlohmann::json checks = nlohmann::json::array();
        // The picture of the check: per light, the middle uncross-faded cell lit directly, by
        // the blend, and their difference four times over (on black).
        const uint32_t shown = (layout.cells() - options.loop) / 2;
        std::vector<uint8_t> check;
        for (size_t d = 0; d < std::size(kDiagonals); ++d) {
            const glm::vec3 toward = diagonalDirection(camera, kDiagonals[d]);
            const std::array<float, 6> weights = render::sixWayWeights(camera, toward);
            double difference = 0.0, light = 0.0;
            render::CellImage shownRelit;
            for (uint32_t i = 0; i + options.loop < layout.cells(); ++i) {
                render::CellImage relit =
                    render::relightSixWay(stored[i][0], stored[i][1], w, h, scales, weights);
                const render::CellImage& direct = frames[options.loop + i].direct[d];
                for (size_t p = 0; p < size_t(w) * h; ++p) {
                    if (!(direct.rgba[p * 4 + 3] > 1.0f / 255.0f) && relit.rgba[p * 4 + 3] == 0.0f)
                        continue;
                    difference += std::abs(double(relit.rgba[p * 4]) - double(direct.rgba[p * 4]));
                    light += double(direct.rgba[p * 4]);
                }
                if (i == shown) shownRelit = std::move(relit);
            }
            const double relative = light > 0.0 ? difference / light : 0.0;
            {
                const render::CellImage& relit = shownRelit;
                const render::CellImage& direct = frames[options.loop + shown].direct[d];
                std::vector<std::vector<float>> panels(3, std::vector<float>(pixels)),
                    covers(3, std::vector<float>(pixels));
                for (size_t p = 0; p < pixels; ++p) {
                    panels[0][p] = direct.rgba[p * 4];
                    panels[1][p] = relit.rgba[p * 4];
                    panels[2][p] = 4.0f * std::abs(relit.rgba[p * 4] - direct.rgba[p * 4]);
                    covers[0][p] = direct.rgba[p * 4 + 3];
                    covers[1][p] = relit.rgba[p * 4 + 3];
                    covers[2][p] = 1.0f; // on black
                }
                const std::vector<uint8_t> row = greyStrip(panels, covers, w, h);
                check.insert(check.end(), row.begin(), row.end());
            }
            std::printf("six-way blend against the smoke lit directly from the %s (%.2f, %.2f, "
                        "%.2f): relative mean difference %.4f\n",
                        kDiagonals[d].name, double(toward.x), double(toward.y), double(toward.z),
                        relative);
            checks.push_back({{"light", kDiagonals[d].name},
                              {"toward_light_world", vec(toward)},
                              {"relative_difference", relative}});
        }
        if (Status written = render::writePng(options.out + "/six_way_check.png", 3 * w,
                                              uint32_t(std::size(kDiagonals)) * h, check);
            !written)
            return written.error();
        if (evaluation.is_null()) evaluation = nlohmann::json::object();
        evaluation["six_way"] = {
            {"measure", "sum over covered pixels of |blend - direct| / sum of direct, the "
                        "premultiplied luminance, over the cells not cross-faded"},
            {"lights", checks}};
    }
    return meta;
}

} // namespace

int runBake(const cli::ParsedArgs& parsed) {
    BakeOptions options;
    if (Status s = readLayoutOptions(parsed, options); !s) {
        printError(s.error().message);
        return kExitUsage;
    }
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode)) return exitCode;
    const scene::Scene& s = argument.scene;
    const uint32_t frameCount = scene::frameCount(s, argument.cast);
    if (Status status = readSceneOptions(parsed, s, frameCount, options); !status) {
        printError(status.error().message);
        return kExitUsage;
    }
    const uint32_t cells = options.layout.cells();
    const Result<std::vector<uint32_t>> capture =
        render::sampleFrames(options.first, options.last, cells + options.loop);
    if (!capture) {
        printError(capture.error().message);
        return kExitUsage;
    }
    if (Status dir = render::ensureOutputDirectory(options.out); !dir) {
        printError(dir.error().message);
        return kExitFailure;
    }
    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const uint32_t side = ctx.limits().maxImageDimension2D;
    if (options.layout.cellWidth > side || options.layout.cellHeight > side) {
        printError("--cell: this device draws at most " + std::to_string(side) + " pixels a side");
        return kExitUsage;
    }

    // The camera: the scene's, or framed on what the effects draw.
    glm::vec4 crop{-1.0f, -1.0f, 1.0f, 1.0f};
    if (options.frameOnEffect) {
        const std::optional<glm::vec4> framed =
            frameEffects(ctx, argument, options, capture.value(), exitCode);
        if (!framed) return exitCode;
        crop = *framed;
    }

    const std::unique_ptr<sim::SceneSimulation> sim =
        createSceneSimulation(ctx, argument, exitCode);
    if (!sim) return exitCode;
    const std::unique_ptr<render::BakeRenderer> renderer = makeRenderer(ctx, *sim, options);
    const render::SceneCamera camera = render::cropCamera(renderer->camera(), crop);
    renderer->setCamera(camera);
    const uint32_t w = options.layout.cellWidth, h = options.layout.cellHeight;
    std::vector<render::CellImage> frames(capture.value().size());
    std::vector<SixWayFrame> sixWay;

    // The smoke's velocity carried to the screen: for --motion velocity (toward the next cell),
    // and for --evaluate's comparison (over `evaluate` cells' time), where the smoke is baked on
    // dense grids (a sparse domain's whole fields would be read back every frame).
    std::vector<size_t> velocityGrids;
    bool sparseSmoke = false;
    for (size_t g = 0; g < sim->smokeGrids().size(); ++g) {
        const sim::SceneSimulation::SmokeGrid& grid = sim->smokeGrids()[g];
        const bool baked = std::any_of(grid.effects.begin(), grid.effects.end(), [&](size_t e) {
            const size_t index = sim->effectIndex(sim->trajectories()[e]);
            return std::find(options.effects.begin(), options.effects.end(), index) !=
                   options.effects.end();
        });
        if (!baked) continue;
        velocityGrids.push_back(g);
        sparseSmoke = sparseSmoke || grid.grid.sparse();
    }
    if (options.motion == MotionSource::Velocity && sparseSmoke) {
        printError("--motion velocity reads the smoke's fields back every frame, which a sparse "
                   "domain's are too large for; use --motion flow");
        return kExitUsage;
    }
    const bool velocityWanted = options.motion == MotionSource::Velocity ||
                                (options.evaluate && !velocityGrids.empty() && !sparseSmoke);
    std::vector<render::MotionField> velocityNext(velocityWanted ? frames.size() : 0),
        velocityRate(velocityWanted && options.evaluate ? frames.size() : 0);
    auto captureVelocity = [&](size_t k) {
        std::vector<fluid::FieldState> states;
        for (size_t g : velocityGrids)
            states.push_back(sim->smokeGrids()[g].grid.state());
        std::vector<render::SmokeFields> fields;
        for (size_t i = 0; i < states.size(); ++i)
            fields.push_back({&states[i], sim->smokeGrids()[velocityGrids[i]].grid.origin()});
        // Seconds from this picture to the one `steps` pictures on (past the last, the spacing
        // before it, continued).
        const std::vector<uint32_t>& at = capture.value();
        auto seconds = [&](size_t steps) {
            const size_t later = std::min(k + steps, at.size() - 1);
            double span = double(at[later]) - double(at[k]);
            if (later - k < steps && k > 0)
                span += double(steps - (later - k)) * (double(at[k]) - double(at[k - 1]));
            return float(std::max(span, 1.0) / double(s.output.fps));
        };
        const float density = render::SmokeLook{}.densityScale;
        velocityNext[k] = render::projectedSmokeMotion(fields, camera, w, h, seconds(1), density);
        if (options.evaluate)
            velocityRate[k] = render::projectedSmokeMotion(fields, camera, w, h,
                                                           seconds(options.evaluate), density);
    };
    playCaptured(
        ctx, *sim, *renderer, capture.value(), "baking", [&](size_t k, std::vector<float> layer) {
            render::CellImage& cell = frames[k];
            cell.width = w;
            cell.height = h;
            cell.rgba = std::move(layer); // linear: tone-mapped for the 8-bit sheet below
            if (options.sixWay)
                sixWay.push_back(captureSixWay(ctx, *renderer, *sim, options.evaluate != 0));
            if (velocityWanted) captureVelocity(k);
        });
    frames = render::crossFadeLoop(std::move(frames), options.loop);

    // The colour sheet, and its cells as stored (what the motion is measured on and played from).
    const render::FlipbookLayout& layout = options.layout;
    std::vector<uint8_t> colourSheet(size_t(layout.sheetWidth()) * layout.sheetHeight() * 4, 0);
    std::vector<render::CellImage> stored;
    std::vector<float> hdrSheet(options.hdr ? colourSheet.size() : 0, 0.0f);
    for (uint32_t i = 0; i < cells; ++i) {
        if (options.hdr) {
            const size_t x0 = size_t(i % layout.columns) * w, y0 = size_t(i / layout.columns) * h;
            for (uint32_t y = 0; y < h; ++y)
                std::copy_n(&frames[i].rgba[size_t(y) * w * 4], size_t(w) * 4,
                            &hdrSheet[((y0 + y) * layout.sheetWidth() + x0) * 4]);
        }
        render::toneMapCell(frames[i], s.post.exposure, s.post.toneMap == scene::ToneMap::Aces);
        const std::vector<uint8_t> cell = render::encodeColour8(frames[i]);
        render::placeCell(colourSheet, layout, i, cell);
        stored.push_back(render::cellFromRgba8(cell, w, h));
    }
    frames.clear();
    if (options.hdr)
        if (Status written = render::writeExr(options.out + "/colour.exr", layout.sheetWidth(),
                                              layout.sheetHeight(), hdrSheet);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
    const std::string colourFile = options.out + "/colour.png";
    const float background[3] = {render::kClearColour.r, render::kClearColour.g,
                                 render::kClearColour.b};
    for (const auto& [file, pixels] :
         {std::pair{colourFile, colourSheet},
          std::pair{options.out + "/preview.png", render::previewOver(colourSheet, background)}})
        if (Status written =
                render::writePng(file, layout.sheetWidth(), layout.sheetHeight(), pixels);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }

    nlohmann::json motionJson = nullptr;
    std::string motionNote;
    if (options.motion != MotionSource::None) {
        const bool flow = options.motion == MotionSource::Flow;
        std::vector<render::MotionField> fields(cells);
        if (flow) {
            Progress progress("motion vectors", cells);
            for (uint32_t i = 0; i < cells; ++i) {
                const bool last = i + 1 == cells;
                if (!last || options.loop)
                    fields[i] = render::opticalFlow(stored[i], stored[last ? 0 : i + 1]);
                else
                    fields[i] = i > 0 ? fields[i - 1] : render::MotionField(w, h);
                progress.update(i + 1);
            }
            progress.finish();
        } else {
            fields = render::crossFadeLoop(velocityNext, options.loop);
        }
        const float scale = render::motionScale(fields);
        std::vector<uint8_t> motionSheet(colourSheet.size(), 0);
        for (uint32_t i = 0; i < cells; ++i)
            render::placeCell(motionSheet, layout, i, render::encodeMotion(fields[i], scale));
        const std::string motionFile = options.out + "/motion.png";
        if (Status written = render::writePng(motionFile, layout.sheetWidth(), layout.sheetHeight(),
                                              motionSheet);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
        motionNote = ", " + motionFile;
        motionJson = {
            {"file", "motion.png"},
            {"method", flow ? "flow" : "velocity"},
            {"measured", flow ? "optical flow between consecutive cells of the colour sheet (Horn "
                                "and Schunck, coarse to fine)"
                              : "the smoke's simulated velocity carried to the screen over the "
                                "time to the next cell, weighted along each ray by what each "
                                "sample adds to the pixel; 0 where no smoke is"},
            {"encoding", "rg = 0.5 + 0.5 * m / scale, b = 0, a = 1; m: the displacement in the "
                         "cell's uv (u right, v down, 1 = a cell's width or height) taking a "
                         "pixel of this cell to its content in the next cell"},
            {"scale", scale},
            {"v_axis", "down"},
            {"last_cell", options.loop ? "toward cell 0"
                          : flow       ? "the cell before's motion"
                                       : "its own velocity"},
            {"blend", "out(uv) = (1 - t) A(uv - t m(uv)) + t B(uv + (1 - t) m(uv)), m from A"}};
    }

    nlohmann::json evaluation = nullptr;
    if (options.evaluate) {
        std::vector<render::MotionField> velocity;
        for (size_t i = 0; velocityWanted && i < cells; ++i)
            velocity.push_back(std::move(velocityRate[options.loop + i]));
        evaluation = evaluateRate(stored, options.evaluate, velocityWanted ? &velocity : nullptr);
    }

    nlohmann::json sixWayJson = nullptr;
    if (options.sixWay) {
        Result<nlohmann::json> written =
            writeSixWay(std::move(sixWay), options, renderer->camera(), evaluation);
        if (!written) {
            printError(written.error().message);
            return kExitFailure;
        }
        sixWayJson = std::move(written).value();
    }

    std::vector<uint32_t> cellFrames;
    for (uint32_t i = 0; i < cells; ++i)
        cellFrames.push_back(capture.value()[options.loop + i]);
    std::vector<std::string> effectNames;
    for (size_t e : options.effects)
        effectNames.push_back(s.effects[e].name);
    const double step = cells + options.loop > 1 ? double(options.last - options.first) /
                                                       double(cells + options.loop - 1)
                                                 : 1.0;
    nlohmann::json meta = {
        {"scene", s.file},
        {"effects", effectNames},
        {"grid", {{"columns", layout.columns}, {"rows", layout.rows}}},
        {"cell", {{"width", w}, {"height", h}}},
        {"sheet", {{"width", layout.sheetWidth()}, {"height", layout.sheetHeight()}}},
        {"cells", cells},
        {"order", "left to right, then top to bottom; row 0 at the top of the image"},
        {"fps", double(s.output.fps) / step},
        {"scene_fps", s.output.fps},
        {"scene_frames", cellFrames},
        {"loop",
         {{"on", options.loop > 0},
          {"cross_faded_cells", options.loop},
          {"how", "the last cells fade toward the frames before cell 0's, so the last cell "
                  "leads into the first"}}},
        {"colour",
         {{"file", "colour.png"},
          {"channels", "RGBA"},
          {"alpha", "premultiplied"},
          {"encoding", "colour premultiplied in linear light, RGB sRGB-encoded (import as sRGB), "
                       "alpha linear; blend one, one-minus-source-alpha"},
          {"tone_map", s.post.toneMap == scene::ToneMap::Aces ? "aces" : "none"},
          {"exposure", s.post.exposure},
          {"hdr", options.hdr ? nlohmann::json{{"file", "colour.exr"},
                                               {"encoding", "OpenEXR, uncompressed, half-float R, "
                                                            "G, B, A: linear light, "
                                                            "premultiplied, before the exposure "
                                                            "and tone map"}}
                              : nlohmann::json(nullptr)}}},
        {"motion_vectors", motionJson},
        {"six_way", sixWayJson},
        {"character", options.holdout ? "holdout" : "hidden"},
        {"camera",
         {{"mode", options.frameOnEffect ? "effect" : "scene"},
          {"crop", {crop.x, crop.y, crop.z, crop.w}},
          {"eye", {camera.eye.x, camera.eye.y, camera.eye.z}},
          {"view", matrixJson(camera.view)},
          {"projection", matrixJson(camera.projection)}}},
        {"evaluation", evaluation}};
    const std::string metaFile = options.out + "/flipbook.json";
    std::ofstream metaOut(metaFile);
    metaOut << meta.dump(1) << "\n";
    if (!metaOut) {
        printError("cannot write " + metaFile);
        return kExitFailure;
    }
    std::printf("baked %u cells of %ux%u (scene frames %u to %u) into %s (%ux%u)%s%s%s and %s\n",
                cells, w, h, options.first, options.last, colourFile.c_str(), layout.sheetWidth(),
                layout.sheetHeight(), options.hdr ? ", colour.exr" : "", motionNote.c_str(),
                options.sixWay ? ", the six-way sheets" : "", metaFile.c_str());
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
