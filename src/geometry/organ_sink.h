#pragma once
// Where tessellation puts a plant's organs. The Context is one destination (the plant's
// geometry); collision avoidance is another (light proxies of the organs it treats as
// obstacles, and single organs placed on trial while turning them out of solid obstacles).
// Both run the same placement code, so an organ's proxy sits exactly where its mesh does.

#include <optional>
#include <span>
#include <vector>

#include "core/math.h"
#include "geometry/prototype_cache.h"
#include "geometry/tube.h"
#include "model/plant_store.h"

namespace plantarch {

/// What an organ is, for labels and for sinks that keep only some kinds.
struct OrganLabels {
    OrganKind kind;
    const Shoot* shoot;
    int node;
    float age;
    int leafID = -1;
};

class OrganSink {
public:
    virtual ~OrganSink() = default;
    /// Whether organs of this kind are wanted; unwanted ones are not meshed at all.
    virtual bool wants(OrganKind kind) const = 0;
    /// One organ made of `mesh` (tubes: internodes, petioles, peduncles).
    virtual void write(ObjectID& object, const Mesh& mesh, const Material& material,
                       const OrganLabels& labels) = 0;
    /// One organ made of the parts of a prototype placed by `transform` (leaves, flowers, fruit).
    virtual void writeParts(std::vector<ObjectID>& objects, const OrganPrototype& prototype,
                            const mat4& transform, const OrganLabels& labels) = 0;
    /// An organ that has no geometry now (fallen, not yet visible, of zero size).
    virtual void remove(ObjectID& object) { (void)object; }
    virtual void removeAll(std::vector<ObjectID>& objects) { (void)objects; }
};

/// Places every organ of the plant into `sink` (the plant's state as it stands), with the
/// shoot types of `store` (for types the plant holds no copy of) and the prototypes of
/// `prototypes`.
void tessellatePlant(const PlantStore& store, PrototypeCache& prototypes, OrganSink& sink,
                     PlantInstance& plant);

/// The sines and cosines of an organ's pitch, yaw and roll.
struct TurnTrig {
    SinCos pitch, yaw, roll;
};

/// What placing a leaf takes of its angles: kept by a caller that places the same leaves again
/// and again (OrganPlacer::leaves), so the sines are taken again only where an angle changed.
/// `set` false: nothing kept yet.
struct LeafTrig {
    float pitch = 0.0f, yaw = 0.0f, roll = 0.0f;
    int leaflet = 0;  ///< LeafOrgan::leafletIndex
    TurnTrig turn;
    SinCos swing;  ///< lateral leaflets: their swing toward the tip (yaw)
    bool set = false;
    /// A leaf with a target pose (LeafOrgan::angleTarget): `target` holds it and `normal` is
    /// the world direction of its blade's mean normal; `prototypeNormal` is the mean normal
    /// of the leaf's prototype (prototype coordinates, set by the caller with the prototype).
    std::optional<LeafAngleTarget> target;
    vec3 normal{0.0f, 0.0f, 1.0f};
    vec3 prototypeNormal{0.0f, 0.0f, 1.0f};
    const OrganPrototype* normalPrototype = nullptr;  ///< the prototype prototypeNormal is of
    /// The leaf's prototype as last looked up, for the parameters, variant and leaf ID it was
    /// looked up for, while PetioleTrig::epoch is the one it was looked up in.
    const OrganPrototype* prototype = nullptr;
    const LeafParameters* parameters = nullptr;
    unsigned variant = 0;
    int leafID = -1;
    std::uint64_t epoch = 0;
};

/// The same for a petiole's own angles and curve.
struct PetioleTrig {
    /// Set by the caller: prototypes kept in LeafTrig are used again only within one epoch, not
    /// at all with 0 (prototypes live as long as the caches of the PlantArchitecture that made
    /// them).
    std::uint64_t epoch = 0;
    float azimuth = 0.0f, pitch = 0.0f;
    SinCos azimuthTrig, pitchTrig;
    bool set = false;
    // The petiole's lean and initial direction for these sines, its internode's axes and its
    // clearance turn as last seen (frameSet false: none kept).
    vec3 axis{0.0f}, guide{0.0f}, rollReference{0.0f};
    OrganTurn clearance;
    vec3 side{0.0f}, dir{0.0f};
    bool frameSet = false;
    // The petiole's curve for its last direction and curvature sign.
    vec3 direction{0.0f};
    bool bendsUp = false, curveSet = false;
    geometry::CurveBasis curve;
};

/// One leaf of a petiole as tessellation places it: its prototype (null: fallen, or of zero size)
/// and the transform of the prototype's coordinates to the world.
struct LeafPlacement {
    const OrganPrototype* prototype = nullptr;
    mat4 transform{1.0f};
};

/// Places single organs of one plant, for trials (collision clearance). Node positions are
/// computed once when it is made: the plant's shape must not change while it is used.
class OrganPlacer {
public:
    OrganPlacer(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant);
    /// The same at mesh detail `detail` instead of the store's (1: each organ's own resolution,
    /// at which growth decides what depends on shape, so that no state depends on the detail).
    OrganPlacer(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                float detail);
    ~OrganPlacer();
    OrganPlacer(const OrganPlacer&) = delete;
    OrganPlacer& operator=(const OrganPlacer&) = delete;

    /// World positions of the nodes of a shoot: [0] its base, [i+1] the tip of internode i
    /// (empty for a removed shoot).
    const std::vector<vec3>& nodes(unsigned shoot) const;
    /// The petiole `petiole` of node `node` on shoot `shoot`, with its leaves.
    void petiole(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole);
    /// Where that petiole starts (its organs move with this point when the plant below grows).
    vec3 petioleStart(unsigned shoot, unsigned node, unsigned petiole) const;
    /// The leaves of that petiole, placed by the same formulas as `petiole` places them but
    /// with no mesh made and no sink: `out` gets one entry per leaf, in order. `trig` and
    /// `leafTrig` (one per leaf) keep the angles' sines from one call to the next (for this
    /// petiole only). Returns where the petiole starts; `side` is its lean (see
    /// petioleStartOn).
    vec3 leaves(unsigned shoot, unsigned node, unsigned petiole, PetioleTrig& trig,
                std::span<LeafTrig> leafTrig, std::vector<LeafPlacement>& out, vec3& side);
    /// Where the petiole of node `node` with lean `side` starts: equal to petioleStart while
    /// its internode's direction, guide and roll reference and its own azimuth are those
    /// `side` was had with (the internode's length and radius may differ).
    vec3 petioleStartOn(unsigned shoot, unsigned node, vec3 side) const;
    /// A floral bud's peduncle, flowers or fruit: an axillary bud (petiole, bud) of a node, or
    /// the shoot's terminal bud `bud` when `terminal`.
    void floralBud(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole, unsigned bud,
                   bool terminal);

    struct State;

private:
    std::unique_ptr<State> state_;
};

namespace geometry {
/// An organ's frame: x along it, y and z across.
struct OrganFrame {
    vec3 x, y, z;
};

/// The frame with x along `axis` (any length) and z as near world up as it can be (else toward
/// `fallbackUp`, else any perpendicular); y = z x x.
[[gnu::always_inline]] inline OrganFrame uprightFrame(vec3 axis, vec3 fallbackUp) {
    constexpr vec3 up{0.0f, 0.0f, 1.0f};
    OrganFrame f;
    f.x = glm::normalize(axis);
    vec3 z = up - glm::dot(up, f.x) * f.x;
    if (glm::length(z) < 1e-4f) z = fallbackUp - glm::dot(fallbackUp, f.x) * f.x;
    if (glm::length(z) < 1e-6f) z = anyPerpendicular(f.x);
    f.z = glm::normalize(z);
    f.y = glm::cross(f.z, f.x);
    return f;
}

/// Where a leaf's prototype goes: at `origin` on its petiole (or rachis) heading along unit
/// `tangent`, with the petiole leaning toward `side`, turned by the leaf's angles (`t`, from
/// trigOf-style sines of its pitch, yaw and roll) and scaled by `scale`; `offset` is the
/// prototype's leaf_offset. The frame: x along the tangent, z as near world up as it can be
/// (else toward `side`), y = z x x. A lateral leaflet (t.leaflet != 0) first points x across
/// the rachis on its side (+y when t.leaflet < 0, else -y), swung toward the tip by t.swing.
/// Then t.turn: pitch lifts x toward z, yaw turns x toward y, roll turns y toward z. A leaf
/// with a target (t.target) is then turned about `origin` so that its prototype's mean normal
/// (t.prototypeNormal) points along t.normal, its midrib as near the turned x as it can be.
mat4 leafTransform(vec3 origin, vec3 tangent, vec3 side, const LeafTrig& t, float scale,
                   vec3 offset);

/// The area-weighted mean normal of a leaf prototype's triangles (prototype coordinates, the
/// side of +z: a blade's upper side), unit; +z for a prototype with no such normal (a blade
/// folded shut).
vec3 meanNormal(const OrganPrototype& prototype);

/// The world direction of the mean normal of a leaf with target pose `t`: `inclination` from
/// the zenith, facing `azimuth` clockwise from north (+y).
vec3 targetNormal(const LeafAngleTarget& t);
}  // namespace geometry

}  // namespace plantarch
