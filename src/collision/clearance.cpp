// Solid obstacles for the clearance of side organs (growth/organ_clearance.cpp turns the
// organs): an organ crosses one when a triangle of its tubes or the bounding box of one of its
// prototype parts overlaps an obstacle triangle by more than a tolerance.

#include "collision/clearance.h"

#include <cmath>

#include "collision/collision_world.h"
#include "core/math.h"

namespace plantarch::collision {

namespace {

// Overlap of less than this counts as touching, not crossing (m).
constexpr float kTolerance = 1e-5f;

}  // namespace

SolidClearance::SolidClearance(const Worker& worker, const World& world)
    : worker_(worker), world_(world) {
    if (!world.solid() || !world.hasSolid()) return;
    const SolidObstacleOptions& o = *world.solid();
    organs = o.organClearance;
    flowers = false;  // flowers turn with their peduncle only
    fruit = o.fruitAdjustment;
    active_ = organs || fruit;
}

bool SolidClearance::near(vec3 p, float reach) {
    world_.solidTrianglesNear(p, reach, candidates_);
    return !candidates_.empty();
}

void SolidClearance::shape(const TrialSink& trial) {
    boxes_.clear();
    bounds_ = AABB{};
    for (const vec3& q : trial.triangles) bounds_.add(q);
    for (const TrialSink::Part& part : trial.parts) {
        const PrototypeShape& s = worker_.proxies.shape(*part.prototype);
        if (s.bounds.empty()) continue;
        const mat4& xf = part.transform;
        OrientedBox b;
        const vec3 localCenter = s.bounds.center();
        const vec3 localHalf = 0.5f * s.bounds.extent();
        b.center = vec3(xf * glm::vec4(localCenter, 1.0f));
        for (int i = 0; i < 3; ++i) {
            const vec3 col = vec3(xf[i]);
            const float len = glm::length(col);
            b.axis[i] = len > 0.0f ? col / len : vec3(i == 0, i == 1, i == 2);
            b.half[i] = localHalf[i] * len;
        }
        boxes_.push_back(b);
        for (int i = 0; i < 8; ++i) {
            vec3 corner = b.center;
            for (int k = 0; k < 3; ++k)
                corner += ((i >> k) & 1 ? 1.0f : -1.0f) * b.half[k] * b.axis[k];
            bounds_.add(corner);
        }
    }
}

bool SolidClearance::crosses(const TrialSink& trial) {
    shape(trial);
    if (bounds_.empty()) return false;
    const vec3 c = bounds_.center();
    world_.solidTrianglesNear(c, 0.5f * glm::length(bounds_.extent()) + kTolerance, candidates_);
    for (unsigned i : candidates_) {
        const auto& t = world_.solidTriangle(i);
        for (const OrientedBox& b : boxes_)
            if (boxTriangleOverlap(b, t[0], t[1], t[2], kTolerance)) return true;
        for (std::size_t k = 0; k + 2 < trial.triangles.size(); k += 3)
            if (triangleTriangleOverlap(t, trial.triangles[k], trial.triangles[k + 1],
                                        trial.triangles[k + 2], kTolerance))
                return true;
    }
    return false;
}

void SolidClearance::turnAxes(const TrialSink& trial, vec3 attachment, std::vector<vec3>& axes) {
    shape(trial);
    const vec3 out = glm::normalize(bounds_.center() - attachment);
    const auto contact = world_.closestSolid(attachment, 1e3f);
    const vec3 n = contact ? contact->normal : vec3(0, 0, 1);
    const vec3 axis = glm::cross(out, n);
    axes.assign(1, glm::length(axis) > 1e-4f ? glm::normalize(axis) : anyPerpendicular(n));
}

void countClearance(const World& world, const ClearanceCounts& counts) {
    AtomicStats& st = world.stats();
    st.organsTurned.fetch_add(counts.turned, std::memory_order_relaxed);
    st.organsUnresolved.fetch_add(counts.unresolved, std::memory_order_relaxed);
}

void clearOrgans(const Worker& worker, const World& world, PlantInstance& plant) {
    SolidClearance solid(worker, world);
    OrganObstacle* const solids[] = {&solid};
    ClearanceCounts counts;
    clearSideOrgans(worker.store, worker.prototypes, plant,
                    solid.active() ? std::span<OrganObstacle* const>(solids)
                                   : std::span<OrganObstacle* const>(),
                    &counts);
    countClearance(world, counts);
}

}  // namespace plantarch::collision
