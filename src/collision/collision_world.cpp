// The collision scene on Embree (see collision_world.h).

#include "collision/collision_world.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "collision/cone.h"
#include "collision/proxies.h"
#include "core/embree_api.h"
#include "core/embree_scene.h"

namespace plantarch::collision {

namespace {

void appendObject(const Context& ctx, ObjectID id, TriangleSoup& out) {
    const ObjectView v = ctx.object(id);
    for (std::uint32_t k : v.indices) out.push_back(v.positions[k]);
}

}  // namespace

struct World::Embree {
    RTCScene solid = nullptr;
    ~Embree() {
        if (solid) core::embree().rtcReleaseScene(solid);
    }
};

struct World::PlantSlot : PlantProxies {
    bool set = false;
};

World::World() : rtc_(std::make_unique<Embree>()) {
    rtc_->solid = core::triangleScene({}, RTC_BUILD_QUALITY_LOW);
    core::throwOnEmbreeError("creating the collision scene");
}

World::~World() = default;

void World::setSoft(std::optional<SoftCollisionOptions> options, const Context& ctx) {
    soft_ = std::move(options);
    memos.clear();  // the organ kinds may differ
    softPatterns_ = soft_ ? conePatterns(soft_->cone.rays, soft_->cone.halfAngle) : nullptr;
    buildStaticScenes(ctx);
}

void World::setSolid(std::optional<SolidObstacleOptions> options, const Context& ctx) {
    solid_ = std::move(options);
    buildStaticScenes(ctx);
}

void World::buildStaticScenes(const Context& ctx) {
    TriangleSoup solid;
    if (solid_)
        for (ObjectID id : solid_->obstacles) appendObject(ctx, id, solid);
    solidTriangles_.clear();
    for (std::size_t i = 0; i + 2 < solid.size(); i += 3)
        solidTriangles_.push_back({solid[i], solid[i + 1], solid[i + 2]});
    softStatic_ = solid;
    if (soft_)
        for (ObjectID id : soft_->objects) appendObject(ctx, id, softStatic_);

    boundingSpheres(softStatic_, softStaticSpheres_);
    core::embree().rtcReleaseScene(rtc_->solid);
    rtc_->solid = core::triangleScene(solid, RTC_BUILD_QUALITY_LOW);
    commit();
    core::throwOnEmbreeError("building the obstacle scenes");
}

void World::reservePlants(const std::vector<unsigned>& ids) {
    for (unsigned id : ids) {
        auto& slot = plants_[id];
        if (!slot) slot = std::make_unique<PlantSlot>();
        auto& memo = memos[id];
        if (!memo) memo = std::make_unique<PlantProxyMemo>();
    }
}

bool World::setPlantProxies(unsigned plantID, TriangleSoup&& triangles,
                            std::vector<OrganTag>&& tags) {
    PlantSlot& slot = *plants_.at(plantID);
    if (slot.set && slot.triangles.size() == triangles.size() && slot.tags == tags &&
        (triangles.empty() || std::memcmp(slot.triangles.data(), triangles.data(),
                                          triangles.size() * sizeof(vec3)) == 0)) {
        stats_.plantsUnchanged.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    slot.triangles = std::move(triangles);
    slot.tags = std::move(tags);
    index(slot);
    slot.set = true;
    stats_.plantsRebuilt.fetch_add(1, std::memory_order_relaxed);
    return true;
}

void World::index(PlantProxies& proxies) const {
    boundingSpheres(proxies.triangles, proxies.spheres, &proxies.tags);
    proxies.keyCell = gridCell();
    SoftGrid::cellKeys(proxies.spheres, proxies.keyCell, proxies.keys);
}

bool World::swapPlantProxies(unsigned plantID, PlantProxies& proxies, bool changed) {
    PlantSlot& slot = *plants_.at(plantID);
    if (slot.set && !changed) {
        stats_.plantsUnchanged.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    if (!changed) index(proxies);  // a plant new to the scene: proxies not indexed yet
    std::swap(static_cast<PlantProxies&>(slot), proxies);
    slot.set = true;
    stats_.plantsRebuilt.fetch_add(1, std::memory_order_relaxed);
    return true;
}

const PlantProxies* World::plantProxies(unsigned plantID) const {
    const auto it = plants_.find(plantID);
    return it == plants_.end() || !it->second->set ? nullptr : it->second.get();
}

void World::removePlant(unsigned plantID) {
    if (!plants_.count(plantID) && !memos.count(plantID)) return;  // nothing written
    memos.erase(plantID);
    stale.erase(plantID);
    if (plants_.erase(plantID)) commit();
}

// Cells one and a half times the look-ahead: a query visits a few cells a side. (Its reach
// adds the largest leaf's sphere to the look-ahead, so smaller cells mean many more visits;
// of 0.7, 1, 1.5, 2 and 3 look-aheads, the queries of the soft-avoidance benchmark canopy
// (bench/bench_collision.cpp) cost least with 1.5: 119 M instructions against 133 M with 1.)
float World::gridCell() const {
    return soft_ ? std::max(1.5f * soft_->cone.lookAhead, 0.005f) : 0.1f;
}

void World::commit(int threads) {
    const float cell = gridCell();
    SoftGrid::cellKeys(softStaticSpheres_, cell, softStaticKeys_);
    std::vector<SoftGrid::Source> sources;
    sources.push_back({&softStatic_, &softStaticSpheres_, &softStaticKeys_, nullptr, 0});
    for (auto& [id, slot] : plants_) {
        if (slot->keyCell != cell) {  // the look-ahead changed since they were binned
            slot->keyCell = cell;
            SoftGrid::cellKeys(slot->spheres, cell, slot->keys);
        }
        sources.push_back({&slot->triangles, &slot->spheres, &slot->keys, &slot->tags, id + 1});
    }
    grid_.build(sources, cell, threads);
}

std::uint64_t World::plantTriangles() const {
    std::uint64_t n = 0;
    for (const auto& [id, slot] : plants_) n += slot->triangles.size() / 3;
    return n;
}

std::shared_ptr<const ConePatterns> World::patterns(const PerceptionCone& cone) const {
    if (softPatterns_ && soft_->cone.rays == cone.rays && soft_->cone.halfAngle == cone.halfAngle)
        return softPatterns_;
    return conePatterns(cone.rays, cone.halfAngle);
}

// ---- queries ---------------------------------------------------------------------------

bool World::softOccluded(vec3 org, vec3 dir, float tnear, float tfar, const Ignore* ignore) const {
    // Moller-Trumbore against every triangle: slow and plain, the cones' reference.
    bool hit = false;
    grid_.forEach(ignore, [&](const vec3* p) {
        if (hit) return;
        const vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const vec3 h = glm::cross(dir, e2);
        const float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-20f) return;
        const float inv = 1.0f / det;
        const vec3 s = org - p[0];
        const float u = glm::dot(s, h) * inv;
        if (u < 0.0f || u > 1.0f) return;
        const vec3 q = glm::cross(s, e1);
        const float v = glm::dot(dir, q) * inv;
        if (v < 0.0f || u + v > 1.0f) return;
        const float t = glm::dot(e2, q) * inv;
        hit = t >= tnear && t <= tfar;
    });
    return hit;
}

std::optional<SolidHit> World::solidHit(vec3 org, vec3 dir, float tnear, float tfar) const {
    if (solidTriangles_.empty()) return std::nullopt;
    RTCIntersectContext ictx;
    rtcInitIntersectContext(&ictx);
    RTCRayHit rh = core::rayHit(org, dir, tnear, tfar);
    core::embree().rtcIntersect1(rtc_->solid, &ictx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    // The normal of the stored triangle (not Embree's, so equal for any BVH layout).
    const auto& t = solidTriangles_[rh.hit.primID];
    vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    const float len = glm::length(n);
    if (!(len > 0.0f)) return std::nullopt;
    n /= len;
    if (glm::dot(n, dir) > 0.0f) n = -n;
    return SolidHit{rh.ray.tfar, n, org + dir * rh.ray.tfar};
}

namespace {

struct NearQuery {
    std::vector<unsigned>* out;
};

bool collectNear(RTCPointQueryFunctionArguments* args) {
    static_cast<NearQuery*>(args->userPtr)->out->push_back(args->primID);
    return false;
}

// Closest point on triangle (a, b, c) to p (region tests on the barycentric plane).
vec3 closestOnTriangle(vec3 p, vec3 a, vec3 b, vec3 c) {
    const vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    const vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    const vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = 1.0f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

void World::softTrianglesNear(vec3 center, float radius, const Ignore* ignore, TriangleBatch& out,
                              const vec3* front) const {
    out.clear();
    grid_.near(center, radius, ignore, out, front);
}

void World::solidTrianglesNear(vec3 center, float radius, std::vector<unsigned>& out) const {
    out.clear();
    if (solidTriangles_.empty()) return;
    RTCPointQuery q{};
    q.x = center.x;
    q.y = center.y;
    q.z = center.z;
    q.radius = radius;
    q.time = 0.0f;
    RTCPointQueryContext pctx;
    rtcInitPointQueryContext(&pctx);
    NearQuery nq{&out};
    core::embree().rtcPointQuery(rtc_->solid, &q, &pctx, collectNear, &nq);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::optional<SolidHit> World::closestSolid(vec3 p, float radius) const {
    std::vector<unsigned> near;
    solidTrianglesNear(p, radius, near);
    std::optional<SolidHit> best;
    for (unsigned i : near) {  // ascending IDs: ties resolve the same way every time
        const auto& t = solidTriangles_[i];
        const vec3 q = closestOnTriangle(p, t[0], t[1], t[2]);
        const float d = glm::length(p - q);
        if (d > radius || (best && d >= best->distance)) continue;
        vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        const float len = glm::length(n);
        if (!(len > 0.0f)) continue;
        n /= len;
        if (glm::dot(n, p - q) < 0.0f) n = -n;
        best = SolidHit{d, n, q};
    }
    return best;
}

CollisionStats World::snapshotStats() const {
    CollisionStats s;
    auto get = [](const std::atomic<std::uint64_t>& a) {
        return a.load(std::memory_order_relaxed);
    };
    s.softCones = get(stats_.softCones);
    s.softRays = get(stats_.softRays);
    s.softSteered = get(stats_.softSteered);
    s.solidCones = get(stats_.solidCones);
    s.solidSteered = get(stats_.solidSteered);
    s.attractionQueries = get(stats_.attractionQueries);
    s.attracted = get(stats_.attracted);
    s.organsTurned = get(stats_.organsTurned);
    s.organsUnresolved = get(stats_.organsUnresolved);
    s.sceneRefreshes = get(stats_.sceneRefreshes);
    s.plantsRebuilt = get(stats_.plantsRebuilt);
    s.plantsUnchanged = get(stats_.plantsUnchanged);
    s.sceneTriangles = plantTriangles();
    s.refreshSeconds = stats_.refreshSeconds.load(std::memory_order_relaxed);
    s.coneSeconds = double(stats_.coneNanoseconds.load(std::memory_order_relaxed)) * 1e-9;
    return s;
}

void World::resetStats() {
    for (auto* a : {&stats_.softCones, &stats_.softRays, &stats_.softSteered, &stats_.solidCones,
                    &stats_.solidSteered, &stats_.attractionQueries, &stats_.attracted,
                    &stats_.organsTurned, &stats_.organsUnresolved, &stats_.sceneRefreshes,
                    &stats_.plantsRebuilt, &stats_.plantsUnchanged})
        a->store(0, std::memory_order_relaxed);
    stats_.refreshSeconds.store(0.0, std::memory_order_relaxed);
    stats_.coneNanoseconds.store(0, std::memory_order_relaxed);
}

}  // namespace plantarch::collision
