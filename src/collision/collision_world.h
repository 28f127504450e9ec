#pragma once
// The collision scene: Embree BVHs of what growing tips can perceive.
//
//   solid scene   the solid obstacles (ray hits with normals, nearby-triangle queries)
//   static scene  the soft obstacle objects and the solid obstacles (built when enabled)
//   plant scenes  one small BVH per plant over light proxies of its collision organs
//   top scene     instances of the static scene and of every plant scene
//
// Plants are separate BVHs so a refresh rebuilds only the plants whose proxies changed and the
// small top level over the instances; distant plants are culled by their instance bounds.
// Queries are const and may run on many threads at once; changes may not overlap queries.

#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Context.h"

namespace plantarch::collision {

class AttractionIndex;
struct PlantProxyMemo;

/// Triangle corners, three per triangle, world coordinates.
using TriangleSoup = std::vector<vec3>;
/// The organ a proxy triangle belongs to: shoot ID << 32 | node.
using OrganTag = std::uint64_t;
inline OrganTag organTag(unsigned shoot, unsigned node) {
    return (OrganTag(shoot) << 32) | node;
}

/// Organs of one plant a query does not see: a growing tip's own young leaves around it.
struct Ignore {
    unsigned plant = 0;
    OrganTag organs[2] = {~OrganTag(0), ~OrganTag(0)};
};

/// Counters shared by all threads (relaxed atomics; totals do not depend on the order).
struct AtomicStats {
    std::atomic<std::uint64_t> softCones{0}, softRays{0}, softSteered{0}, solidCones{0},
        solidSteered{0}, attractionQueries{0}, attracted{0}, organsTurned{0},
        organsUnresolved{0}, sceneRefreshes{0}, plantsRebuilt{0}, plantsUnchanged{0};
    std::atomic<double> refreshSeconds{0.0};
    std::atomic<std::int64_t> coneNanoseconds{0};
};

struct SolidHit {
    float distance = 0.0f;
    vec3 normal{0.0f};   ///< unit, facing the ray's origin
    vec3 point{0.0f};
};

class World {
public:
    World();
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // ---- settings (validated by the caller) ------------------------------------------
    const std::optional<SoftCollisionOptions>& soft() const { return soft_; }
    const std::optional<SolidObstacleOptions>& solid() const { return solid_; }
    /// Reads the soft obstacle objects from `ctx` and rebuilds the static scene.
    void setSoft(std::optional<SoftCollisionOptions> options, const Context& ctx);
    /// Reads the solid obstacles from `ctx` and rebuilds the solid and static scenes.
    void setSolid(std::optional<SolidObstacleOptions> options, const Context& ctx);
    /// Attraction points of every plant without its own (null: none).
    std::shared_ptr<const AttractionIndex> globalAttraction;

    // ---- plants (soft avoidance) -------------------------------------------------------
    /// Makes room for these plants (call before setPlantProxies for them, single-threaded).
    void reservePlants(const std::vector<unsigned>& plantIDs);
    /// Replaces a plant's proxies; rebuilds its BVH only when they changed. Safe to call for
    /// distinct plants from several threads at once (after reservePlants). Returns whether
    /// the BVH was rebuilt.
    bool setPlantProxies(unsigned plantID, TriangleSoup&& triangles, std::vector<OrganTag>&& tags);
    void removePlant(unsigned plantID);
    bool hasPlant(unsigned plantID) const { return plants_.count(plantID) > 0; }
    /// Commits the top level after plant changes (single-threaded).
    void commit();
    std::uint64_t plantTriangles() const;

    // ---- collision clock ----------------------------------------------------------------
    /// Days of growth since soft avoidance was enabled (refreshes fall on multiples of the
    /// update interval of this clock).
    double clock = 0.0;
    /// Plants whose proxies must be rebuilt at the next call (edited outside growth).
    std::map<unsigned, bool> stale;
    /// Proxies of each plant's organs kept between refreshes (proxies.cpp); an entry is only
    /// touched by the thread refreshing that plant.
    std::map<unsigned, std::unique_ptr<PlantProxyMemo>> memos;

    // ---- queries (thread-safe) ---------------------------------------------------------
    /// Whether anything soft or solid lies on the segment org + t dir, t in [tnear, tfar],
    /// the organs in `ignore` (if given) excepted.
    bool softOccluded(vec3 org, vec3 dir, float tnear, float tfar,
                      const Ignore* ignore = nullptr) const;
    /// The soft obstacle triangles (plant proxies, obstacle objects) whose bounds come within
    /// `radius` of `center`, the organs in `ignore` excepted: pointers to their first corner
    /// (three consecutive corners each), valid until the scene changes.
    void softTrianglesNear(vec3 center, float radius, const Ignore* ignore,
                           std::vector<const vec3*>& out) const;
    /// Nearest solid obstacle on the segment, if any.
    std::optional<SolidHit> solidHit(vec3 org, vec3 dir, float tnear, float tfar) const;
    bool hasSolid() const { return !solidTriangles_.empty(); }
    /// Indices of solid triangles whose bounds come within `radius` of `center`.
    void solidTrianglesNear(vec3 center, float radius, std::vector<unsigned>& out) const;
    const std::array<vec3, 3>& solidTriangle(unsigned i) const { return solidTriangles_[i]; }
    /// The closest point on the solid obstacles to `p` within `radius`, and that triangle's
    /// normal facing `p`.
    std::optional<SolidHit> closestSolid(vec3 p, float radius) const;

    AtomicStats& stats() const { return stats_; }
    CollisionStats snapshotStats() const;
    void resetStats();

    struct Embree;  ///< Embree handles (collision_world.cpp)
    /// Triangles and tags of an instance of the top scene (0: the static scene).
    struct InstanceView {
        const TriangleSoup* triangles = nullptr;
        const std::vector<OrganTag>* tags = nullptr;
        unsigned plant = 0;
    };

private:
    void buildStaticScenes(const Context& ctx);
    void attachInstances();

    std::optional<SoftCollisionOptions> soft_;
    std::optional<SolidObstacleOptions> solid_;
    std::vector<std::array<vec3, 3>> solidTriangles_;
    TriangleSoup softStatic_;  ///< soft objects and solid obstacles
    struct PlantSlot;
    std::map<unsigned, std::unique_ptr<PlantSlot>> plants_;
    std::vector<InstanceView> instances_;  ///< by instance ID in the top scene
    std::unique_ptr<Embree> rtc_;
    mutable AtomicStats stats_;
};

}  // namespace plantarch::collision
