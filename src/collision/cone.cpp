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
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>

#if defined(__x86_64__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "collision/collision_world.h"
#include "core/math.h"
#include "plantarch/Error.h"

namespace plantarch::collision {

namespace {

// Rings and sectors of a cone of `rays` rays: about four sectors per ring per ring.
void gridOf(unsigned rays, int& rings, int& sectors) {
    rings = std::max(1, int(std::lround(std::sqrt(double(rays) / 4.0))));
    sectors = std::max(3, int(rays) / rings);
}

// What a candidate is: a triangle; a quad whose triangles lie either side of its diagonal as
// seen from the apex; or a quad folded so that both lie on the same side (they may overlap).
enum Kind { kTriangle, kQuad, kFolded };

struct Frame {
    vec3 apex, e1, e2, axis;
    float cosHalf, sinHalf;
    float tnear, lookAhead;
    int rings, sectors;
};

// The inner loops, for any processor and, where the compiler can target it, for AVX2
// (cone_kernel.inc).
namespace portable {
#define PLANTARCH_CONE_LANES 4
#include "collision/cone_kernel.inc"
#undef PLANTARCH_CONE_LANES
}  // namespace portable

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PLANTARCH_CONE_WIDE 1
#pragma GCC push_options
#pragma GCC target("avx2")
namespace wide {
#define PLANTARCH_CONE_LANES 8
#include "collision/cone_kernel.inc"
#undef PLANTARCH_CONE_LANES
}  // namespace wide
#pragma GCC pop_options
#endif

bool processorRunsWide() {
#if defined(PLANTARCH_CONE_WIDE)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
#else
    return false;
#endif
}

// The kernel set by setConeKernel (-1: none, the widest available).
std::atomic<int> chosenKernel{-1};

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
                const vec3 v =
                    glm::normalize(vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT));
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

bool coneKernelAvailable(ConeKernel kernel) {
    return kernel == ConeKernel::kPortable || processorRunsWide();
}

void setConeKernel(std::optional<ConeKernel> kernel) {
    if (kernel && !coneKernelAvailable(*kernel))
        throw Error("this processor cannot run the wide cone kernel (AVX2)",
                    {.parameter = "cone kernel", .value = "wide", .validRange = "portable"});
    chosenKernel.store(kernel ? int(*kernel) : -1, std::memory_order_relaxed);
}

ConeKernel coneKernel() {
    const int chosen = chosenKernel.load(std::memory_order_relaxed);
    if (chosen >= 0) return ConeKernel(chosen);
    return processorRunsWide() ? ConeKernel::kWide : ConeKernel::kPortable;
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
    const vec3 e1 = anyPerpendicular(axis);
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
        const Frame f{apex,
                      out.e1,
                      out.e2,
                      axis,
                      patterns->cosHalf,
                      patterns->sinHalf,
                      tnear,
                      cone.lookAhead,
                      patterns->rings,
                      patterns->sectors};
#if defined(PLANTARCH_CONE_WIDE)
        if (coneKernel() == ConeKernel::kWide) {
            wide::castRays(near, f, out.x, out.y, out.z, out.blocked.data());
        } else
#endif
        {
            portable::castRays(near, f, out.x, out.y, out.z, out.blocked.data());
        }
    }
    out.blocked.resize(std::size_t(patterns->cells()));
    // (A local sum: the flags could alias out.hits, which kept the loop from going four wide.)
    unsigned hits = 0;
    for (std::uint32_t b : out.blocked) hits += b;
    out.hits = int(hits);
}

namespace {

// Bit j set when flag j of the n (at most 64) is 0: four flags at a time where SSE2 is at hand.
// (SSE kept: bestGap costs 62 M instructions on bench/callgrind/soft_canopy.cpp soft with the
// plain loop alone, 55 M with vector extensions, 49 M with this.)
std::uint64_t openBits(const std::uint32_t* flags, int n) {
    std::uint64_t open = 0;
    int j = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    for (; j + 4 <= n; j += 4) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(flags + j));
        const int four = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(v, zero)));
        open |= std::uint64_t(unsigned(four)) << j;
    }
#endif
    for (; j < n; ++j) open |= std::uint64_t(flags[j] == 0) << j;
    return open;
}

}  // namespace

std::optional<vec3> bestGap(const ConeSample& sample, float halfAngleDegrees) {
    const int rings = sample.rings, sectors = sample.sectors, n = rings * sectors;
    if (sample.hits == 0 || sample.hits == n) return std::nullopt;
    // Each ring's open cells as pieces [first, last] in sector order; the runs they make (a
    // run may wrap past the last sector: then its two pieces share it) are numbered ring by
    // ring, from the first blocked cell around, and joined across rings by a union-find whose
    // roots are the lowest run numbers (so the components come in a fixed order).
    struct Piece {
        int first, last, run;
    };
    thread_local std::vector<Piece> pieces;
    thread_local std::vector<int> ringPieces, parent, size;
    thread_local std::vector<vec3> sum;
    pieces.clear();
    ringPieces.assign(1, 0);
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
        const std::size_t from = pieces.size();
        // The ring's open cells as bits, 64 sectors at a time, runs of ones taken lowest first:
        // adding a run's lowest bit carries through the run and clears it (no branch per
        // cell). A run that reaches the next 64 sectors goes on there.
        for (int base = 0; base < sectors; base += 64) {
            const int width = std::min(64, sectors - base);
            for (std::uint64_t open = openBits(row + base, width); open;) {
                const std::uint64_t rest = open & (open + (open & (~open + 1)));
                const std::uint64_t run = open ^ rest;
                const int first = base + __builtin_ctzll(run);
                const int last = base + 63 - __builtin_clzll(run);
                if (first == base && pieces.size() > from && pieces.back().last == first - 1)
                    pieces.back().last = last;
                else
                    pieces.push_back({first, last, -1});
                open = rest;
            }
        }
        Piece* ring = pieces.data() + from;
        const std::size_t count = pieces.size() - from;
        // Cells before the first blocked one belong to the ring's last run: the one that wraps
        // (when the last cell is open) or one of their own.
        const bool leading = count > 0 && ring[0].first == 0;
        const bool open = leading && ring[0].last == sectors - 1;  // no blocked cell
        for (std::size_t k = leading && !open ? 1 : 0; k < count; ++k) {
            ring[k].run = int(parent.size());
            parent.push_back(ring[k].run);
        }
        if (leading && !open) {
            const bool wraps = count > 1 && ring[count - 1].last == sectors - 1;
            ring[0].run = wraps ? ring[count - 1].run : int(parent.size());
            if (!wraps) parent.push_back(ring[0].run);
        }
        ringPieces.push_back(int(pieces.size()));
        if (i == 0) {  // the innermost ring's open cells all meet at the axis
            for (std::size_t r = 1; r < parent.size(); ++r) parent[r] = 0;
            continue;
        }
        // Neighbours across the ring boundary share a sector: pieces that overlap join.
        const Piece* below = pieces.data() + ringPieces[std::size_t(i) - 1];
        const Piece* belowEnd = ring;
        for (const Piece* p = ring; p != ring + count && below != belowEnd;) {
            if (below->last < p->first) {
                ++below;
            } else if (p->last < below->first) {
                ++p;
            } else {
                unite(p->run, below->run);
                if (p->last < below->last)
                    ++p;
                else
                    ++below;
            }
        }
    }
    const std::size_t components = parent.size();
    for (std::size_t r = 0; r < components; ++r) parent[r] = find(int(r));  // roots, flat
    size.assign(components, 0);
    sum.assign(components, vec3(0.0f));
    // Each component's directions summed in cell order (pieces come in it).
    for (int i = 0; i < rings; ++i)
        for (int q = ringPieces[std::size_t(i)]; q < ringPieces[std::size_t(i) + 1]; ++q) {
            const Piece& p = pieces[std::size_t(q)];
            const std::size_t root = std::size_t(parent[std::size_t(p.run)]);
            size[root] += p.last - p.first + 1;
            vec3& total = sum[root];
            for (int k = i * sectors + p.first, end = i * sectors + p.last; k <= end; ++k)
                total += vec3(sample.x[k], sample.y[k], sample.z[k]);
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
