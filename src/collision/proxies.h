#pragma once
// Light stand-ins of organs for the collision scene, from the tessellator's placement code
// through an OrganSink, so they sit exactly where the organs' meshes do; and the overlap tests
// of the solid-obstacle clearance (clearance.cpp).

#include <array>
#include <map>
#include <memory>

#include "collision/collision_state.h"
#include "collision/collision_world.h"
#include "geometry/organ_sink.h"

namespace plantarch::collision {

/// What collision needs of one prototype, in prototype coordinates.
struct PrototypeShape {
    TriangleSoup outline;  ///< a few triangles following the blade (leaves)
    TriangleSoup box;      ///< the bounding box as 12 triangles (flowers, fruit)
    AABB bounds;
};

/// Shapes per prototype, built on first use. Not thread-safe: one per PlantArchitecture.
class ProxyCache {
public:
    const PrototypeShape& shape(const OrganPrototype& prototype);

private:
    std::map<const OrganPrototype*, PrototypeShape> shapes_;
};

/// Leaf proxies of a plant's petioles kept between refreshes, relative to each petiole's
/// start: reused while nothing that shapes the petiole and its leaves has changed (a grown
/// leaf on a grown node keeps its proxy while the stem below it still lengthens or thickens).
/// Each shoot's petioles lie in flat arrays in node order (read at every refresh, in order);
/// a shoot that grows appends to them. Only the thread refreshing the plant touches it.
struct PlantProxyMemo {
    /// The petiole's and internode's directions, angles, length, growth, leaf count, fallen
    /// leaves.
    using Key = std::array<float, 20>;
    struct Petiole {
        Key key{};
        std::uint32_t visit = 0;                  ///< the refresh that last read it
        std::uint32_t first = 0, corners = 0;     ///< its proxies in the shoot's `local`
        std::uint32_t leafFirst = 0, leaves = 0;  ///< its leaves' sines in `leafTrig`
        bool set = false;                         ///< placed at least once
        vec3 side{0.0f};                          ///< its lean when last placed
        vec3 start{0.0f};                         ///< where it started at the last refresh
    };
    struct Shoot {
        std::vector<std::uint32_t> nodeFirst{
            0};  ///< node k: petioles [nodeFirst[k], nodeFirst[k + 1])
        std::vector<Petiole> petioles;
        std::vector<PetioleTrig> trig;  ///< per petiole
        std::vector<LeafTrig> leafTrig;
        TriangleSoup local;  ///< leaf proxies relative to their petiole's start
        std::size_t unusedCorners = 0, unusedLeaves = 0;  ///< left behind in local, leafTrig
    };
    std::vector<Shoot> shoots;  ///< by shoot ID
    /// Set before each build: pointers to prototypes and their outlines are kept from one
    /// build to the next only within one epoch (World::calls), never with 0.
    std::uint64_t epoch = 0;
    std::uint64_t outlinesEpoch = 0;
    std::array<std::pair<const OrganPrototype*, const TriangleSoup*>, 32> outlines{};
    std::uint32_t visit = 0;                  ///< refreshes so far
    std::size_t visited = 0;                  ///< petioles read at the last refresh
    std::uint64_t reads = 0, placements = 0;  ///< petioles read and placed again, in all
    PlantProxies next;                  ///< the next refresh's proxies (prepared, not installed)
    bool nextChanged = true;            ///< whether they differ from the installed ones
    bool pending = false;               ///< prepared proxies not installed (growth failed)
    std::vector<LeafPlacement> leaves;  ///< scratch: one petiole's leaves
    std::vector<const TriangleSoup*> leafOutlines;  ///< scratch: their outlines (null: fallen)
    /// Scratch: the petioles read, in order, with their proxies' place and their start.
    struct Run {
        std::uint32_t shoot, node, first, corners;
        vec3 start;
    };
    std::vector<Run> runs;
};

/// The proxies of a plant's organs of the kinds in `organs`, with their organ tags. Leaves
/// alone go through `memo`; other kinds are placed afresh every time. Returns false when
/// the proxies are known to equal those `memo` gave at the last refresh, true when they may
/// differ.
bool buildProxies(const Worker& worker, PlantInstance& plant, const CollisionOrgans& organs,
                  PlantProxyMemo& memo, TriangleSoup& out, std::vector<OrganTag>& tags);

/// Collects proxies of the organ kinds that are obstacles.
class ProxySink final : public OrganSink {
public:
    ProxySink(ProxyCache& cache, const CollisionOrgans& organs, TriangleSoup& out,
              std::vector<OrganTag>& tags)
        : cache_(cache), organs_(organs), out_(out), tags_(tags) {}
    bool wants(OrganKind kind) const override;
    void write(ObjectID&, const Mesh& mesh, const Material&, const OrganLabels&) override;
    void writeParts(std::vector<ObjectID>&, const OrganPrototype& prototype, const mat4& transform,
                    const OrganLabels& labels) override;

private:
    ProxyCache& cache_;
    const CollisionOrgans& organs_;
    TriangleSoup& out_;
    std::vector<OrganTag>& tags_;
    const OrganPrototype* lastPrototype_ = nullptr;
    const PrototypeShape* lastShape_ = nullptr;
};

/// An oriented box: centre, unit axes, half extents.
struct OrientedBox {
    vec3 center{0.0f};
    vec3 axis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    vec3 half{0.0f};
};

/// Whether the box and triangle (a, b, c) overlap by more than `tolerance` (m): touching
/// surfaces count as clear.
bool boxTriangleOverlap(const OrientedBox& box, vec3 a, vec3 b, vec3 c, float tolerance);
/// Whether two triangles cross by more than `tolerance`.
bool triangleTriangleOverlap(const std::array<vec3, 3>& t, vec3 a, vec3 b, vec3 c, float tolerance);

}  // namespace plantarch::collision
