// Perception cones (see cone.h).
//
// Sampling works in the cone's frame. Each triangle within reach is moved into it, the rings
// and sectors its directions can cover are found from a cap around its corners, and the rays
// of those cells are tested against the triangle's three edge planes through the apex (a ray
// hits the triangle's plane inside it when it lies on the inner side of all three), several
// rays at a time. A cell once blocked stays blocked, so the order of the triangles does not
// matter.

#include "collision/cone.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>

#include "collision/collision_world.h"
#include "geometry/tube.h"

namespace plantarch::collision {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kDeg = kPi / 180.0f;

// Rings and sectors of a cone of `rays` rays: about four sectors per ring per ring.
void gridOf(unsigned rays, int& rings, int& sectors) {
    rings = std::max(1, int(std::lround(std::sqrt(double(rays) / 4.0))));
    sectors = std::max(3, int(rays) / rings);
}

// atan2 within 1e-5 rad (a polynomial on [0, 1] and the octant symmetries); the sector ranges
// it feeds have a margin of 1e-3 rad.
float fastAtan2(float y, float x) {
    const float ax = std::abs(x), ay = std::abs(y);
    const float mx = std::max(ax, ay);
    if (mx == 0.0f) return 0.0f;
    const float a = std::min(ax, ay) / mx;
    const float s = a * a;
    float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
    if (ay > ax) r = 1.57079637f - r;
    if (x < 0.0f) r = 3.14159274f - r;
    return y < 0.0f ? -r : r;
}

struct Reach {
    float tnear, lookAhead;
};

// Four rays at a time (GCC/Clang vector extensions: SSE on x86-64, NEON on ARM).
typedef float Float4 __attribute__((vector_size(16)));
typedef std::int32_t Int4 __attribute__((vector_size(16)));

Float4 load4(const float* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

Float4 splat(float v) { return Float4{v, v, v, v}; }

// A triangle's edge planes through the apex (facing inward) and its plane, broadcast.
struct Planes {
    Float4 ax, ay, az, bx, by, bz, cx, cy, cz, nx, ny, nz, dist;
};

// Marks the cells [first, last] (and up to three past it: the arrays are padded, and every
// cell is tested exactly, so extra cells are only extra work) whose rays pass inside the edge
// planes and, with kReach, hit the plane (t = dist / dot(ray, normal)) within reach.
template <bool kReach>
void markInside(const ConeSample& cone, std::uint32_t* blocked, int first, int last,
                const Planes& p, Float4 tnear, Float4 tfar) {
    const Float4 zero = splat(0.0f);
    for (int k = first & ~3; k <= last; k += 4) {
        const Float4 x = load4(cone.x + k), y = load4(cone.y + k), z = load4(cone.z + k);
        Int4 in = (x * p.ax + y * p.ay + z * p.az >= zero) & (x * p.bx + y * p.by + z * p.bz >= zero) &
                  (x * p.cx + y * p.cy + z * p.cz >= zero);
        if constexpr (kReach) {
            const Float4 t = p.dist / (x * p.nx + y * p.ny + z * p.nz);
            in &= (t >= tnear) & (t <= tfar);
        }
        Int4 b;
        std::memcpy(&b, blocked + k, sizeof b);
        b |= in & 1;
        std::memcpy(blocked + k, &b, sizeof b);
    }
}

struct Frame {
    vec3 apex, e1, e2, axis;
    float cosHalf, sinHalf;
    Reach reach;
};

// Marks the cells whose rays hit triangle (p0, p1, p2) within reach.
void rasterize(ConeSample& cone, const vec3* tri, const Frame& f) {
    auto local = [&](vec3 p) {
        p -= f.apex;
        return vec3(glm::dot(p, f.e1), glm::dot(p, f.e2), glm::dot(p, f.axis));
    };
    const vec3 q0 = local(tri[0]), q1 = local(tri[1]), q2 = local(tri[2]);
    // Wholly behind the apex, for a cone no wider than a hemisphere.
    if (f.cosHalf >= 0.0f && q0.z <= 0.0f && q1.z <= 0.0f && q2.z <= 0.0f) return;
    const float l0 = glm::length(q0), l1 = glm::length(q1), l2 = glm::length(q2);
    if (!(l0 > 0.0f && l1 > 0.0f && l2 > 0.0f)) return;
    // Beyond reach: the bounding sphere about the centroid lies past the look-ahead.
    const vec3 centre = (q0 + q1 + q2) * (1.0f / 3.0f);
    const float radius = std::sqrt(std::max({glm::dot(q0 - centre, q0 - centre),
                                             glm::dot(q1 - centre, q1 - centre),
                                             glm::dot(q2 - centre, q2 - centre)}));
    const float dist = glm::length(centre);
    if (dist - radius > f.reach.lookAhead) return;
    // The directions to the corners lie in a cap; so do all directions that hit the triangle.
    const int rings = cone.rings, sectors = cone.sectors;
    int ringLo = 0, ringHi = rings - 1, sectorLo = 0, sectorHi = sectors - 1;
    const vec3 d0 = q0 / l0, d1 = q1 / l1, d2 = q2 / l2;
    const vec3 sum = d0 + d1 + d2;
    const float sumLen = glm::length(sum);
    const vec3 d = sumLen > 1e-6f ? sum / sumLen : vec3(0.0f);
    const float cb = sumLen > 1e-6f
                         ? std::min({glm::dot(d, d0), glm::dot(d, d1), glm::dot(d, d2)}) - 1e-4f
                         : -1.0f;
    if (cb > 0.0f) {  // a cap narrower than a hemisphere
        const float sb = std::sqrt(std::max(0.0f, 1.0f - cb * cb));
        const float c = std::clamp(d.z, -1.0f, 1.0f);
        const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
        // Outside the cone: the cap's centre is farther from the axis than half-angle + radius
        // (a sum below 180 degrees when the half-angle is at most 90 or the cap is narrow).
        const bool sumBelowPi = f.cosHalf >= 0.0f || sb < f.sinHalf;
        if (sumBelowPi && c < f.cosHalf * cb - f.sinHalf * sb - 1e-5f) return;
        const bool pastEdge =
            (f.cosHalf >= 0.0f && sb >= f.sinHalf) || c < f.cosHalf * cb + f.sinHalf * sb + 1e-5f;
        const float oneMinusCos = 1.0f - f.cosHalf;
        auto ringOf = [&](float cosTheta) {
            const float u = (1.0f - cosTheta) / oneMinusCos;
            return std::clamp(int(u * float(rings)), 0, rings - 1);
        };
        ringHi = pastEdge ? rings - 1 : ringOf(c * cb - s * sb + 1e-5f);
        if (c < cb) ringLo = ringOf(c * cb + s * sb - 1e-5f);  // the cap misses the axis
        // Wholly in front of the apex, the triangle is farthest from the axis at a corner
        // (along a great-circle arc in the front half-space the height z is a positive arc
        // of a cosine, least at an end).
        if (q0.z > 0.0f && q1.z > 0.0f && q2.z > 0.0f) {
            const float leastCos = std::min({q0.z / l0, q1.z / l1, q2.z / l2});
            if (leastCos > f.cosHalf) ringHi = std::min(ringHi, ringOf(leastCos - 1e-5f));
        }
    }
    // Sectors: when the triangle's shadow on the cone's base plane (x, y) misses the origin
    // (the triangle crosses neither the axis nor its extension backward), the azimuths it
    // covers are those between its corners' (an edge's azimuth runs monotonically: it lies
    // on a great circle, whose shadow is an ellipse about the origin).
    const float c01 = q0.x * q1.y - q0.y * q1.x, c12 = q1.x * q2.y - q1.y * q2.x,
                c20 = q2.x * q0.y - q2.y * q0.x;
    const float maxL = std::max({l0, l1, l2});
    const float eps = 1e-5f * maxL * maxL;  // shadows that nearly touch the origin count
    const bool aroundAxis = (c01 >= -eps && c12 >= -eps && c20 >= -eps) ||
                            (c01 <= eps && c12 <= eps && c20 <= eps);
    if (!aroundAxis) {
        const float p0 = fastAtan2(q0.y, q0.x);
        float p1 = fastAtan2(q1.y, q1.x) - p0, p2 = fastAtan2(q2.y, q2.x) - p0;
        // Relative to corner 0, each within half a turn (the span is under half a turn).
        p1 -= p1 > kPi ? 2.0f * kPi : (p1 < -kPi ? -2.0f * kPi : 0.0f);
        p2 -= p2 > kPi ? 2.0f * kPi : (p2 < -kPi ? -2.0f * kPi : 0.0f);
        float lo = p0 + std::min({0.0f, p1, p2}) - 1e-3f;
        float hi = p0 + std::max({0.0f, p1, p2}) + 1e-3f;
        if (lo < 0.0f) {
            lo += 2.0f * kPi;
            hi += 2.0f * kPi;
        }
        const float perSector = float(sectors) / (2.0f * kPi);
        sectorLo = int(std::floor(lo * perSector));
        sectorHi = int(std::floor(hi * perSector));
        if (sectorHi - sectorLo + 1 >= sectors) {
            sectorLo = 0;
            sectorHi = sectors - 1;
        }
    }
    // Edge planes through the apex, facing inward.
    vec3 n0 = glm::cross(q0, q1), n1 = glm::cross(q1, q2), n2 = glm::cross(q2, q0);
    const float volume = glm::dot(q0, n1);
    if (std::abs(volume) < 1e-18f) return;  // seen edge-on
    if (volume < 0.0f) {
        n0 = -n0;
        n1 = -n1;
        n2 = -n2;
    }
    const vec3 normal = glm::cross(q1 - q0, q2 - q0);
    const float planeDist = glm::dot(q0, normal);
    const bool checkReach = maxL > f.reach.lookAhead || dist - radius <= f.reach.tnear;
    // The sector range as at most two runs inside [0, sectors).
    int runs[2][2] = {{sectorLo, sectorHi}, {0, -1}};
    if (sectorLo < 0) {
        runs[0][0] = sectorLo + sectors;
        runs[0][1] = sectors - 1;
        runs[1][1] = sectorHi;
    } else if (sectorHi >= sectors) {
        runs[0][1] = sectors - 1;
        runs[1][1] = sectorHi - sectors;
    }
    std::uint32_t* blocked = cone.blocked.data();
    const Planes p{splat(n0.x),     splat(n0.y),     splat(n0.z),     splat(n1.x), splat(n1.y),
                   splat(n1.z),     splat(n2.x),     splat(n2.y),     splat(n2.z), splat(normal.x),
                   splat(normal.y), splat(normal.z), splat(planeDist)};
    const Float4 tnear = splat(f.reach.tnear), tfar = splat(f.reach.lookAhead);
    for (int i = ringLo; i <= ringHi; ++i)
        for (const auto& run : runs) {
            if (run[1] < run[0]) continue;
            const int first = i * sectors + run[0], last = i * sectors + run[1];
            if (checkReach)
                markInside<true>(cone, blocked, first, last, p, tnear, tfar);
            else
                markInside<false>(cone, blocked, first, last, p, tnear, tfar);
        }
}

}  // namespace

ConePatterns::ConePatterns(unsigned rays, float halfAngleDegrees) : halfAngle(halfAngleDegrees) {
    gridOf(rays, rings, sectors);
    cosHalf = std::cos(halfAngle * kDeg);
    sinHalf = std::sin(halfAngle * kDeg);
    const std::size_t n = std::size_t(stride());
    xyz_.assign(std::size_t(kSets) * 3 * n, 0.0f);
    const float oneMinusCos = 1.0f - cosHalf;
    for (int set = 0; set < kSets; ++set) {
        Rng rng(0x636f6e652d726179ULL, std::uint64_t(set));  // "cone-ray"
        float* px = xyz_.data() + std::size_t(set) * 3 * n;
        float* py = px + n;
        float* pz = py + n;
        for (int i = 0; i < rings; ++i)
            for (int j = 0; j < sectors; ++j) {
                const float u = (float(i) + rng.uniform01()) / float(rings);
                const float phi = 2.0f * kPi * (float(j) + rng.uniform01()) / float(sectors);
                const float cosT = 1.0f - u * oneMinusCos;
                const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
                const vec3 v = glm::normalize(vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT));
                const std::size_t k = std::size_t(i * sectors + j);
                px[k] = v.x;
                py[k] = v.y;
                pz[k] = v.z;
            }
    }
}

std::shared_ptr<const ConePatterns> conePatterns(unsigned rays, float halfAngleDegrees) {
    static std::mutex mutex;
    static std::map<std::pair<int, float>, std::shared_ptr<const ConePatterns>> made;
    int rings, sectors;
    gridOf(rays, rings, sectors);
    const std::pair<int, float> key(rings * 100000 + sectors, halfAngleDegrees);
    std::lock_guard<std::mutex> lock(mutex);
    // A few shapes at a time (a scene uses one or two); cones in flight keep theirs alive.
    if (made.size() >= 16 && !made.count(key)) made.clear();
    auto& p = made[key];
    if (!p) p = std::make_shared<const ConePatterns>(rays, halfAngleDegrees);
    return p;
}

void sampleCone(const World& world, vec3 apex, vec3 axis, const PerceptionCone& cone, Rng& rng,
                float tnear, const Ignore& ignore, ConeSample& out, bool traced) {
    out.patterns = world.patterns(cone);
    const ConePatterns* patterns = out.patterns.get();
    const int set = int(rng.nextU32() % unsigned(ConePatterns::kSets));
    const float roll = 2.0f * kPi * rng.uniform01();
    out.rings = patterns->rings;
    out.sectors = patterns->sectors;
    out.hits = 0;
    out.cast = false;
    out.blocked.assign(std::size_t(patterns->stride()), 0u);  // padded while rays are cast
    out.x = patterns->x(set);
    out.y = patterns->y(set);
    out.z = patterns->z(set);
    const vec3 e1 = geometry::anyPerpendicular(axis);
    const vec3 e2 = glm::cross(axis, e1);
    const float cr = std::cos(roll), sr = std::sin(roll);
    out.axis = axis;
    out.e1 = cr * e1 + sr * e2;
    out.e2 = cr * e2 - sr * e1;

    thread_local std::vector<const vec3*> near;
    // A cone no wider than a hemisphere sees nothing behind its apex.
    world.softTrianglesNear(apex, cone.lookAhead + tnear, &ignore, near,
                            patterns->cosHalf >= 0.0f && !traced ? &axis : nullptr);
    if (near.empty() && !traced) {  // nothing within reach: every ray is free
        out.blocked.resize(std::size_t(patterns->cells()));
        return;
    }
    out.cast = true;
    world.stats().softRays.fetch_add(std::uint64_t(patterns->cells()), std::memory_order_relaxed);
    if (traced) {
        for (int k = 0; k < patterns->cells(); ++k)
            out.blocked[std::size_t(k)] =
                world.softOccluded(apex, out.direction(k), tnear, cone.lookAhead, &ignore);
    } else {
        const Frame f{apex, out.e1, out.e2, axis, patterns->cosHalf, patterns->sinHalf,
                      {tnear, cone.lookAhead}};
        for (const vec3* tri : near) rasterize(out, tri, f);
    }
    out.blocked.resize(std::size_t(patterns->cells()));
    for (std::uint32_t b : out.blocked) out.hits += int(b);
}

std::optional<vec3> bestGap(const ConeSample& sample, float halfAngleDegrees) {
    const int rings = sample.rings, sectors = sample.sectors, n = rings * sectors;
    if (sample.hits == 0 || sample.hits == n) return std::nullopt;
    // Runs of open cells along each ring, joined across rings by a union-find whose roots
    // are the lowest run numbers (so the components come in a fixed order).
    thread_local std::vector<int> runOf, parent, size;
    thread_local std::vector<vec3> sum;
    runOf.assign(std::size_t(n), -1);
    parent.clear();
    auto find = [&](int r) {
        while (parent[std::size_t(r)] != r) {
            parent[std::size_t(r)] = parent[std::size_t(parent[std::size_t(r)])];
            r = parent[std::size_t(r)];
        }
        return r;
    };
    auto unite = [&](int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        if (a < b) std::swap(a, b);
        parent[std::size_t(a)] = b;
    };
    const std::uint32_t* blocked = sample.blocked.data();
    for (int i = 0; i < rings; ++i) {
        const std::uint32_t* row = blocked + i * sectors;
        int* runs = runOf.data() + i * sectors;
        int start = -1;  // a blocked cell to start from, so no run wraps past it
        for (int j = 0; j < sectors && start < 0; ++j)
            if (row[j]) start = j;
        int current = -1;
        for (int step = 1, j = start < 0 ? 0 : start + 1; step <= sectors; ++step, ++j) {
            if (j == sectors) j = 0;
            if (row[j]) {
                current = -1;
                continue;
            }
            if (current < 0) {
                current = int(parent.size());
                parent.push_back(current);
            }
            runs[j] = current;
        }
        if (i == 0) {  // the innermost ring's open cells all meet at the axis
            int first = -1;
            for (int j = 0; j < sectors; ++j)
                if (runs[j] >= 0) {
                    if (first < 0) first = runs[j];
                    unite(runs[j], first);
                }
            continue;
        }
        const int* below = runs - sectors;
        for (int j = 0; j < sectors; ++j)
            if (runs[j] >= 0 && below[j] >= 0) unite(runs[j], below[j]);
    }
    const std::size_t components = parent.size();
    for (std::size_t r = 0; r < components; ++r) parent[r] = find(int(r));  // roots, flat
    size.assign(components, 0);
    sum.assign(components, vec3(0.0f));
    for (int k = 0; k < n; ++k) {
        const int r = runOf[std::size_t(k)];
        if (r < 0) continue;
        const std::size_t root = std::size_t(parent[std::size_t(r)]);
        ++size[root];
        sum[root] += vec3(sample.x[k], sample.y[k], sample.z[k]);
    }
    const float halfRad = halfAngleDegrees * kDeg;
    float bestScore = -1.0f;
    vec3 best(0.0f);
    for (std::size_t r = 0; r < components; ++r) {
        if (parent[r] != int(r)) continue;
        const float len = glm::length(sum[r]);
        if (!(len > 1e-6f)) continue;
        const vec3 centre = sum[r] / len;
        const float angle = std::acos(std::clamp(centre.z, -1.0f, 1.0f));
        // Gap size (fraction of the cone) weighed against its distance from the axis.
        const float score = float(size[r]) / float(n) * (1.0f - 0.5f * angle / halfRad);
        if (score > bestScore) {
            bestScore = score;
            best = centre;
        }
    }
    if (bestScore < 0.0f) return std::nullopt;
    const vec3 w = best.x * sample.e1 + best.y * sample.e2 + best.z * sample.axis;
    const float len = glm::length(w);
    return len > 1e-6f ? std::optional<vec3>(w / len) : std::nullopt;
}

}  // namespace plantarch::collision
