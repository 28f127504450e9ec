#pragma once
// Keeping side organs clear: petioles with their leaves, peduncles with their flowers, and
// flowers and fruit one by one, turned about their attachment point out of the ground below
// their plant and out of obstacles a higher layer defines (solid obstacles:
// collision/clearance.h). See organ_clearance.cpp.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include "geometry/organ_sink.h"
#include "geometry/prototype_cache.h"
#include "model/plant_store.h"

namespace plantarch {

/// An organ placed on trial (OrganPlacer): the triangles of its tubes and its prototype parts
/// as placed, each with the organ's object slot (which tells the fruit of one peduncle apart).
class TrialSink final : public OrganSink {
public:
    struct Part {
        const OrganPrototype* prototype;
        mat4 transform;
        const std::vector<ObjectID>* owner;  ///< the organ's object IDs (FlowerOrgan::objects)
    };

    bool wants(OrganKind kind) const override { return kinds_[int(kind)]; }
    void setWanted(std::initializer_list<OrganKind> kinds);
    void write(ObjectID&, const Mesh& mesh, const Material&, const OrganLabels&) override;
    void writeParts(std::vector<ObjectID>& objects, const OrganPrototype& prototype,
                    const mat4& transform, const OrganLabels&) override;
    void clear();
    /// Keeps the parts of one organ only, and no tube.
    void keepOnly(const std::vector<ObjectID>* owner);

    std::vector<vec3> triangles;  ///< tubes, three corners a triangle
    std::vector<Part> parts;
    /// The tube being tried (petiole or peduncle): where its axis starts and its base radius,
    /// m. The ground lets a tube's surface reach its radius below the ground, or below its
    /// start where that is lower (a petiole of a stem lying on the soil).
    vec3 tubeStart{0.0f};
    float tubeRadius = 0.0f;

private:
    bool kinds_[kOrganKinds] = {};
};

/// Something side organs are kept out of.
class OrganObstacle {
public:
    virtual ~OrganObstacle() = default;
    /// Whether an organ attached at `p` that reaches no farther than `reach` (m) from it may
    /// touch this obstacle; organs that cannot are not placed at all.
    virtual bool near(vec3 p, float reach) = 0;
    /// Whether the organ held by `trial` crosses it (touching counts as clear).
    virtual bool crosses(const TrialSink& trial) = 0;
    /// The axes (unit, world) an organ attached at `attachment` may turn about, by positive
    /// angles, to leave this obstacle, best first; `trial` holds the organ, unturned, crossing
    /// it. The first axis about which a turn of at most 180 degrees clears the organ is taken.
    virtual void turnAxes(const TrialSink& trial, vec3 attachment, std::vector<vec3>& axes) = 0;

    /// What it keeps out, each organ turned about its attachment point: petioles with their
    /// leaves and peduncles with their flowers; then each flower still crossing it, about its
    /// place on the peduncle; each fruit likewise.
    bool organs = true;
    bool flowers = true;
    bool fruit = true;
};

/// Organs turned, and organs no turn could clear (left as grown).
struct ClearanceCounts {
    std::uint64_t turned = 0;
    std::uint64_t unresolved = 0;
};

/// Sets the clearance turns of the plant's petioles, peduncles, flowers and fruit from its shape
/// now:
/// an organ that crosses one of `obstacles` or, with the plant's groundClearance on, goes below
/// the plant's base (z) is turned about its attachment point away from it, in 10-degree steps
/// until clear, then back one degree at a time while still clear; every other organ gets no
/// turn. Organs are placed at mesh detail 1, so the turns do not depend on the mesh detail.
/// `counts` (may be null) gets the organs turned and those left unresolved.
void clearSideOrgans(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                     std::span<OrganObstacle* const> obstacles = {},
                     ClearanceCounts* counts = nullptr);

/// Ground clipping (PlantStore::groundClipping) at z = `height`: leaves and floral buds (peduncle,
/// flowers, fruit) whose geometry reaches below it are removed; a side shoot whose stem does stops
/// growing (its apical bud dies). State only. Returns whether anything changed.
bool clipBelowGround(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                     float height);

}  // namespace plantarch
