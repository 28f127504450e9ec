#pragma once
// The collision scene: what growing tips can perceive.
//
//   solid scene   the solid obstacles in an Embree BVH (ray hits with normals, nearby-triangle
//                 queries)
//   soft scene    light proxies of every plant's collision organs, the soft obstacle objects
//                 and the solid obstacles, in a hashed grid (soft_grid.h) for the perception
//                 cones' "every triangle within reach" query
//
// Each plant's proxies are kept between refreshes and replaced only when they changed; the
// grid over all of them is rebuilt at each commit (a counting sort, linear in the triangles).
// Queries are const and may run on many threads at once; changes may not overlap queries.

#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "collision/soft_grid.h"
#include "plantarch/Collision.h"
#include "plantarch/Context.h"

namespace plantarch::collision {

class AttractionIndex;
class ConePatterns;
struct PlantProxyMemo;

/// Triangle corners, three per triangle, world coordinates.
using TriangleSoup = std::vector<vec3>;
/// The organ a proxy triangle belongs to: shoot ID << 32 | node.
using OrganTag = std::uint64_t;
inline OrganTag organTag(unsigned shoot, unsigned node) {
    return (OrganTag(shoot) << 32) | node;
}

/// A plant's proxies as the scene holds them: triangles with their organ tags, bounding
/// spheres and grid cells.
struct PlantProxies {
    TriangleSoup triangles;
    std::vector<OrganTag> tags;       ///< per triangle
    std::vector<glm::vec4> spheres;   ///< per triangle
    std::vector<std::uint64_t> keys;  ///< grid cell per triangle, for cells of keyCell
    float keyCell = 0.0f;
};

/// Organs of one plant a query does not see: a growing tip's own young leaves around it.
struct Ignore {
    unsigned plant = 0;
    OrganTag organs[2] = {~OrganTag(0), ~OrganTag(0)};
};

/// Counters shared by all threads (relaxed atomics; totals do not depend on the order).
struct AtomicStats {
    std::atomic<std::uint64_t> softCones{0}, softRays{0}, softSteered{0}, solidCones{0},
        solidSteered{0}, attractionQueries{0}, attracted{0}, organsTurned{0}, organsUnresolved{0},
        sceneRefreshes{0}, plantsRebuilt{0}, plantsUnchanged{0};
    std::atomic<double> refreshSeconds{0.0};
    std::atomic<std::int64_t> coneNanoseconds{0};
};

struct SolidHit {
    float distance = 0.0f;
    vec3 normal{0.0f};  ///< unit, facing the ray's origin
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
    /// Replaces a plant's proxies (kept as they are when unchanged). Safe to call for distinct
    /// plants from several threads at once (after reservePlants). Returns whether they changed.
    bool setPlantProxies(unsigned plantID, TriangleSoup&& triangles, std::vector<OrganTag>&& tags);
    /// Makes the spheres and grid cells of `proxies`' triangles (as setPlantProxies does).
    /// Touches nothing of the scene: may run while the scene is queried.
    void index(PlantProxies& proxies) const;
    /// The same as setPlantProxies for proxies made by `index`, whose change the caller knows:
    /// with `changed` false they are the plant's already and nothing happens (unless the plant
    /// has none yet); else they become the plant's and `proxies` gets the old ones (to reuse
    /// their storage). Same thread safety.
    bool swapPlantProxies(unsigned plantID, PlantProxies& proxies, bool changed);
    void removePlant(unsigned plantID);
    /// The plant's proxies in the scene (null when it has none).
    const PlantProxies* plantProxies(unsigned plantID) const;
    bool hasPlant(unsigned plantID) const { return plants_.count(plantID) > 0; }
    /// Rebuilds the soft scene's grid after plant changes, on up to `threads` threads (the
    /// same grid for any number).
    void commit(int threads = 1);
    std::uint64_t plantTriangles() const;

    // ---- collision clock ----------------------------------------------------------------
    /// Days of growth since soft avoidance was enabled (refreshes fall on multiples of the
    /// update interval of this clock).
    double clock = 0.0;
    /// Growth calls with soft avoidance so far: the epoch within which the proxy memos keep
    /// pointers to prototypes (PlantProxyMemo::epoch).
    std::uint64_t calls = 0;
    /// Plants whose proxies must be rebuilt at the next call (edited outside growth).
    std::map<unsigned, bool> stale;
    /// Proxies of each plant's organs kept between refreshes (proxies.cpp); an entry is only
    /// touched by the thread refreshing that plant.
    std::map<unsigned, std::unique_ptr<PlantProxyMemo>> memos;

    // ---- queries (thread-safe) ---------------------------------------------------------
    /// Whether anything soft or solid lies on the segment org + t dir, t in [tnear, tfar],
    /// the organs in `ignore` (if given) excepted. Tests every triangle of the soft scene:
    /// the reference the perception cones are checked against, not for growth.
    bool softOccluded(vec3 org, vec3 dir, float tnear, float tfar,
                      const Ignore* ignore = nullptr) const;
    /// The soft obstacle triangles (plant proxies, obstacle objects) whose bounds come within
    /// `radius` of `center`, the organs in `ignore` excepted, and, given `front`, not wholly
    /// behind the plane through `center` facing `front`, copied into `out` (cleared first).
    void softTrianglesNear(vec3 center, float radius, const Ignore* ignore, TriangleBatch& out,
                           const vec3* front = nullptr) const;
    /// Nearest solid obstacle on the segment, if any.
    std::optional<SolidHit> solidHit(vec3 org, vec3 dir, float tnear, float tfar) const;
    bool hasSolid() const { return !solidTriangles_.empty(); }
    /// Indices of solid triangles whose bounds come within `radius` of `center`.
    void solidTrianglesNear(vec3 center, float radius, std::vector<unsigned>& out) const;
    const std::array<vec3, 3>& solidTriangle(unsigned i) const { return solidTriangles_[i]; }
    /// The closest point on the solid obstacles to `p` within `radius`, and that triangle's
    /// normal facing `p`.
    std::optional<SolidHit> closestSolid(vec3 p, float radius) const;

    /// The ray sets of a perception cone's shape (the soft cone's are kept at hand).
    std::shared_ptr<const ConePatterns> patterns(const PerceptionCone& cone) const;

    AtomicStats& stats() const { return stats_; }
    CollisionStats snapshotStats() const;
    void resetStats();

    struct Embree;  ///< Embree handles (collision_world.cpp)

private:
    void buildStaticScenes(const Context& ctx);
    float gridCell() const;

    std::optional<SoftCollisionOptions> soft_;
    std::optional<SolidObstacleOptions> solid_;
    std::vector<std::array<vec3, 3>> solidTriangles_;
    TriangleSoup softStatic_;  ///< soft objects and solid obstacles
    std::vector<glm::vec4> softStaticSpheres_;
    std::vector<std::uint64_t> softStaticKeys_;
    struct PlantSlot;
    std::map<unsigned, std::unique_ptr<PlantSlot>> plants_;
    SoftGrid grid_;
    std::shared_ptr<const ConePatterns> softPatterns_;
    std::unique_ptr<Embree> rtc_;
    mutable AtomicStats stats_;
};

}  // namespace plantarch::collision
