// The viewer panel's model under random use: 200 edits of random keys of a scene with every
// effect kind (random sections, keys and values in the ranges the widgets offer) through the
// scene document, each one the reader accepts played by the viewer's session (rebuilt and
// re-simulated to the frame shown, then a frame drawn), with no crash and no Vulkan validation
// error. Values the reader or the character refuses leave the scene playing as it was.
#include "apps/panel_widgets.h"
#include "apps/view_session.h"
#include "core/gpu/commands.h"
#include "core/scene/scene_document.h"
#include "gpu_test.h"
#include "render/image_output.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>

namespace mfx::test {
namespace {

using nlohmann::json;
using scene::ParamInfo;

class PanelEdits : public GpuTest {};

// Every effect kind, small: the picture, the frames and the smoke grid.
const char* const kEveryKind = R"({
  "output": {"width": 64, "height": 36, "frames": 6},
  "effects": [
    {"type": "speed_lines", "name": "lines", "bones": ["foot_r", "toe_r"]},
    {"type": "motion_blur", "name": "blur", "bones": ["shin_r", "foot_r"]},
    {"type": "motion_particles", "name": "particles", "bones": ["foot_r"]},
    {"type": "smoke", "name": "smoke", "bones": ["foot_r"], "grid": [16, 16, 16],
     "cell_size": 0.12},
    {"type": "afterimage_smear", "name": "smear", "bones": ["shin_r", "foot_r"]},
    {"type": "swept_volume", "name": "swept", "bones": ["foot_r"]},
    {"type": "silhouette_shell", "name": "shell", "bones": ["foot_r"]}
  ]
})";

// A value of `p` the panel's widget could give: in range, numbers log-uniform over wide ranges.
json randomValue(const ParamInfo& p, const std::vector<ParamInfo>& table, std::mt19937& rng) {
    using T = ParamInfo::Type;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const app::PanelWidget w = app::widgetFor(p, table);
    auto number = [&](double low, double high) {
        if (high - low > 1000.0 && high > 0.0) {
            const double a = std::log(std::max(low, 1e-3)), b = std::log(high);
            return std::clamp(std::exp(a + (b - a) * unit(rng)), low, high);
        }
        return low + (high - low) * unit(rng);
    };
    switch (p.type) {
    case T::Number:
        return number(app::widgetLowest(w), w.max);
    case T::Integer:
        return uint32_t(std::llround(number(w.min, w.max)));
    case T::Boolean:
        return unit(rng) < 0.5;
    case T::Choice:
        return p.choices[size_t(unit(rng) * double(p.choices.size())) % p.choices.size()];
    case T::Colour:
        return json::array({unit(rng), unit(rng), unit(rng), unit(rng)});
    case T::Vec3:
        return json::array({number(-5.0, 5.0), number(-5.0, 5.0), number(-5.0, 5.0)});
    case T::Numbers: {
        json v = json::array();
        for (size_t i = 0; i < p.minCount; ++i)
            v.push_back(std::llround(number(p.low, std::min(p.high, 64.0))));
        return v;
    }
    case T::Strings: {
        const char* names[] = {"foot_r", "toe_r", "shin_r", "hand_l", "legs", "no_such_bone"};
        return json::array({names[size_t(unit(rng) * 6) % 6]});
    }
    case T::String:
        return unit(rng) < 0.5 ? json("fighter") : json("edited");
    case T::CharacterName:
        return unit(rng) < 0.75 ? json("p1") : json("no_such_character");
    case T::Objects: {
        const size_t count = 2 + size_t(unit(rng) * double(p.maxCount - 1)) % (p.maxCount - 1);
        std::vector<double> at;
        for (size_t i = 0; i < count; ++i)
            at.push_back(unit(rng));
        std::sort(at.begin(), at.end());
        json stops = json::array();
        for (double a : at) {
            json stop = {{"at", a}};
            for (const ParamInfo& q : table)
                if (q.key.rfind(p.key + "[].", 0) == 0 && q.key != p.key + "[].at")
                    stop[q.key.substr(p.key.size() + 3)] = randomValue(q, table, rng);
            stops.push_back(stop);
        }
        return stops;
    }
    }
    return json();
}

// The viewer's session on the scene file `file`, read and started as `motionfx view FILE` does
// (at 64x36); null, with the failure reported, where it cannot be. The session refers to the
// arguments, kept beside it.
struct StartedView {
    cli::ParsedArgs parsed;
    std::unique_ptr<app::ViewSession> session;
};
std::unique_ptr<StartedView> startView(const gpu::Context& ctx, const std::string& file) {
    auto started = std::make_unique<StartedView>();
    started->parsed.positional = {file};
    Result<app::SceneArgument> first = app::readSceneArgument(started->parsed, "64x36", nullptr);
    EXPECT_TRUE(first.ok()) << first.error().message;
    if (!first) return nullptr;
    started->session = std::make_unique<app::ViewSession>(
        ctx, started->parsed, "64x36", std::move(first).value(), VK_SAMPLE_COUNT_1_BIT);
    const Status running = started->session->start();
    EXPECT_TRUE(running.ok()) << running.error().message;
    return running ? std::move(started) : nullptr;
}

TEST_F(PanelEdits, TwoHundredRandomEditsPlayWithoutCrashOrValidationError) {
    const std::filesystem::path dir = std::filesystem::path(MFX_TEST_OUTPUT_DIR) / "panel_edits";
    std::filesystem::create_directories(dir);
    const std::string file = (dir / "scene.json").string();
    std::ofstream(file) << kEveryKind;
    Result<scene::SceneDocument> base = scene::SceneDocument::load(file);
    ASSERT_TRUE(base.ok()) << base.error().message;
    const std::unique_ptr<StartedView> viewer = startView(ctx(), file);
    ASSERT_TRUE(viewer);
    app::ViewSession& view = *viewer->session;
    gpu::CommandBuffer commands = gpu::CommandBuffer::create(ctx(), ctx().graphicsQueue());
    auto drawFrame = [&](bool advance) {
        view.record(commands.begin(), advance);
        commands.end();
        commands.submit();
        commands.wait();
        view.finish();
    };
    for (int f = 0; f < 3; ++f) // on to frame 3, where the kick is under way
        drawFrame(true);

    std::mt19937 rng(20261127);
    scene::SceneDocument doc = base.value();
    int played = 0, refused = 0, notPlayed = 0;
    const auto started = std::chrono::steady_clock::now();
    for (int edit = 0; edit < 200; ++edit) {
        // Every tenth edit starts again from the file, so that no run of edits piles up cost
        // (a 64^3 grid stepped 30 times a frame at 1,000 Jacobi sweeps) beyond a test's time.
        if (edit % 10 == 0) doc = base.value();
        std::vector<std::string> sections;
        for (size_t e = 0; e < doc.scene().effects.size(); ++e)
            sections.push_back("effects[" + std::to_string(e) + "]");
        for (const std::string& s : scene::sceneSections())
            if (s != "lights") sections.push_back(s);
        const std::string section = sections[rng() % sections.size()];
        const std::vector<ParamInfo> table = doc.params(section);
        std::vector<const ParamInfo*> keys;
        for (const ParamInfo& p : table)
            if (p.key != "type" && p.key.find("[].") == std::string::npos) keys.push_back(&p);
        const ParamInfo& p = *keys[rng() % keys.size()];
        const json value = randomValue(p, table, rng);
        SCOPED_TRACE("edit " + std::to_string(edit) + ": " + section + "." + p.key + " = " +
                     value.dump());
        const scene::SceneDocument before = doc;
        if (Status set = doc.set(section, p.key, value); !set) {
            ++refused; // the reader's own refusal, naming the key
            EXPECT_NE(set.error().message.find(p.key.substr(0, p.key.find('['))), std::string::npos)
                << set.error().message;
            continue;
        }
        if (Status replaced = view.replace(doc.scene()); !replaced) {
            ++notPlayed; // e.g. a bone the character does not have: the old scene plays on
            EXPECT_FALSE(replaced.error().message.empty());
            doc = before;
            drawFrame(false);
            continue;
        }
        ++played;
        drawFrame(true);
        ASSERT_TRUE(describeMessages().empty()) << describeMessages();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::printf("200 panel edits: %d played, %d refused by the reader, %d not played (the "
                "character), %.1f s\n",
                played, refused, notPlayed, seconds);
    EXPECT_GE(played, 120) << "most random edits in range are played";
}

// A ribbon's texture named in the panel: a file that is not there is refused in one line naming
// the key (the old scene plays on), one that is there is drawn and watched with the scene file.
TEST_F(PanelEdits, ATextureNamedInThePanelIsCheckedAndWatched) {
    const std::filesystem::path dir =
        std::filesystem::path(MFX_TEST_OUTPUT_DIR) / "panel_edits_texture";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string file = (dir / "scene.json").string();
    std::ofstream(file) << R"({"output": {"frames": 4},
                              "effects": [{"type": "speed_lines", "stride": 40}]})";
    const std::vector<uint8_t> texels(4 * 4 * 4, 255);
    ASSERT_TRUE(render::writePng((dir / "stripes.png").string(), 4, 4, texels).ok());
    Result<scene::SceneDocument> doc = scene::SceneDocument::load(file);
    ASSERT_TRUE(doc.ok()) << doc.error().message;
    const std::unique_ptr<StartedView> viewer = startView(ctx(), file);
    ASSERT_TRUE(viewer);
    app::ViewSession& view = *viewer->session;
    EXPECT_EQ(view.files().size(), 1u);

    ASSERT_TRUE(doc.value().set("effects[0]", "texture", "missing.png").ok());
    Status missing = view.replace(doc.value().scene());
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("effects[0].texture: no file"), std::string::npos)
        << missing.error().message;

    ASSERT_TRUE(doc.value().set("effects[0]", "texture", "stripes.png").ok());
    ASSERT_TRUE(view.replace(doc.value().scene()).ok());
    const std::vector<std::filesystem::path> files = view.files();
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(std::filesystem::weakly_canonical(files[1]),
              std::filesystem::weakly_canonical(dir / "stripes.png"));
}

} // namespace
} // namespace mfx::test
