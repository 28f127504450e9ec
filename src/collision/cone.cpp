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

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

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

// Four lanes at a time (GCC/Clang vector extensions: SSE on x86-64, NEON on ARM): four rays
// against one triangle when marking cells, four triangles at once when bounding them.
typedef float Float4 __attribute__((vector_size(16)));
typedef std::int32_t Int4 __attribute__((vector_size(16)));

Float4 load4(const float* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

Float4 splat(float v) { return Float4{v, v, v, v}; }

Float4 select(Int4 mask, Float4 a, Float4 b) {
    return reinterpret_cast<Float4>((reinterpret_cast<Int4>(a) & mask) | (reinterpret_cast<Int4>(b) & ~mask));
}
Float4 min4(Float4 a, Float4 b) { return select(a < b, a, b); }
Float4 max4(Float4 a, Float4 b) { return select(a > b, a, b); }
Float4 abs4(Float4 a) {
    return reinterpret_cast<Float4>(reinterpret_cast<Int4>(a) & Int4{0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff});
}
Float4 sqrt4(Float4 v) {
#if defined(__SSE__)
    return reinterpret_cast<Float4>(_mm_sqrt_ps(reinterpret_cast<__m128>(v)));
#else
    return Float4{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}
bool any(Int4 m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }

// atan2 within 1e-5 rad (a polynomial on [0, 1] and the octant symmetries); the sector ranges
// it feeds have a margin of 1e-3 rad.
Float4 atan2v(Float4 y, Float4 x) {
    const Float4 ax = abs4(x), ay = abs4(y);
    const Float4 mx = max4(ax, ay);
    const Int4 zero = mx == splat(0.0f);
    const Float4 a = min4(ax, ay) / select(zero, splat(1.0f), mx);
    const Float4 s = a * a;
    Float4 r = ((splat(-0.0464964749f) * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
    r = select(ay > ax, 1.57079637f - r, r);
    r = select(x < 0.0f, 3.14159274f - r, r);
    r = select(y < 0.0f, -r, r);
    return select(zero, splat(0.0f), r);
}

// What a candidate is: a triangle; a quad whose triangles lie either side of its diagonal as
// seen from the apex; or a quad folded so that both lie on the same side (they may overlap).
enum Kind { kTriangle, kQuad, kFolded };

// A triangle's or quad's planes, broadcast: edge planes through the apex facing inward (a
// triangle: e[0..2]; a quad (a, b, c, d): e[0], e[1] edges ab, bc; e[2] the diagonal ca as
// the first triangle sees it; e[3], e[4] edges cd, da) and the planes of its triangles.
struct Planes {
    Float4 e[5][3];
    Float4 n1[3], d1, n2[3], d2;
};

Float4 dot4(const Float4 (&n)[3], Float4 x, Float4 y, Float4 z) { return x * n[0] + y * n[1] + z * n[2]; }

// Marks the cells [first, last] (and up to three past it, four at a time: the arrays are
// padded, and every cell is tested exactly, so extra cells are only extra work, and the
// cells past the last are cut off at the end) whose rays pass inside the edge
// planes and, with kReach, hit the plane (t = dist / dot(ray, normal)) within reach. A quad's
// ray is tested against the triangle on its side of the diagonal, a folded quad's against
// both.
template <int kKind, bool kReach>
void markInside(const float* __restrict rx, const float* __restrict ry, const float* __restrict rz,
                std::uint32_t* __restrict blocked, int first, int last, const Planes& p,
                Float4 tnear, Float4 tfar) {
    const Float4 zero = splat(0.0f);
    for (int k = first; k <= last; k += 4) {
        const Float4 x = load4(rx + k), y = load4(ry + k), z = load4(rz + k);
        Int4 in;
        Float4 t;
        if constexpr (kKind == kFolded) {
            const Int4 side = dot4(p.e[2], x, y, z) >= zero;
            Int4 in1 = side & (dot4(p.e[0], x, y, z) >= zero) & (dot4(p.e[1], x, y, z) >= zero);
            Int4 in2 = side & (dot4(p.e[3], x, y, z) >= zero) & (dot4(p.e[4], x, y, z) >= zero);
            if constexpr (kReach) {
                const Float4 t1 = p.d1 / dot4(p.n1, x, y, z), t2 = p.d2 / dot4(p.n2, x, y, z);
                in1 &= (t1 >= tnear) & (t1 <= tfar);
                in2 &= (t2 >= tnear) & (t2 <= tfar);
            }
            in = in1 | in2;
        } else if constexpr (kKind == kQuad) {
            const Int4 side = dot4(p.e[2], x, y, z) >= zero;
            in = (side & (dot4(p.e[0], x, y, z) >= zero) & (dot4(p.e[1], x, y, z) >= zero)) |
                 (~side & (dot4(p.e[3], x, y, z) >= zero) & (dot4(p.e[4], x, y, z) >= zero));
            if constexpr (kReach) {
                const Float4 denom = x * select(side, p.n1[0], p.n2[0]) + y * select(side, p.n1[1], p.n2[1]) +
                                     z * select(side, p.n1[2], p.n2[2]);
                t = select(side, p.d1, p.d2) / denom;
            }
        } else {
            in = (dot4(p.e[0], x, y, z) >= zero) & (dot4(p.e[1], x, y, z) >= zero) &
                 (dot4(p.e[2], x, y, z) >= zero);
            if constexpr (kReach) t = p.d1 / dot4(p.n1, x, y, z);
        }
        if constexpr (kReach && kKind != kFolded) in &= (t >= tnear) & (t <= tfar);
        Int4 b;
        std::memcpy(&b, blocked + k, sizeof b);
        b |= in & 1;
        std::memcpy(blocked + k, &b, sizeof b);
    }
}

struct Frame {
    vec3 apex, e1, e2, axis;
    float cosHalf, sinHalf;
    float tnear, lookAhead;
    int rings, sectors;
};

// One triangle or quad that may block rays, in the cone's frame: its planes (as Planes) and
// the cells its directions can reach.
struct Candidate {
    float e[5][3];
    float n1[3], d1, n2[3], d2;
    int ringLo, ringHi;
    int runs[2][2];  ///< sector runs [first, last] within a ring; the second may be empty
    Kind kind;
    bool checkReach;
};

// Four quads bounded at once (lane k: quad k of the block): whether each may block rays, its
// edge planes (as in boundBlock), planes and the cells its directions can reach.
struct BlockBounds {
    struct Lanes {
        Int4 valid, first, second, aroundAxis, checkReach, ringLo, ringHi, sectorLo, sectorHi;
        Float4 volume1, volume2, dist1, dist2;
    } lanes;
    Float4 n[5][3], normal1[3], normal2[3];
};

// Appends the candidates of a bounded block: a quad (flat or folded as seen from the apex), or
// the triangle of it that is not seen edge-on; planes facing inward.
void emitCandidates(const BlockBounds& b, const Frame& f, std::vector<Candidate>& out) {
    const Float4(&n)[5][3] = b.n;
    const BlockBounds::Lanes& l = b.lanes;
    for (int k = 0; k < 4; ++k) {
        if (!l.valid[k]) continue;
        Candidate bounds;
        bounds.ringLo = l.ringLo[k];
        bounds.ringHi = l.ringHi[k];
        bounds.checkReach = l.checkReach[k] != 0;
        // The sector range as at most two runs inside [0, sectors).
        const int sectors = f.sectors, lo = l.sectorLo[k], hi = l.sectorHi[k];
        int(&runs)[2][2] = bounds.runs;
        runs[1][0] = 0;
        runs[1][1] = -1;
        if (l.aroundAxis[k] || hi - lo + 1 >= sectors) {
            runs[0][0] = 0;
            runs[0][1] = sectors - 1;
        } else if (lo < 0) {
            runs[0][0] = lo + sectors;
            runs[0][1] = sectors - 1;
            runs[1][1] = hi;
        } else if (hi >= sectors) {
            runs[0][0] = lo;
            runs[0][1] = sectors - 1;
            runs[1][1] = hi - sectors;
        } else {
            runs[0][0] = lo;
            runs[0][1] = hi;
        }
        // Planes facing inward: each triangle's edges flipped when it faces away.
        const float s1 = l.volume1[k] < 0.0f ? -1.0f : 1.0f, s2 = l.volume2[k] < 0.0f ? -1.0f : 1.0f;
        auto set = [&](float (&to)[3], const Float4 (&from)[3], float sign) {
            for (int i = 0; i < 3; ++i) to[i] = from[i][k] * sign;
        };
        auto plane = [&](float (&to)[3], const Float4 (&from)[3]) {
            for (int i = 0; i < 3; ++i) to[i] = from[i][k];
        };
        const bool one = l.first[k] != 0, two = l.second[k] != 0;
        if (one && two) {  // a quad
            Candidate& t = out.emplace_back(bounds);
            t.kind = s1 == s2 ? kQuad : kFolded;
            set(t.e[0], n[0], s1);
            set(t.e[1], n[1], s1);
            set(t.e[2], n[4], s1);
            set(t.e[3], n[2], s2);
            set(t.e[4], n[3], s2);
            plane(t.n1, b.normal1);
            t.d1 = l.dist1[k];
            plane(t.n2, b.normal2);
            t.d2 = l.dist2[k];
            continue;
        }
        if (one) {  // a lone triangle
            Candidate& t = out.emplace_back(bounds);
            t.kind = kTriangle;
            set(t.e[0], n[0], s1);
            set(t.e[1], n[1], s1);
            set(t.e[2], n[4], s1);
            plane(t.n1, b.normal1);
            t.d1 = l.dist1[k];
        }
        if (two) {  // a quad whose first triangle is seen edge-on
            Candidate& t = out.emplace_back(bounds);
            t.kind = kTriangle;
            set(t.e[0], n[4], -s2);
            set(t.e[1], n[2], s2);
            set(t.e[2], n[3], s2);
            plane(t.n1, b.normal2);
            t.d1 = l.dist2[k];
        }
    }
}

// Bounds four quads of `batch` (block `b`) at once; appends those that may block rays.
//
// Each quad is moved into the cone's frame; the directions to its corners lie in a cap, and
// so do all directions that hit it: the rings it can reach come from the cap and, for a quad
// wholly in front of the apex, from its corners (along a great-circle arc in the front
// half-space the height z is a positive arc of a cosine, least at an end). When neither
// triangle's shadow on the cone's base plane holds the origin (neither crosses the axis nor
// its extension backward), the azimuths it covers are those between its corners' (an edge's
// azimuth runs monotonically: it lies on a great circle, whose shadow is an ellipse about the
// origin; each triangle spans less than half a turn and both hold corner a). A lone triangle
// is a quad whose last two corners are the same: its second triangle is seen edge-on.
void boundBlock(const TriangleBatch& batch, std::size_t b, const Frame& f,
                std::vector<Candidate>& out) {
    const std::size_t count = std::min<std::size_t>(4, batch.size() - 4 * b);
    Int4 valid = Int4{0, 1, 2, 3} < Int4{int(count), int(count), int(count), int(count)};
    Float4 qx[4], qy[4], qz[4];
    for (int c = 0; c < 4; ++c) {
        const Float4 px = load4(batch.row(b, 3 * c)) - f.apex.x;
        const Float4 py = load4(batch.row(b, 3 * c + 1)) - f.apex.y;
        const Float4 pz = load4(batch.row(b, 3 * c + 2)) - f.apex.z;
        qx[c] = px * f.e1.x + py * f.e1.y + pz * f.e1.z;
        qy[c] = px * f.e2.x + py * f.e2.y + pz * f.e2.z;
        qz[c] = px * f.axis.x + py * f.axis.y + pz * f.axis.z;
    }
    const Float4 zero = splat(0.0f);
    // Wholly behind the apex, for a cone no wider than a hemisphere.
    if (f.cosHalf >= 0.0f) valid &= (qz[0] > zero) | (qz[1] > zero) | (qz[2] > zero) | (qz[3] > zero);
    Float4 l[4];
    for (int c = 0; c < 4; ++c) {
        l[c] = sqrt4(qx[c] * qx[c] + qy[c] * qy[c] + qz[c] * qz[c]);
        valid &= l[c] > zero;
    }
    // Beyond reach: the bounding sphere about the corners' mean lies past the look-ahead.
    const Float4 quarter = splat(0.25f);
    const Float4 mx = (qx[0] + qx[1] + qx[2] + qx[3]) * quarter,
                 my = (qy[0] + qy[1] + qy[2] + qy[3]) * quarter,
                 mz = (qz[0] + qz[1] + qz[2] + qz[3]) * quarter;
    Float4 r2 = zero;
    for (int c = 0; c < 4; ++c) {
        const Float4 dx = qx[c] - mx, dy = qy[c] - my, dz = qz[c] - mz;
        r2 = max4(r2, dx * dx + dy * dy + dz * dz);
    }
    const Float4 nearest = sqrt4(mx * mx + my * my + mz * mz) - sqrt4(r2);
    valid &= nearest <= f.lookAhead;
    if (!any(valid)) return;
    // Edge planes through the apex (edge i runs from corner i to corner i + 1; edge 4 is the
    // diagonal c -> a), and which way each triangle faces the apex.
    auto cross = [](Float4 ax, Float4 ay, Float4 az, Float4 bx, Float4 by, Float4 bz, Float4* o) {
        o[0] = ay * bz - az * by;
        o[1] = az * bx - ax * bz;
        o[2] = ax * by - ay * bx;
    };
    BlockBounds bounds;  // what the candidates are made of (emitCandidates)
    Float4(&n)[5][3] = bounds.n;
    for (int c = 0; c < 4; ++c) {
        const int e = c == 3 ? 0 : c + 1;
        cross(qx[c], qy[c], qz[c], qx[e], qy[e], qz[e], n[c]);
    }
    cross(qx[2], qy[2], qz[2], qx[0], qy[0], qz[0], n[4]);
    const Float4 volume1 = qx[0] * n[1][0] + qy[0] * n[1][1] + qz[0] * n[1][2];
    const Float4 volume2 = qx[0] * n[2][0] + qy[0] * n[2][1] + qz[0] * n[2][2];
    const Int4 first = abs4(volume1) >= 1e-18f, second = abs4(volume2) >= 1e-18f;  // not edge-on
    valid &= first | second;
    // Rings: the quad's directions come nearest the axis at a corner, inside an edge (where
    // its great circle passes nearest the axis, when that lies between the edge's ends), or on
    // the axis itself (when it crosses it); wholly in front of the apex, they are farthest
    // from it at a corner (along a great-circle arc in the front half-space the height z is a
    // positive arc of a cosine, least at an end).
    Float4 cosCorner[4];
    for (int c = 0; c < 4; ++c) cosCorner[c] = qz[c] / select(valid, l[c], splat(1.0f));
    Float4 maxCos = max4(max4(cosCorner[0], cosCorner[1]), max4(cosCorner[2], cosCorner[3]));
    const Float4 minCos = min4(min4(cosCorner[0], cosCorner[1]), min4(cosCorner[2], cosCorner[3]));
    static constexpr int kEnds[5][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {2, 0}};
    for (int e = 0; e < 5; ++e) {
        const int p = kEnds[e][0], q = kEnds[e][1];
        const Float4(&m)[3] = n[e];
        const Float4 mm = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
        const Int4 inside = (mm > zero) & (m[0] * qy[p] - m[1] * qx[p] >= zero) &
                            (qx[q] * m[1] - qy[q] * m[0] >= zero);
        const Float4 cosEdge = sqrt4(max4(zero, 1.0f - m[2] * m[2] / select(inside, mm, splat(1.0f))));
        maxCos = select(inside, max4(maxCos, cosEdge), maxCos);
    }
    const Float4 maxL = max4(max4(l[0], l[1]), max4(l[2], l[3]));
    const Float4 eps = 1e-5f * maxL * maxL;  // shadows that nearly touch the origin count
    auto holdsAxis = [&](Float4 u, Float4 v, Float4 w) {
        return ((u >= -eps) & (v >= -eps) & (w >= -eps)) | ((u <= eps) & (v <= eps) & (w <= eps));
    };
    const Int4 aroundAxis = (first & holdsAxis(n[0][2], n[1][2], n[4][2])) |
                            (second & holdsAxis(-n[4][2], n[2][2], n[3][2]));
    maxCos = select(aroundAxis, splat(2.0f), maxCos + 1e-5f);
    valid &= maxCos >= f.cosHalf;  // else wholly outside the cone
    const Int4 front = (qz[0] > zero) & (qz[1] > zero) & (qz[2] > zero) & (qz[3] > zero);
    const Float4 cosLo = maxCos, cosHi = select(front, minCos - 1e-5f, splat(-2.0f));
    if (!any(valid)) return;
    // Sectors (the 2-d cross products in holdsAxis are the edge planes' z).
    const Float4 pi = splat(kPi), twoPi = splat(2.0f * kPi);
    const Float4 p0 = atan2v(qy[0], qx[0]);
    Float4 lo = zero, hi = zero;
    for (int c = 1; c < 4; ++c) {
        // Relative to corner a, each within half a turn.
        Float4 pc = atan2v(qy[c], qx[c]) - p0;
        pc -= select(pc > pi, twoPi, select(pc < -pi, -twoPi, zero));
        lo = min4(lo, pc);
        hi = max4(hi, pc);
    }
    lo = p0 + lo - 1e-3f;
    hi = p0 + hi + 1e-3f;
    const Int4 wrap = lo < zero;
    lo += select(wrap, twoPi, zero);
    hi += select(wrap, twoPi, zero);
    // The triangles' planes.
    Float4(&normal1)[3] = bounds.normal1;
    Float4(&normal2)[3] = bounds.normal2;
    cross(qx[1] - qx[0], qy[1] - qy[0], qz[1] - qz[0], qx[2] - qx[0], qy[2] - qy[0], qz[2] - qz[0],
          normal1);
    cross(qx[2] - qx[0], qy[2] - qy[0], qz[2] - qz[0], qx[3] - qx[0], qy[3] - qy[0], qz[3] - qz[0],
          normal2);
    const Float4 dist1 = qx[0] * normal1[0] + qy[0] * normal1[1] + qz[0] * normal1[2];
    const Float4 dist2 = qx[0] * normal2[0] + qy[0] * normal2[1] + qz[0] * normal2[2];
    const Int4 checkReach = (maxL > f.lookAhead) | (nearest <= f.tnear);
    // Rings from the cosines (2: the first ring; -2: the last), sectors from the azimuths.
    const Float4 rings = splat(float(f.rings));
    const Float4 ringScale = rings / (1.0f - f.cosHalf), lastRing = rings - 1.0f;
    auto ringOf = [&](Float4 cosTheta) {
        const Float4 u = max4(zero, min4(lastRing, (1.0f - cosTheta) * ringScale));
        return __builtin_convertvector(u, Int4);  // u >= 0: truncation is the floor
    };
    const Int4 ringLo = ringOf(cosLo), ringHi = ringOf(cosHi);
    const Float4 perSector = splat(float(f.sectors) / (2.0f * kPi));
    auto floorOf = [](Float4 v) {
        const Int4 t = __builtin_convertvector(v, Int4);
        return t + (__builtin_convertvector(t, Float4) > v);  // a true comparison is -1
    };
    const Int4 sectorLo = floorOf(lo * perSector), sectorHi = floorOf(hi * perSector);
    bounds.lanes = {valid,  first,    second,   aroundAxis, checkReach, ringLo, ringHi,
                    sectorLo, sectorHi, volume1, volume2, dist1,      dist2};
    emitCandidates(bounds, f, out);
}

// Marks the cells whose rays hit candidate `t`.
template <int kKind, bool kReach>
void rasterize(ConeSample& cone, const Candidate& t, const Frame& f) {
    std::uint32_t* blocked = cone.blocked.data();
    constexpr bool kTwo = kKind != kTriangle;
    Planes p;
    for (int e = 0; e < (kTwo ? 5 : 3); ++e)
        for (int i = 0; i < 3; ++i) p.e[e][i] = splat(t.e[e][i]);
    for (int i = 0; i < 3; ++i) {
        p.n1[i] = splat(t.n1[i]);
        if (kTwo) p.n2[i] = splat(t.n2[i]);
    }
    p.d1 = splat(t.d1);
    if (kTwo) p.d2 = splat(t.d2);
    const Float4 tnear = splat(f.tnear), tfar = splat(f.lookAhead);
    const bool second = t.runs[1][1] >= 0;
    for (int i = t.ringLo, row = i * f.sectors; i <= t.ringHi; ++i, row += f.sectors) {
        markInside<kKind, kReach>(cone.x, cone.y, cone.z, blocked, row + t.runs[0][0],
                                  row + t.runs[0][1], p, tnear, tfar);
        if (second)
            markInside<kKind, kReach>(cone.x, cone.y, cone.z, blocked, row, row + t.runs[1][1], p,
                                      tnear, tfar);
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

    thread_local TriangleBatch near;
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
                      tnear, cone.lookAhead, patterns->rings, patterns->sectors};
        thread_local std::vector<Candidate> candidates;
        candidates.clear();
        for (std::size_t b = 0; b < near.blocks(); ++b) boundBlock(near, b, f, candidates);
        for (const Candidate& t : candidates) {
            switch (t.kind) {
                case kTriangle:
                    t.checkReach ? rasterize<kTriangle, true>(out, t, f) : rasterize<kTriangle, false>(out, t, f);
                    break;
                case kQuad:
                    t.checkReach ? rasterize<kQuad, true>(out, t, f) : rasterize<kQuad, false>(out, t, f);
                    break;
                case kFolded:
                    t.checkReach ? rasterize<kFolded, true>(out, t, f) : rasterize<kFolded, false>(out, t, f);
                    break;
            }
        }
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
    runOf.resize(std::size_t(n));
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
        int start = 0;  // a blocked cell to start from, so no run wraps past it
        while (start < sectors && !row[start]) ++start;
        if (start == sectors) {  // an open ring: one run
            const int r = int(parent.size());
            parent.push_back(r);
            std::fill(runs, runs + sectors, r);
        } else {
            runs[start] = -1;
            int current = -1;
            for (int step = 1, j = start + 1; step < sectors; ++step, ++j) {
                if (j == sectors) j = 0;
                if (row[j]) {
                    runs[j] = -1;
                    current = -1;
                    continue;
                }
                if (current < 0) {
                    current = int(parent.size());
                    parent.push_back(current);
                }
                runs[j] = current;
            }
        }
        if (i == 0) {  // the innermost ring's open cells all meet at the axis
            for (std::size_t r = 1; r < parent.size(); ++r) parent[r] = 0;
            continue;
        }
        // Neighbours across the ring boundary share a sector; a pair once joined is skipped
        // along the rest of the two runs.
        const int* below = runs - sectors;
        int lastA = -1, lastB = -1;
        for (int j = 0; j < sectors; ++j) {
            const int a = runs[j], b = below[j];
            if (a < 0 || b < 0 || (a == lastA && b == lastB)) continue;
            unite(a, b);
            lastA = a;
            lastB = b;
        }
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
