// The collision scene on Embree (see collision_world.h).

#include "collision/collision_world.h"

#include "collision/proxies.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace plantarch::collision {

namespace {

void check(RTCDevice device, const char* what) {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree error ") + std::to_string(int(err)) +
                                 " while " + what);
}

// A triangle geometry holding `soup` (three corners per triangle), committed.
RTCGeometry triangleGeometry(RTCDevice device, const TriangleSoup& soup) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_LOW);
    const std::size_t n = soup.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n / 3));
    for (std::size_t i = 0; i < n; ++i) {
        v[3 * i + 0] = soup[i].x;
        v[3 * i + 1] = soup[i].y;
        v[3 * i + 2] = soup[i].z;
        idx[i] = unsigned(i);
    }
    rtcCommitGeometry(g);
    return g;
}

// A committed scene of one triangle geometry (an empty scene when the soup is empty).
RTCScene sceneOf(RTCDevice device, const TriangleSoup& soup) {
    RTCScene s = rtcNewScene(device);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_LOW);
    if (!soup.empty()) {
        RTCGeometry g = triangleGeometry(device, soup);
        rtcAttachGeometryByID(s, g, 0);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s);
    return s;
}

RTCGeometry instanceOf(RTCDevice device, RTCScene scene) {
    RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, scene);
    const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
    rtcCommitGeometry(inst);
    return inst;
}

// The context of a soft query: Embree's, then what the query must not see.
struct QueryContext {
    RTCIntersectContext rtc;
    const Ignore* ignore;
};

// Drops hits on the ignored organs of the querying plant (plant geometries only).
void ignoreFilter(const RTCFilterFunctionNArguments* args) {
    const auto* q = reinterpret_cast<const QueryContext*>(args->context);
    if (!q->ignore) return;
    const auto* tags = static_cast<const std::vector<OrganTag>*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (RTCHitN_instID(args->hit, args->N, i, 0) != q->ignore->plant + 1) continue;
        const OrganTag tag = (*tags)[RTCHitN_primID(args->hit, args->N, i)];
        if (tag == q->ignore->organs[0] || tag == q->ignore->organs[1]) args->valid[i] = 0;
    }
}

void appendObject(const Context& ctx, ObjectID id, TriangleSoup& out) {
    const ObjectView v = ctx.object(id);
    for (std::uint32_t k : v.indices) out.push_back(v.positions[k]);
}

}  // namespace

struct World::Embree {
    RTCDevice device = nullptr;
    RTCScene solid = nullptr;
    RTCScene statics = nullptr;
    RTCScene top = nullptr;
    RTCGeometry staticInstance = nullptr;
    ~Embree() {
        if (staticInstance) rtcReleaseGeometry(staticInstance);
        if (top) rtcReleaseScene(top);
        if (statics) rtcReleaseScene(statics);
        if (solid) rtcReleaseScene(solid);
        if (device) rtcReleaseDevice(device);
    }
};

struct World::PlantSlot {
    unsigned id = 0;
    RTCScene scene = nullptr;
    RTCGeometry instance = nullptr;
    TriangleSoup triangles;
    std::vector<OrganTag> tags;  ///< per triangle
    bool attached = false;
    ~PlantSlot() {
        if (instance) rtcReleaseGeometry(instance);
        if (scene) rtcReleaseScene(scene);
    }
};

World::World() : rtc_(std::make_unique<Embree>()) {
    rtc_->device = rtcNewDevice(nullptr);
    if (!rtc_->device) throw std::runtime_error("cannot create an Embree device");
    rtc_->top = rtcNewScene(rtc_->device);
    rtcSetSceneFlags(rtc_->top, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(rtc_->top, RTC_BUILD_QUALITY_LOW);
    rtcCommitScene(rtc_->top);
    solidTriangles_.clear();
    TriangleSoup none;
    rtc_->solid = sceneOf(rtc_->device, none);
    rtc_->statics = sceneOf(rtc_->device, none);
    check(rtc_->device, "creating the collision scene");
}

// Plant slots release their Embree handles before the device goes.
World::~World() { plants_.clear(); }


void World::setSoft(std::optional<SoftCollisionOptions> options, const Context& ctx) {
    soft_ = std::move(options);
    memos.clear();  // the organ kinds may differ
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

    rtcReleaseScene(rtc_->solid);
    rtc_->solid = sceneOf(rtc_->device, solid);
    rtcReleaseScene(rtc_->statics);
    rtc_->statics = sceneOf(rtc_->device, softStatic_);
    if (rtc_->staticInstance) {
        rtcDetachGeometry(rtc_->top, 0);
        rtcReleaseGeometry(rtc_->staticInstance);
        rtc_->staticInstance = nullptr;
    }
    if (!softStatic_.empty()) {
        rtc_->staticInstance = instanceOf(rtc_->device, rtc_->statics);
        rtcAttachGeometryByID(rtc_->top, rtc_->staticInstance, 0);
    }
    if (instances_.empty()) instances_.resize(1);
    instances_[0] = {&softStatic_, nullptr, 0};
    rtcCommitScene(rtc_->top);
    check(rtc_->device, "building the obstacle scenes");
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
    if (slot.scene && slot.triangles.size() == triangles.size() && slot.tags == tags &&
        (triangles.empty() ||
         std::memcmp(slot.triangles.data(), triangles.data(), triangles.size() * sizeof(vec3)) == 0)) {
        stats_.plantsUnchanged.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    slot.triangles = std::move(triangles);
    slot.tags = std::move(tags);
    if (slot.scene) rtcReleaseScene(slot.scene);
    slot.scene = rtcNewScene(rtc_->device);
    rtcSetSceneBuildQuality(slot.scene, RTC_BUILD_QUALITY_LOW);
    if (!slot.triangles.empty()) {
        RTCGeometry g = triangleGeometry(rtc_->device, slot.triangles);
        rtcSetGeometryUserData(g, &slot.tags);
        rtcSetGeometryOccludedFilterFunction(g, ignoreFilter);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(slot.scene, g, 0);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(slot.scene);
    if (!slot.instance) slot.instance = rtcNewGeometry(rtc_->device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(slot.instance, slot.scene);
    const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    rtcSetGeometryTransform(slot.instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
    rtcCommitGeometry(slot.instance);
    stats_.plantsRebuilt.fetch_add(1, std::memory_order_relaxed);
    return true;
}

void World::removePlant(unsigned plantID) {
    if (!plants_.count(plantID) && !memos.count(plantID)) return;  // nothing written
    memos.erase(plantID);
    stale.erase(plantID);
    auto it = plants_.find(plantID);
    if (it == plants_.end()) return;
    if (it->second->attached) rtcDetachGeometry(rtc_->top, plantID + 1);
    plants_.erase(it);
    rtcCommitScene(rtc_->top);
}

void World::commit() {
    instances_.assign(plants_.empty() ? 1 : plants_.rbegin()->first + 2, InstanceView{});
    instances_[0] = {&softStatic_, nullptr, 0};
    for (auto& [id, slot] : plants_) {
        const bool want = slot->instance && !slot->triangles.empty();
        if (want && !slot->attached) rtcAttachGeometryByID(rtc_->top, slot->instance, id + 1);
        if (!want && slot->attached) rtcDetachGeometry(rtc_->top, id + 1);
        slot->attached = want;
        instances_[id + 1] = {&slot->triangles, &slot->tags, id};
    }
    rtcCommitScene(rtc_->top);
    check(rtc_->device, "refreshing the collision scene");
}

std::uint64_t World::plantTriangles() const {
    std::uint64_t n = 0;
    for (const auto& [id, slot] : plants_) n += slot->triangles.size() / 3;
    return n;
}

// ---- queries ---------------------------------------------------------------------------

bool World::softOccluded(vec3 org, vec3 dir, float tnear, float tfar, const Ignore* ignore) const {
    QueryContext q;
    rtcInitIntersectContext(&q.rtc);
    q.ignore = ignore;
    RTCRay ray{};
    ray.org_x = org.x;
    ray.org_y = org.y;
    ray.org_z = org.z;
    ray.dir_x = dir.x;
    ray.dir_y = dir.y;
    ray.dir_z = dir.z;
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    rtcOccluded1(rtc_->top, &q.rtc, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

std::optional<SolidHit> World::solidHit(vec3 org, vec3 dir, float tnear, float tfar) const {
    if (solidTriangles_.empty()) return std::nullopt;
    RTCIntersectContext ictx;
    rtcInitIntersectContext(&ictx);
    RTCRayHit rh{};
    rh.ray.org_x = org.x;
    rh.ray.org_y = org.y;
    rh.ray.org_z = org.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_->solid, &ictx, &rh);
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

namespace {

struct SoftNearQuery {
    const std::vector<World::InstanceView>* instances;
    const Ignore* ignore;
    std::vector<const vec3*>* out;
};

bool collectSoftNear(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<SoftNearQuery*>(args->userPtr);
    const unsigned inst = args->context->instID[0];
    if (inst >= q->instances->size()) return false;
    const World::InstanceView& v = (*q->instances)[inst];
    if (!v.triangles) return false;
    if (q->ignore && v.tags && v.plant == q->ignore->plant) {
        const OrganTag tag = (*v.tags)[args->primID];
        if (tag == q->ignore->organs[0] || tag == q->ignore->organs[1]) return false;
    }
    q->out->push_back(v.triangles->data() + 3 * std::size_t(args->primID));
    return false;
}

}  // namespace

void World::softTrianglesNear(vec3 center, float radius, const Ignore* ignore,
                              std::vector<const vec3*>& out) const {
    out.clear();
    RTCPointQuery q{};
    q.x = center.x;
    q.y = center.y;
    q.z = center.z;
    q.radius = radius;
    q.time = 0.0f;
    RTCPointQueryContext pctx;
    rtcInitPointQueryContext(&pctx);
    SoftNearQuery sq{&instances_, ignore, &out};
    rtcPointQuery(rtc_->top, &q, &pctx, collectSoftNear, &sq);
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
    rtcPointQuery(rtc_->solid, &q, &pctx, collectNear, &nq);
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
    auto get = [](const std::atomic<std::uint64_t>& a) { return a.load(std::memory_order_relaxed); };
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
