// One effect of a scene (docs/architecture.md, "Adding an effect kind"): what every effect has --
// its name, its time window, the bones and meshes whose vertices it is bound to -- and its kind's
// own settings, a value of one of the kinds the registry lists (core/scene/effect_kinds.h), each
// in its own file under core/scene/kinds/ with its keys, defaults, parser and checks.
#pragma once

#include "core/trajectory/trajectory_kind.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mfx::scene {

// What the simulation keeps for an effect drawn from a trajectory queue (sim/scene_simulation.h):
// the queue's shape and sub-sampling, how long a segment lives, which vertices, and the colour and
// alpha of a segment over its life.
struct TrailSpec {
    trajectory::Kind shape = trajectory::Kind::Lines;
    uint32_t subSamples = 4;
    uint32_t lifetime = 12; // frames
    uint32_t stride = 1;    // every n-th source vertex (volumes keep every vertex)
    glm::vec4 colour{1.0f}; // RGBA; the mesh colour when "colour" is absent
    bool useMeshColour = true;
    float alphaStart = 1.0f;
    float alphaEnd = 0.0f;
    float alphaPower = 1.0f;
    // Only the two bound vertices spanning the selection from the joint it hangs from outwards (a
    // speed-line sheet between them; trajectory::twoEnds), instead of every stride-th.
    bool twoEnds = false;
};

// How many vertices fitScene leaves an effect without "stride" (scene_fit.h).
enum class StrideTarget { EveryVertex, Lines, Particles };

// A kind's own settings. The kinds are plain structs deriving from EffectKind<Kind> (below); the
// virtual functions are what the kind-independent code (fitting, simulation) asks of any kind.
class EffectKindSpec {
public:
    virtual ~EffectKindSpec() = default;
    virtual std::unique_ptr<EffectKindSpec> clone() const = 0;
    // The scene file's "type" (the registry's name for the kind).
    virtual const char* type() const = 0;
    // The trajectory queue the simulation keeps for the effect; null: none (the kind keeps its
    // own history in its pass).
    virtual const TrailSpec* queue() const { return nullptr; }
    // The stride fitScene chooses when the file gives none; null: the kind has no stride.
    virtual uint32_t* strideValue() { return nullptr; }
    virtual StrideTarget strideTarget() const { return StrideTarget::EveryVertex; }
    // The kind's lengths in world units, by key: fitScene scales those the file did not give to a
    // character sized outside the human range.
    virtual std::vector<std::pair<const char*, float*>> lengths() { return {}; }
    // Whether the effect shows something while its vertices stand still (motionlessEffects does
    // not warn about it).
    virtual bool showsAtRest() const { return false; }
    // Whether it fades out in front of the scene's surfaces (a depth_fade above 0): the frame then
    // copies the scene's depth for it (render/frame_renderer.cpp).
    virtual bool fadesAgainstDepth() const { return false; }
    // For an effect emitted from the surface: the UV-space step its points are sampled at
    // (core/scene/effect_source.h).
    virtual std::optional<float> surfaceSampling() const { return std::nullopt; }

protected:
    EffectKindSpec() = default;
    EffectKindSpec(const EffectKindSpec&) = default;
    EffectKindSpec& operator=(const EffectKindSpec&) = default;
};

// The base of every kind: its type name is Kind::kType.
template <class Kind>
class EffectKind : public EffectKindSpec {
public:
    std::unique_ptr<EffectKindSpec> clone() const override {
        return std::make_unique<Kind>(static_cast<const Kind&>(*this));
    }
    const char* type() const override { return Kind::kType; }
};

class EffectSpec {
public:
    template <class Kind>
    requires std::is_base_of_v<EffectKindSpec, Kind>
    explicit EffectSpec(Kind kind, std::string effectName = {})
        : name(std::move(effectName)), kind_{std::make_unique<Kind>(std::move(kind))} {}
    explicit EffectSpec(std::unique_ptr<EffectKindSpec> kind) : kind_{std::move(kind)} {}

    std::string name;                // default: type and index, e.g. "speed_lines#0"
    std::string character;           // the name of the character it follows; empty: the first
    std::vector<std::string> bones;  // empty: the whole character
    std::vector<std::string> meshes; // empty: every mesh
    float minBoneWeight = 0.5f;
    // Set by the parser where the effect has neither "bones" nor "meshes" (fitScene binds it to
    // the fastest limb) and where it has no "stride" (fitScene chooses one from the vertex count).
    bool automaticBones = false;
    bool automaticStride = false;
    // The keys the scene file gave this effect (fitScene scales the length defaults of the others
    // to a character sized outside the human range on purpose).
    std::vector<std::string> givenKeys;
    bool given(const std::string& key) const {
        return std::find(givenKeys.begin(), givenKeys.end(), key) != givenKeys.end();
    }
    float start = 0.0f;       // the window, in scene seconds
    std::optional<float> end; // default: the end of the scene

    // The kind: its name, and its settings when it is `Kind` (else null).
    const char* type() const { return kind_.value->type(); }
    template <class Kind>
    bool is() const {
        return dynamic_cast<const Kind*>(kind_.value.get());
    }
    template <class Kind>
    const Kind* as() const {
        return dynamic_cast<const Kind*>(kind_.value.get());
    }
    template <class Kind>
    Kind* as() {
        return dynamic_cast<Kind*>(kind_.value.get());
    }
    const EffectKindSpec& kind() const { return *kind_.value; }
    EffectKindSpec& kind() { return *kind_.value; }

private:
    // The kind, copied by cloning, so EffectSpec's copies are the defaulted member-wise ones.
    struct Owned {
        std::unique_ptr<EffectKindSpec> value; // never null
        Owned(std::unique_ptr<EffectKindSpec> v) : value(std::move(v)) {}
        Owned(const Owned& o) : value(o.value->clone()) {}
        Owned& operator=(const Owned& o) {
            if (this != &o) value = o.value->clone();
            return *this;
        }
        Owned(Owned&&) = default;
        Owned& operator=(Owned&&) = default;
    };
    Owned kind_;
};

} // namespace mfx::scene
