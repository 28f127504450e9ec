// The hashed uniform grid of soft obstacles (see soft_grid.h).

#include "collision/soft_grid.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "collision/collision_world.h"
#include "core/parallel.h"

namespace plantarch::collision {

namespace {

// Cell coordinates packed 21 bits each (a grid of two million cells a side, centred on 0).
constexpr std::int64_t kBias = std::int64_t(1) << 20;
constexpr std::int64_t kMask = (std::int64_t(1) << 21) - 1;

inline std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::uint64_t((x + kBias) & kMask) | (std::uint64_t((y + kBias) & kMask) << 21) |
           (std::uint64_t((z + kBias) & kMask) << 42);
}

// floor(v * inverse) within the grid's range, without a call to floor: clamped first (so the
// conversion cannot overflow; NaN goes to the lowest cell), truncated, then one down for
// negative non-integers.
inline std::int64_t cellIndex(float v, float inverse) {
    const float x = v * inverse, lo = float(-kBias), hi = float(kBias - 1);
    const float c = x >= lo ? (x <= hi ? x : hi) : lo;
    const std::int64_t t = std::int64_t(c);
    return t - (float(t) > c ? 1 : 0);
}

// Makes `v` hold n elements whose values are all about to be written: storage too small is
// replaced, not copied.
template <class T>
void resizeOver(std::vector<T>& v, std::size_t n) {
    if (v.capacity() < n) {
        v.clear();
        v.reserve(n + n / 4);
    }
    v.resize(n);
}

}  // namespace

// SSE intrinsics kept in sphereOf, cellKeys and near's test4: the plain forms after each #else
// give the same bytes but cost more (instructions of bench/callgrind/soft_canopy.cpp soft, one
// thread): boundingSpheres 48 M instead of 35 M, cellKeys 27 M instead of 18 M, near 54 M
// instead of 50 M.
#if defined(__SSE2__)
namespace {

// The sphere of the triangle at p, or of the quad it starts with the next when `pairs` (the
// next is of the same organ) and their corners make one (see boundingSpheres); returns
// whether they do. glm's operations in glm's order, a corner's three coordinates (and the
// four corners' distances) at once; `load` reads a corner as (x, y, z, anything).
template <class Load>
inline bool sphereOf(const vec3* p, bool pairs, Load load, glm::vec4& sphere) {
    const __m128 a = load(p[0]), b = load(p[1]), c = load(p[2]);
    // (Lane by lane ==, as vec3's: -0 equals 0, NaN nothing.)
    const bool quad =
        pairs &&
        (_mm_movemask_ps(_mm_and_ps(_mm_cmpeq_ps(load(p[3]), a), _mm_cmpeq_ps(load(p[4]), c))) &
         7) == 7;
    const __m128 d = quad ? load(p[5]) : c;
    const __m128 sum = _mm_add_ps(_mm_add_ps(a, b), c);
    const __m128 centre = quad ? _mm_mul_ps(_mm_add_ps(sum, d), _mm_set1_ps(0.25f))
                               : _mm_mul_ps(sum, _mm_set1_ps(1.0f / 3.0f));
    __m128 ea = _mm_sub_ps(a, centre), eb = _mm_sub_ps(b, centre);
    __m128 ec = _mm_sub_ps(c, centre), ed = _mm_sub_ps(d, centre);
    ea = _mm_mul_ps(ea, ea);
    eb = _mm_mul_ps(eb, eb);
    ec = _mm_mul_ps(ec, ec);
    ed = _mm_mul_ps(ed, ed);
    _MM_TRANSPOSE4_PS(ea, eb, ec, ed);  // ea: the x terms of the four corners, eb y, ec z
    const __m128 d2 = _mm_add_ps(_mm_add_ps(ea, eb), ec);
    // std::max's r < x ? x : r, which is _mm_max_ss(x, r) (NaN and ties alike).
    __m128 r2 = d2;
    r2 = _mm_max_ss(_mm_shuffle_ps(d2, d2, 1), r2);
    r2 = _mm_max_ss(_mm_shuffle_ps(d2, d2, 2), r2);
    r2 = _mm_max_ss(_mm_shuffle_ps(d2, d2, 3), r2);
    // A hair more than the farthest corner, so rounding never drops a touching triangle.
    const __m128 radius =
        _mm_add_ss(_mm_mul_ss(_mm_sqrt_ss(r2), _mm_set_ss(1.0001f)), _mm_set_ss(1e-7f));
    // (centre.x, centre.y, centre.z, radius)
    const __m128 zr = _mm_shuffle_ps(centre, radius, _MM_SHUFFLE(0, 0, 2, 2));
    _mm_storeu_ps(&sphere.x, _mm_shuffle_ps(centre, zr, _MM_SHUFFLE(2, 0, 1, 0)));
    return quad;
}

}  // namespace
#endif

void boundingSpheres(const std::vector<vec3>& soup, std::vector<glm::vec4>& spheres,
                     const std::vector<std::uint64_t>* tags) {
    const std::size_t n = soup.size() / 3;
    spheres.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
        const vec3* p = soup.data() + 3 * t;
        // The centre, c = (a + b + c + d) / 4 for a quad, (a + b + c) / 3 for a triangle, and
        // the squared distances of the corners from it, max(|a - c|^2, ..., |d - c|^2).
        const bool pairs = t + 1 < n && (!tags || (*tags)[t] == (*tags)[t + 1]);
#if defined(__SSE2__)
        // Four floats read at a time where a float follows the corner (all six corners of a
        // pair but the last pair's), else three.
        const bool quad =
            t + 2 < n ? sphereOf(
                            p, pairs, [](const vec3& v) { return _mm_loadu_ps(&v.x); }, spheres[t])
                      : sphereOf(
                            p, pairs,
                            [](const vec3& v) {
                                return _mm_movelh_ps(_mm_castsi128_ps(_mm_loadl_epi64(
                                                         reinterpret_cast<const __m128i*>(&v))),
                                                     _mm_load_ss(&v.z));
                            },
                            spheres[t]);
        if (quad) {
            spheres[t + 1] = glm::vec4(vec3(spheres[t]), -1.0f);
            ++t;
        }
#else
        const bool quad = pairs && p[3] == p[0] && p[4] == p[2];
        const vec3& d = quad ? p[5] : p[2];
        const vec3 c =
            quad ? (p[0] + p[1] + p[2] + d) * 0.25f : (p[0] + p[1] + p[2]) * (1.0f / 3.0f);
        const float r2 = std::max({glm::dot(p[0] - c, p[0] - c), glm::dot(p[1] - c, p[1] - c),
                                   glm::dot(p[2] - c, p[2] - c), glm::dot(d - c, d - c)});
        // A hair more than the farthest corner, so rounding never drops a touching triangle.
        spheres[t] = glm::vec4(c, std::sqrt(r2) * 1.0001f + 1e-7f);
        if (quad) spheres[++t] = glm::vec4(c, -1.0f);
#endif
    }
}

bool SoftGrid::ignored(const SoftTriangle& t, const Ignore* ignore) {
    return ignore && t.owner == ignore->plant + 1 &&
           (t.tag == ignore->organs[0] || t.tag == ignore->organs[1]);
}

void SoftGrid::cellKeys(const std::vector<glm::vec4>& spheres, float cell,
                        std::vector<std::uint64_t>& keys) {
    const float size = std::max(cell, kMinCell), inverse = 1.0f / size;
    keys.resize(spheres.size());
    const glm::vec4* sphere = spheres.data();
    std::uint64_t* key = keys.data();
#if defined(__SSE2__)
    // cellIndex of x, y and z at once (the same comparisons, truncation and step down; the
    // indices fit 32 bits once clamped).
    const __m128 scale = _mm_set1_ps(inverse), lo = _mm_set1_ps(float(-kBias)),
                 hi = _mm_set1_ps(float(kBias - 1));
    const __m128i bias = _mm_set1_epi32(std::int32_t(kBias)),
                  mask = _mm_set1_epi32(std::int32_t(kMask));
#endif
    for (std::size_t t = 0; t < spheres.size(); ++t) {
        const float w = sphere[t].w;
        if (w < 0.0f) {
            key[t] = kSecond;
            continue;
        }
        if (w > size) {
            key[t] = kLarge;
            continue;
        }
#if defined(__SSE2__)
        const __m128 x = _mm_mul_ps(_mm_loadu_ps(&sphere[t].x), scale);
        const __m128 below = _mm_cmple_ps(x, hi), above = _mm_cmpge_ps(x, lo);
        __m128 c = _mm_or_ps(_mm_and_ps(below, x), _mm_andnot_ps(below, hi));
        c = _mm_or_ps(_mm_and_ps(above, c), _mm_andnot_ps(above, lo));
        __m128i i = _mm_cvttps_epi32(c);
        i = _mm_add_epi32(i, _mm_castps_si128(_mm_cmpgt_ps(_mm_cvtepi32_ps(i), c)));  // -1: down
        i = _mm_and_si128(_mm_add_epi32(i, bias), mask);
        key[t] = std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(i))) |
                 std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(i, 1)))) << 21 |
                 std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(i, 2)))) << 42;
#else
        key[t] = pack(cellIndex(sphere[t].x, inverse), cellIndex(sphere[t].y, inverse),
                      cellIndex(sphere[t].z, inverse));
#endif
    }
}

void SoftGrid::build(const std::vector<Source>& sources, float cell, int threads) {
    cell_ = std::max(cell, kMinCell);
    inverse_ = 1.0f / cell_;
    large_.clear();
    largeSpheres_.clear();
    std::size_t total = 0;
    for (const Source& s : sources) total += s.spheres->size();
    // Buckets: a power of two, at least a quarter as many as triangles (a cell in use holds
    // several quads, so buckets still outnumber such cells), which keeps the bucket arrays that
    // every build counts and sums small: on the soft-avoidance benchmark canopy the grid builds
    // take 66 M instructions (77 M with at least one bucket per triangle), the queries 1 M more.
    int bits = 6;
    while ((std::size_t(1) << bits) < total / 4 && bits < 30) ++bits;
    shift_ = 64 - bits;
    const std::size_t buckets = std::size_t(1) << bits;
    // A counting sort by bucket, stable in the sources' order: the sources are cut into as many
    // runs as threads, of about equal triangle counts; each thread counts its run's
    // triangles per bucket, the bucket starts and each run's place within each bucket follow,
    // and each thread copies its run's triangles into place. Any number of threads makes the
    // same grid. Large quads go aside.
    const int runs = std::max(1, std::min<int>(threads, int(sources.size())));
    std::vector<std::size_t> cut(std::size_t(runs) + 1, sources.size());
    cut[0] = 0;
    for (std::size_t i = 0, seen = 0, r = 1; i < sources.size() && r < std::size_t(runs); ++i) {
        seen += sources[i].spheres->size();
        while (r < std::size_t(runs) && seen * std::size_t(runs) >= r * total) cut[r++] = i + 1;
    }
    counts_.resize(std::size_t(runs));
    struct Aside {
        std::vector<SoftTriangle> quads;
        std::vector<glm::vec4> spheres;
        float maxRadius = 0.0f;
    };
    std::vector<Aside> aside(static_cast<std::size_t>(runs));
    for (auto& c : counts_) resizeOver(c, buckets);
    auto forRuns = [&](auto&& f) {
        ParallelErrors errors;
#pragma omp parallel for schedule(static, 1) num_threads(runs) if (runs > 1 && !omp_in_parallel())
        for (int r = 0; r < runs; ++r) errors.run(r, [&] { f(std::size_t(r)); });
        errors.rethrow();
    };
    forRuns([&](std::size_t r) {  // count (a triangle starts a quad when the next is its second)
        std::uint32_t* count = counts_[r].data();
        std::fill_n(count, buckets, 0u);
        Aside& mine = aside[r];
        for (std::size_t i = cut[r]; i < cut[r + 1]; ++i) {
            const Source& s = sources[i];
            const std::uint64_t* keys = s.keys->data();
            const glm::vec4* spheres = s.spheres->data();
            const std::size_t size = s.keys->size();
            for (std::size_t t = 0; t < size; ++t) {
                const std::uint64_t key = keys[t];
                if (key == kSecond) continue;
                if (key == kLarge) {
                    const bool quad = t + 1 < size && keys[t + 1] == kSecond;
                    mine.quads.push_back(
                        {s.soup->data() + 3 * t, s.owner, quad, s.tags ? (*s.tags)[t] : 0});
                    mine.spheres.push_back(spheres[t]);
                    continue;
                }
                mine.maxRadius = std::max(mine.maxRadius, spheres[t].w);
                ++count[bucketOf(key)];
            }
        }
    });
    // Bucket b: [start_[b], start_[b + 1]); run r's triangles of it from counts_[r][b] on.
    float maxRadius = 0.0f;
    for (Aside& mine : aside) {
        large_.insert(large_.end(), mine.quads.begin(), mine.quads.end());
        largeSpheres_.insert(largeSpheres_.end(), mine.spheres.begin(), mine.spheres.end());
        maxRadius = std::max(maxRadius, mine.maxRadius);
    }
    maxRadius_ = maxRadius;
    resizeOver(start_, buckets + 1);
    std::uint32_t* start = start_.data();
    std::uint32_t sum = 0;
    if (runs == 1) {  // (the loop over runs below costs 11 M more instructions a canopy)
        std::uint32_t* count = counts_[0].data();
        for (std::size_t b = 0; b < buckets; ++b) {
            start[b] = sum;
            sum += count[b];
            count[b] = start[b];
        }
    } else {
        std::vector<std::uint32_t*> count;
        for (auto& c : counts_) count.push_back(c.data());
        for (std::size_t b = 0; b < buckets; ++b) {
            start[b] = sum;
            for (std::uint32_t* c : count) {
                const std::uint32_t n = c[b];
                c[b] = sum;
                sum += n;
            }
        }
    }
    start[buckets] = sum;
    const std::size_t n = sum;
    resizeOver(small_, n);
    resizeOver(corners_, 4 * n);
    // Padded with a key no cell has and far-away spheres (so tests go four at a time).
    resizeOver(keys_, n + 4);
    std::fill_n(keys_.data() + n, 4, kLarge);
    for (int r = 0; r < 4; ++r) {
        resizeOver(sphereRows_[r], n + 4);
        std::fill_n(sphereRows_[r].data() + n, 4, r < 3 ? 1e30f : 0.0f);
    }
    SoftTriangle* small = small_.data();
    vec3* corners = corners_.data();
    std::uint64_t* sortedKeys = keys_.data();
    float* rows[4] = {sphereRows_[0].data(), sphereRows_[1].data(), sphereRows_[2].data(),
                      sphereRows_[3].data()};
    forRuns([&](std::size_t r) {  // copy into place
        std::uint32_t* fill = counts_[r].data();
        for (std::size_t i = cut[r]; i < cut[r + 1]; ++i) {
            const Source& s = sources[i];
            const std::uint64_t* keys = s.keys->data();
            const glm::vec4* spheres = s.spheres->data();
            const std::uint64_t* tags = s.tags ? s.tags->data() : nullptr;
            const vec3* soup = s.soup->data();
            const std::size_t size = s.keys->size();
            for (std::size_t t = 0; t < size; ++t) {
                const std::uint64_t key = keys[t];
                if (key == kLarge || key == kSecond) continue;
                const std::uint32_t at = fill[bucketOf(key)]++;
                const vec3* p = soup + 3 * t;
                const bool quad = t + 1 < size && keys[t + 1] == kSecond;
                small[at] = {p, s.owner, quad, tags ? tags[t] : 0};
                vec3* c = corners + 4 * std::size_t(at);
                c[0] = p[0];
                c[1] = p[1];
                c[2] = p[2];
                c[3] = quad ? p[5] : p[2];
                sortedKeys[at] = key;
                const glm::vec4 sphere = spheres[t];
                rows[0][at] = sphere.x;
                rows[1][at] = sphere.y;
                rows[2][at] = sphere.z;
                rows[3][at] = sphere.w;
            }
        }
    });
}

void SoftGrid::near(vec3 centre, float radius, const Ignore* ignore, TriangleBatch& out,
                    const vec3* front) const {
    const vec3 facing = front ? *front : vec3(0.0f);
    const float behind = front ? 0.0f : 1.0f;  // with no plane, nothing is behind it
    auto reaches = [&](const glm::vec4& s) {
        const vec3 d = vec3(s) - centre;
        const float r = radius + s.w;
        return glm::dot(d, d) <= r * r && glm::dot(d, facing) + s.w + behind >= 0.0f;
    };
    for (std::size_t i = 0; i < large_.size(); ++i)
        if (reaches(largeSpheres_[i]) && !ignored(large_[i], ignore)) {
            const SoftTriangle& q = large_[i];
            const vec3 corners[4] = {q.corners[0], q.corners[1], q.corners[2], q.last()};
            out.push(corners);
        }
    if (small_.empty()) return;
    // Cells holding sphere centres within radius + the largest small sphere.
    // Which of the four small triangles from i on reach the sphere (bit k: triangle i + k); the
    // same arithmetic as `reaches`, four lanes at a time.
    typedef float Float4 __attribute__((vector_size(16)));
    typedef std::int32_t Int4 __attribute__((vector_size(16)));
    auto load = [](const std::vector<float>& row, std::uint32_t i) {
        Float4 v;
        std::memcpy(&v, row.data() + i, sizeof v);
        return v;
    };
    auto test4 = [&](std::uint32_t i) {
        const Float4 dx = load(sphereRows_[0], i) - centre.x,
                     dy = load(sphereRows_[1], i) - centre.y,
                     dz = load(sphereRows_[2], i) - centre.z, w = load(sphereRows_[3], i);
        const Float4 r = radius + w;
        const Int4 in = (dx * dx + dy * dy + dz * dz <= r * r) &
                        (dx * facing.x + dy * facing.y + dz * facing.z + w + behind >= 0.0f);
#if defined(__SSE__)
        return unsigned(_mm_movemask_ps(reinterpret_cast<__m128>(in)));
#else
        return unsigned((in[0] & 1) | (in[1] & 2) | (in[2] & 4) | (in[3] & 8));
#endif
    };
    const unsigned ignoredOwner = ignore ? ignore->plant + 1 : 0u;  // owner 0: no plant
    const std::uint64_t ignoredTags[2] = {ignore ? ignore->organs[0] : 0,
                                          ignore ? ignore->organs[1] : 0};
    // (A margin of a thousandth of a cell covers rounding at cell borders.)
    const float reach = radius + maxRadius_ + 1e-3f * cell_;
    const std::int64_t x0 = cellIndex(centre.x - reach, inverse_),
                       x1 = cellIndex(centre.x + reach, inverse_);
    const std::int64_t y0 = cellIndex(centre.y - reach, inverse_),
                       y1 = cellIndex(centre.y + reach, inverse_);
    const std::int64_t z0 = cellIndex(centre.z - reach, inverse_),
                       z1 = cellIndex(centre.z + reach, inverse_);
    const float reach2 = reach * reach;
    // A cell is wholly behind the plane when its farthest point in front of it, plus the
    // largest sphere, still lies behind.
    const float halfCell = 0.5f * cell_;
    const float cellFront =
        halfCell * (std::abs(facing.x) + std::abs(facing.y) + std::abs(facing.z)) + reach - radius +
        behind;
    for (std::int64_t x = x0; x <= x1; ++x) {
        const float dx =
            std::max({0.0f, float(x) * cell_ - centre.x, centre.x - float(x + 1) * cell_});
        const float fx = (float(x) * cell_ + halfCell - centre.x) * facing.x;
        for (std::int64_t y = y0; y <= y1; ++y) {
            const float dy =
                std::max({0.0f, float(y) * cell_ - centre.y, centre.y - float(y + 1) * cell_});
            if (dx * dx + dy * dy > reach2) continue;
            const float fxy = fx + (float(y) * cell_ + halfCell - centre.y) * facing.y;
            for (std::int64_t z = z0; z <= z1; ++z) {
                const float dz =
                    std::max({0.0f, float(z) * cell_ - centre.z, centre.z - float(z + 1) * cell_});
                if (dx * dx + dy * dy + dz * dz > reach2) continue;
                if (fxy + (float(z) * cell_ + halfCell - centre.z) * facing.z + cellFront < 0.0f)
                    continue;
                const std::uint64_t key = pack(x, y, z);
                const std::size_t b = bucketOf(key);
                // A bucket may also hold other cells (hashing): their keys differ.
                for (std::uint32_t i = start_[b], end = start_[b + 1]; i < end; i += 4) {
                    const unsigned same =
                        unsigned(keys_[i] == key) | unsigned(keys_[i + 1] == key) << 1 |
                        unsigned(keys_[i + 2] == key) << 2 | unsigned(keys_[i + 3] == key) << 3;
                    if (!same) continue;
                    unsigned hits = test4(i) & same;
                    if (end - i < 4) hits &= (1u << (end - i)) - 1u;
                    for (; hits; hits &= hits - 1) {
                        const std::uint32_t k = i + std::uint32_t(__builtin_ctz(hits));
                        const SoftTriangle& t = small_[k];
                        if (t.owner != ignoredOwner ||
                            (t.tag != ignoredTags[0] && t.tag != ignoredTags[1]))
                            out.push(corners_.data() + 4 * std::size_t(k));
                    }
                }
            }
        }
    }
}

}  // namespace plantarch::collision
