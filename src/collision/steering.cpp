// The three steering rules (see Collision.h and docs/collision.md); the soft cones' sampling is
// in cone.cpp.
//
// Every cone draws from a random stream keyed by (seed, plant, shoot, node, organ): the
// plant's own numbers, drawn the same way whatever the thread, the step size or the other
// plants, and without shifting the plant's growth stream.

#include "collision/steering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "collision/attraction.h"
#include "collision/collision_world.h"
#include "collision/cone.h"
#include "core/math.h"

namespace plantarch::collision {

namespace {

enum ConeKind : unsigned {
    kConeInternode = 1,
    kConePetiole = 2,
    kConePeduncle = 3,
    kConeSolid = 4
};

std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

Rng coneRng(std::uint64_t seed, unsigned plant, unsigned shoot, unsigned node, ConeKind kind,
            unsigned index) {
    std::uint64_t h = splitmix(seed ^ 0x636f6c6c6973696fULL);  // "collisio"
    for (std::uint64_t v : {std::uint64_t(plant), std::uint64_t(shoot), std::uint64_t(node),
                            std::uint64_t(kind), std::uint64_t(index)})
        h = splitmix(h ^ v);
    return Rng(h, kind);
}

vec3 blend(vec3 current, vec3 target, float inertia) {
    const vec3 v = inertia * current + (1.0f - inertia) * target;
    const float len = glm::length(v);
    return len > 1e-6f ? v / len : current;
}

// The cone's rays: `rings` bands of equal solid angle from the axis out to the half-angle,
// each split into `sectors` equal sectors; one jittered ray per cell.
struct ConeGrid {
    int rings = 1, sectors = 3;
    explicit ConeGrid(unsigned rays) {
        rings = std::max(1, int(std::lround(std::sqrt(double(rays) / 4.0))));
        sectors = std::max(3, int(rays) / rings);
    }
    int size() const { return rings * sectors; }
};

struct ConeRays {
    std::vector<vec3> dirs;
    void make(const ConeGrid& g, vec3 axis, float halfAngle, Rng& rng) {
        const vec3 e1 = anyPerpendicular(axis);
        const vec3 e2 = glm::cross(axis, e1);
        const float oneMinusCos = 1.0f - std::cos(halfAngle * kDeg);
        dirs.resize(std::size_t(g.size()));
        for (int i = 0; i < g.rings; ++i)
            for (int j = 0; j < g.sectors; ++j) {
                const float u = (float(i) + rng.uniform01()) / float(g.rings);
                const float phi = 2.0f * kPi * (float(j) + rng.uniform01()) / float(g.sectors);
                const float cosT = 1.0f - u * oneMinusCos;
                const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
                dirs[std::size_t(i * g.sectors + j)] =
                    glm::normalize(cosT * axis + sinT * (std::cos(phi) * e1 + std::sin(phi) * e2));
            }
    }
};

}  // namespace

namespace {

// Soft avoidance: the centre of the largest open gap in the cone, favouring gaps near the
// axis; nothing when the cone is all open (growth unchanged) or all blocked.
std::optional<vec3> softTarget(const World& world, vec3 apex, vec3 axis, const PerceptionCone& cone,
                               Rng& rng, float tnear, const Ignore& ignore) {
    thread_local ConeSample sample;
    AtomicStats& st = world.stats();
    const auto started = std::chrono::steady_clock::now();
    struct Timer {
        AtomicStats& st;
        std::chrono::steady_clock::time_point started;
        ~Timer() {
            st.coneNanoseconds.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                             std::chrono::steady_clock::now() - started)
                                             .count(),
                                         std::memory_order_relaxed);
        }
    } timer{st, started};
    sampleCone(world, apex, axis, cone, rng, tnear, ignore, sample);
    st.softCones.fetch_add(1, std::memory_order_relaxed);
    const std::optional<vec3> gap = bestGap(sample, cone.halfAngle);
    if (gap) st.softSteered.fetch_add(1, std::memory_order_relaxed);
    return gap;
}

// The nearest solid obstacle in a cone (the axis ray included).
std::optional<SolidHit> nearestSolid(const World& world, vec3 apex, vec3 axis,
                                     const SolidObstacleOptions& o, Rng& rng) {
    const ConeGrid grid(o.rays);
    thread_local ConeRays rays;
    rays.make(grid, axis, o.coneHalfAngle, rng);
    rays.dirs.push_back(axis);
    std::optional<SolidHit> best;
    for (const vec3& d : rays.dirs) {
        const float reach = best ? best->distance : o.avoidanceDistance;
        if (auto h = world.solidHit(apex, d, 1e-5f, reach))
            if (!best || h->distance < best->distance) best = h;
    }
    world.stats().solidCones.fetch_add(1, std::memory_order_relaxed);
    return best;
}

// The component of `v` along the surface with normal `n`; `fallback` when v is (nearly) normal.
vec3 tangential(vec3 v, vec3 n, vec3 fallback) {
    vec3 t = v - glm::dot(v, n) * n;
    if (glm::length(t) < 1e-3f) t = fallback - glm::dot(fallback, n) * n;
    if (glm::length(t) < 1e-6f) t = anyPerpendicular(n);
    return glm::normalize(t);
}

// Solid obstacles: growth heading toward the nearest obstacle turns toward its tangent plane,
// the more the closer; within a quarter of the avoidance distance it follows the tangent.
vec3 solidSteer(const World& world, vec3 apex, vec3 g, vec3 fallback, Rng& rng) {
    const SolidObstacleOptions& o = *world.solid();
    const auto hit = nearestSolid(world, apex, g, o, rng);
    if (!hit || glm::dot(g, hit->normal) >= 0.0f) return g;
    const vec3 t = tangential(g, hit->normal, fallback);
    const float nearest = 0.25f * o.avoidanceDistance;
    const float w = std::clamp(
        (o.avoidanceDistance - hit->distance) / (o.avoidanceDistance - nearest), 0.0f, 1.0f);
    world.stats().solidSteered.fetch_add(1, std::memory_order_relaxed);
    if (w >= 1.0f) return t;
    const vec3 v = glm::mix(g, t, w);
    return glm::length(v) > 1e-6f ? glm::normalize(v) : t;
}

// Pitch from the internode axis and azimuth about the shoot axis of a side organ whose
// direction should be `d` (the inverse of the tessellator's placement).
void toPitchAzimuth(const Internode& in, vec3 d, float& pitch, float& azimuth) {
    const float c = std::clamp(glm::dot(d, in.direction), -1.0f, 1.0f);
    pitch = std::acos(c) / kDeg;
    vec3 s = d - c * in.direction;
    s -= glm::dot(s, in.guide) * in.guide;
    if (glm::length(s) < 1e-6f) return;
    azimuth = std::atan2(glm::dot(s, glm::cross(in.guide, in.rollReference)),
                         glm::dot(s, in.rollReference)) /
              kDeg;
}

// Direction of a side organ at `pitch` from the internode axis and `azimuth` about the
// shoot axis, and the side it leans to (as the tessellator places petioles and peduncles).
vec3 sideDirection(const Internode& in, float pitch, float azimuth, vec3* sideOut = nullptr) {
    vec3 side = azimuthDirection(in.guide, in.rollReference, azimuth);
    side = glm::normalize(side - glm::dot(side, in.direction) * in.direction);
    if (sideOut) *sideOut = side;
    const float p = pitch * kDeg;
    return glm::normalize(std::cos(p) * in.direction + std::sin(p) * side);
}

bool softSteers(const World* world) {
    return world && world->soft();
}

// A growing tip does not see the young organs it grows out of: those of the node it starts
// from (and of the node its shoot grows from).
Ignore ownNode(const PlantInstance& plant, const Shoot& shoot, int node, bool parentNode) {
    Ignore ig;
    ig.plant = plant.id;
    if (node >= 0) ig.organs[0] = organTag(shoot.id, unsigned(node));
    if (parentNode && shoot.parent >= 0 && shoot.parentNode >= 0)
        ig.organs[1] = organTag(unsigned(shoot.parent), unsigned(shoot.parentNode));
    return ig;
}

}  // namespace

vec3 nodePosition(const PlantInstance& plant, unsigned shootID, std::size_t internodes, double now,
                  bool mature) {
    const Shoot& s = plant.shoots[shootID];
    vec3 p = plant.base;
    if (s.parent >= 0) {
        const Shoot& parent = plant.shoots[unsigned(s.parent)];
        p = nodePosition(plant, unsigned(s.parent),
                         std::min(std::size_t(s.parentNode) + 1, parent.phytomers.size()), now,
                         mature);
    }
    const std::size_t n = std::min(internodes, s.phytomers.size());
    for (std::size_t i = 0; i < n; ++i) {
        const Phytomer& ph = s.phytomers[i];
        const float f =
            mature ? 1.0f
                   : float(std::min(1.0, ph.internodeFraction0 +
                                             s.elongationRate * std::max(0.0, now - ph.birth)));
        p += ph.internode.direction * ph.internode.length * f;
    }
    return p;
}

void SceneSteering::steerShootAxis(const PlantInstance& plant, const Shoot& shoot, Internode& in,
                                   float lengthMax) {
    const unsigned node = unsigned(shoot.phytomers.size());
    vec3 g = in.guide;
    bool attracted = false;
    if (attraction && attraction->attracts(shoot.type)) {
        const vec3 apex = nodePosition(plant, shoot.id, node, plant.age, true);
        const AttractionPoints& o = attraction->options();
        if (world) world->stats().attractionQueries.fetch_add(1, std::memory_order_relaxed);
        // Points nearer than half an internode are passed by anyway (and have no direction);
        // a wire within one internode is followed (attraction.h).
        const TipQuery tip{apex, g, nodePosition(plant, shoot.id, 0, plant.age, true),
                           std::max(1e-4f, 0.5f * lengthMax), lengthMax};
        if (auto p = attraction->target(tip)) {
            g = blend(g, glm::normalize(*p - apex), o.inertia);
            attracted = true;
            // A shoot held on its wire loses the bend its random walk was carrying.
            in.walkZenith = 0.0f;
            in.walkYaw = 0.0f;
            if (world) world->stats().attracted.fetch_add(1, std::memory_order_relaxed);
        }
    }
    if (!attracted && softSteers(world) && world->soft()->steerInternodes) {
        const SoftCollisionOptions& o = *world->soft();
        const vec3 apex = nodePosition(plant, shoot.id, node, plant.age, false);
        Rng rng = coneRng(seed, plant.id, shoot.id, node, kConeInternode, 0);
        const Ignore ignore = ownNode(plant, shoot, int(node) - 1, true);
        if (auto t = softTarget(*world, apex, g, o.cone, rng, 2.0f * in.radius + 1e-4f, ignore))
            g = blend(g, *t, o.cone.inertia);
    }
    if (world && world->hasSolid()) {
        const vec3 apex = nodePosition(plant, shoot.id, node, plant.age, true);
        Rng rng = coneRng(seed, plant.id, shoot.id, node, kConeSolid, 0);
        g = solidSteer(*world, apex, g, in.rollReference, rng);
    }
    if (g == in.guide) return;
    in.guide = g;
    // Carry the roll reference along with the smallest rotation (no twist).
    vec3 ref = in.rollReference - glm::dot(in.rollReference, g) * g;
    in.rollReference = glm::length(ref) > 1e-6f ? glm::normalize(ref) : anyPerpendicular(g);
}

void SceneSteering::keepInternodeClear(const PlantInstance& plant, const Shoot& shoot,
                                       Internode& in) {
    if (!world || !world->hasSolid()) return;
    const vec3 apex = nodePosition(plant, shoot.id, shoot.phytomers.size(), plant.age, true);
    // The mature internode and its radius, with a millimetre to spare.
    const float reach = in.length + 2.0f * in.radius + 1e-3f;
    for (int attempt = 0; attempt < 4; ++attempt) {
        const auto hit = world->solidHit(apex, in.direction, 1e-5f, reach);
        if (!hit) return;
        in.direction = tangential(in.direction, hit->normal, in.rollReference);
        if (attempt == 3) in.direction = hit->normal;  // cornered: grow away
    }
}

void SceneSteering::steerPetiole(const PlantInstance& plant, const Shoot& shoot,
                                 const Internode& in, float internodeFraction,
                                 unsigned petioleIndex, Petiole& pt) {
    if (!softSteers(world) || !world->soft()->steerPetioles) return;
    const SoftCollisionOptions& o = *world->soft();
    const unsigned node = unsigned(shoot.phytomers.size());
    vec3 side;
    const vec3 dir = sideDirection(in, std::abs(pt.pitch), pt.azimuth, &side);
    const vec3 top = nodePosition(plant, shoot.id, node, plant.age, false) +
                     in.direction * in.length * internodeFraction;
    const vec3 start = top + side * in.radius * 0.5f;
    Rng rng = coneRng(seed, plant.id, shoot.id, node, kConePetiole, petioleIndex);
    // The new phytomer is not in the scene yet; the leaf of the node below is (it is the one a
    // new leaf most often grows into), so it is seen.
    Ignore ignore = ownNode(plant, shoot, int(node), false);
    if (auto t = softTarget(*world, start, dir, o.cone, rng, 2.0f * pt.radius + 1e-4f, ignore))
        toPitchAzimuth(in, blend(dir, *t, o.cone.inertia), pt.pitch, pt.azimuth);
}

void SceneSteering::steerPeduncle(const PlantInstance& plant, const Shoot& shoot, unsigned node,
                                  unsigned petiole, unsigned bud, bool terminal, FloralBud& fb) {
    if (!softSteers(world) || !world->soft()->steerPeduncles || shoot.phytomers.empty()) return;
    const SoftCollisionOptions& o = *world->soft();
    const unsigned k = terminal ? unsigned(shoot.phytomers.size() - 1) : node;
    const Internode& in = shoot.phytomers[k].internode;
    const float base =
        terminal ? in.azimuth + fb.terminalAzimuth : shoot.phytomers[k].petioles[petiole].azimuth;
    const vec3 dir = sideDirection(in, fb.pedunclePitch, base + fb.peduncleAzimuth);
    const vec3 top = nodePosition(plant, shoot.id, k + 1, plant.age, false);
    Rng rng = coneRng(seed, plant.id, shoot.id, k, kConePeduncle,
                      (terminal ? 0x10000u : 0u) + petiole * 256u + bud);
    // A peduncle stands in its petiole's axil, and what its flowers cross is most often that
    // petiole's own leaf: nothing of the node is ignored, and the cone starts just clear of the
    // stem instead.
    Ignore ignore;
    ignore.plant = plant.id;
    const vec3 start = top + dir * (2.0f * in.radius);
    if (auto t =
            softTarget(*world, start, dir, o.cone, rng, 2.0f * fb.peduncleRadius + 1e-4f, ignore)) {
        float azimuth = base + fb.peduncleAzimuth;
        toPitchAzimuth(in, blend(dir, *t, o.cone.inertia), fb.pedunclePitch, azimuth);
        fb.peduncleAzimuth = azimuth - base;
    }
}

}  // namespace plantarch::collision
