// Organ proxies and overlap tests (see proxies.h).

#include "collision/proxies.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace plantarch::collision {

namespace {

// Stations along a leaf blade at which its width is measured.
constexpr int kStations = 8;

// The blade as a rhombus of 2 triangles: from the middle of its base, to both edges at its
// widest station, to the middle of its tip; heights are the mean z of the vertices there
// (curvature).
TriangleSoup bladeOutline(const OrganPrototype& proto, const AABB& bounds) {
    TriangleSoup out;
    const float x0 = bounds.min.x, x1 = bounds.max.x;
    if (!(x1 > x0)) return out;
    struct Station {
        float ymin = 1e30f, ymax = -1e30f, zsum = 0.0f;
        int n = 0;
        float width() const { return n ? ymax - ymin : -1.0f; }
        vec3 at(float x, float y) const { return {x, y, zsum / float(std::max(1, n))}; }
    };
    Station st[kStations + 1];
    const float step = (x1 - x0) / float(kStations);
    for (const PrototypePart& part : proto)
        for (const vec3& p : part.mesh.positions) {
            const int k = std::clamp(int(std::lround((p.x - x0) / step)), 0, kStations);
            st[k].ymin = std::min(st[k].ymin, p.y);
            st[k].ymax = std::max(st[k].ymax, p.y);
            st[k].zsum += p.z;
            st[k].n++;
        }
    int widest = -1;
    for (int k = 1; k < kStations; ++k)
        if (st[k].n && (widest < 0 || st[k].width() > st[widest].width())) widest = k;
    int base = 0, tip = kStations;
    while (base < kStations && !st[base].n) ++base;
    while (tip > 0 && !st[tip].n) --tip;
    if (widest < 0 || base >= widest || tip <= widest || !(st[widest].width() > 0.0f)) return out;
    const Station& b = st[base];
    const Station& w = st[widest];
    const Station& t = st[tip];
    const vec3 B = b.at(x0 + step * float(base), 0.5f * (b.ymin + b.ymax));
    const vec3 T = t.at(x0 + step * float(tip), 0.5f * (t.ymin + t.ymax));
    const vec3 L = w.at(x0 + step * float(widest), w.ymin);
    const vec3 R = w.at(x0 + step * float(widest), w.ymax);
    out.insert(out.end(), {B, R, T, B, T, L});
    return out;
}

TriangleSoup boxTriangles(const AABB& b) {
    vec3 c[8];
    for (int i = 0; i < 8; ++i)
        c[i] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                (i & 4) ? b.max.z : b.min.z};
    static const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                     {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                     {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    TriangleSoup out;
    for (const auto& f : faces) out.insert(out.end(), {c[f[0]], c[f[1]], c[f[2]]});
    return out;
}

void appendTransformed(const TriangleSoup& local, const mat4& xf, TriangleSoup& out) {
    for (const vec3& p : local) out.push_back(vec3(xf * glm::vec4(p, 1.0f)));
}

}  // namespace

const PrototypeShape& ProxyCache::shape(const OrganPrototype& proto) {
    auto it = shapes_.find(&proto);
    if (it != shapes_.end()) return it->second;
    PrototypeShape s;
    for (const PrototypePart& part : proto)
        for (const vec3& p : part.mesh.positions) s.bounds.add(p);
    if (!s.bounds.empty()) {
        s.outline = bladeOutline(proto, s.bounds);
        s.box = boxTriangles(s.bounds);
    }
    return shapes_.emplace(&proto, std::move(s)).first->second;
}

ProxyCache& proxyCache(CollisionState& state) {
    if (!state.proxies) state.proxies = std::make_shared<ProxyCache>();
    return *state.proxies;
}

// ---- proxies ---------------------------------------------------------------------------

namespace {

// Everything that shapes a petiole and its leaves relative to the petiole's start.
PlantProxyMemo::Key petioleKey(const Phytomer& ph, const Petiole& pt) {
    const Internode& in = ph.internode;
    PlantProxyMemo::Key key{};
    std::size_t k = 0;
    for (const vec3* v : {&in.direction, &in.guide, &in.rollReference, &pt.clearance.axis}) {
        key[k++] = v->x;
        key[k++] = v->y;
        key[k++] = v->z;
    }
    for (float v :
         {pt.pitch, pt.azimuth, pt.length, pt.curvature, pt.clearance.angle, ph.leafFraction})
        key[k++] = v;
    // Which leaves have fallen: one bit each (leaf i and i + 32 share a bit: a change to both
    // at once between two refreshes is as good as impossible, and only costs a stale proxy).
    std::uint32_t fallen = 0;
    for (std::size_t i = 0; i < pt.leaves.size(); ++i)
        if (pt.leaves[i].removed) fallen ^= std::uint32_t(1) << (i % 32);
    const std::uint32_t count = std::uint32_t(pt.leaves.size());
    std::memcpy(&key[k++], &fallen, sizeof fallen);
    std::memcpy(&key[k++], &count, sizeof count);
    return key;
}

bool sameBits(const vec3& a, const vec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// The outlines of the prototypes met last (a plant's leaves share a few), kept in the memo
// within its epoch.
class OutlineLookup {
public:
    OutlineLookup(ProxyCache& cache, PlantProxyMemo& memo) : cache_(cache), table_(memo.outlines) {
        if (memo.epoch == 0 || memo.outlinesEpoch != memo.epoch) {
            table_.fill({nullptr, nullptr});
            memo.outlinesEpoch = memo.epoch;
        }
    }
    const TriangleSoup& operator()(const OrganPrototype& proto) {
        // A multiplicative hash: prototypes are aligned, their low bits all alike.
        const std::size_t slot = std::size_t(
            (std::uint64_t(reinterpret_cast<std::uintptr_t>(&proto)) * 0x9e3779b97f4a7c15ULL) >>
            59);
        auto& [p, outline] = table_[slot];
        if (p != &proto) {
            p = &proto;
            outline = &cache_.shape(proto).outline;
        }
        return *outline;
    }

private:
    ProxyCache& cache_;
    std::array<std::pair<const OrganPrototype*, const TriangleSoup*>, 32>& table_;
};

// SSE intrinsics kept in placeOutline and moveBy: the plain forms give the same bytes but cost
// more (instructions of bench/callgrind/soft_canopy.cpp soft, one thread, in buildProxies,
// 102 M with these): placeOutline on glm::vec4 columns 27 M more, moveBy as a plain loop 2.5 M
// more (as twelve-float blocks, 6 M more).
//
// The points of a prototype's outline placed by `xf`, less `start`, into `out`: to the bit
// as vec3(xf * vec4(p, 1)) - start (glm's product: (x c0 + y c1) + (z c2 + c3), the same
// operations in the same order, four lanes at once where SSE is at hand).
void placeOutline(const mat4& xf, const TriangleSoup& outline, vec3 start, vec3* out) {
#if defined(__SSE2__)
    const __m128 c0 = _mm_loadu_ps(&xf[0][0]), c1 = _mm_loadu_ps(&xf[1][0]);
    const __m128 c2 = _mm_loadu_ps(&xf[2][0]), c3 = _mm_loadu_ps(&xf[3][0]);
    const __m128 s = _mm_setr_ps(start.x, start.y, start.z, 0.0f);
    for (const vec3& p : outline) {
        const __m128 r = _mm_sub_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, _mm_set1_ps(p.x)),
                                                          _mm_mul_ps(c1, _mm_set1_ps(p.y))),
                                               _mm_add_ps(_mm_mul_ps(c2, _mm_set1_ps(p.z)), c3)),
                                    s);
        if (&p + 1 != outline.data() + outline.size()) {
            _mm_storeu_ps(&out->x, r);  // its fourth lane goes where the next point will
        } else {
            alignas(16) float v[4];
            _mm_store_ps(v, r);
            *out = vec3(v[0], v[1], v[2]);
        }
        ++out;
    }
#else
    for (const vec3& p : outline)
        *out++ =
            (vec3(xf[0]) * p.x + vec3(xf[1]) * p.y) + (vec3(xf[2]) * p.z + vec3(xf[3])) - start;
#endif
}

// out[i] = local[i] + start for i < n (four points, twelve floats, at a time where SSE is at
// hand: the same additions).
void moveBy(const vec3* local, std::size_t n, vec3 start, vec3* out) {
    std::size_t i = 0;
#if defined(__SSE2__)
    const __m128 s0 = _mm_setr_ps(start.x, start.y, start.z, start.x);
    const __m128 s1 = _mm_setr_ps(start.y, start.z, start.x, start.y);
    const __m128 s2 = _mm_setr_ps(start.z, start.x, start.y, start.z);
    for (; i + 4 <= n; i += 4) {
        const float* in = &local[i].x;
        float* to = &out[i].x;
        _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(in), s0));
        _mm_storeu_ps(to + 4, _mm_add_ps(_mm_loadu_ps(in + 4), s1));
        _mm_storeu_ps(to + 8, _mm_add_ps(_mm_loadu_ps(in + 8), s2));
    }
    if (i + 2 <= n) {  // two more (six floats: four, then two)
        const float* in = &local[i].x;
        float* to = &out[i].x;
        _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(in), s0));
        // (Eight bytes at a time through the unaligned 64-bit moves: floats are only 4-aligned.)
        const __m128 yz =
            _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(in + 4)));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(to + 4), _mm_castps_si128(_mm_add_ps(yz, s1)));
        i += 2;
    }
    if (i < n) out[i] = local[i] + start;
#else
    for (; i < n; ++i) out[i] = local[i] + start;
#endif
}

// Drops from `data` what no petiole uses once it is as much as they use (and more than
// `slack`): each petiole's run [first, first + count) moves down in petiole order.
template <class T>
void compactRuns(std::vector<T>& data, std::size_t& unused, std::size_t slack,
                 std::vector<PlantProxyMemo::Petiole>& petioles,
                 std::uint32_t PlantProxyMemo::Petiole::*first,
                 std::uint32_t PlantProxyMemo::Petiole::*count) {
    if (unused <= slack || 2 * unused <= data.size()) return;
    std::vector<T> kept;
    kept.reserve(data.size() - unused);
    for (PlantProxyMemo::Petiole& e : petioles) {
        const std::uint32_t at = std::uint32_t(kept.size());
        kept.insert(kept.end(), data.begin() + (e.*first), data.begin() + (e.*first) + (e.*count));
        e.*first = at;
    }
    data = std::move(kept);
    unused = 0;
}

// Drops what no petiole of the shoot uses from its arrays once it is as much as they use.
void compact(PlantProxyMemo::Shoot& m) {
    using P = PlantProxyMemo::Petiole;
    compactRuns(m.local, m.unusedCorners, 64, m.petioles, &P::first, &P::corners);
    compactRuns(m.leafTrig, m.unusedLeaves, 16, m.petioles, &P::leafFirst, &P::leaves);
}

// Drops the shoot's petioles of nodes `node` on.
void truncate(PlantProxyMemo::Shoot& m, std::size_t node) {
    if (node + 1 >= m.nodeFirst.size()) return;
    const std::uint32_t keep = m.nodeFirst[node];
    for (std::size_t i = keep; i < m.petioles.size(); ++i) {
        m.unusedCorners += m.petioles[i].corners;
        m.unusedLeaves += m.petioles[i].leaves;
    }
    m.petioles.resize(keep);
    m.trig.resize(keep);
    m.nodeFirst.resize(node + 1);
}

// The leaf proxies of a plant: each petiole's leaves placed again where anything that shapes
// them changed (OrganPlacer::leaves, the tessellator's own formulas), else moved with the
// petiole's start. `out` and `tags` are overwritten (their storage reused).
bool buildLeafProxies(const Worker& worker, PlantInstance& plant, PlantProxyMemo& memo,
                      TriangleSoup& out, std::vector<OrganTag>& tags) {
    OrganPlacer placer(worker.store, worker.prototypes, plant);
    OutlineLookup outlineOf(worker.proxies, memo);
    const std::uint32_t visit = ++memo.visit;
    std::size_t visited = 0, n = 0;
    memo.runs.clear();
    bool changed = visit == 1;  // a new memo: the scene may hold anything for the plant
    if (memo.shoots.size() < plant.shoots.size()) memo.shoots.resize(plant.shoots.size());
    for (const Shoot& s : plant.shoots) {
        if (s.removed) continue;
        PlantProxyMemo::Shoot& m = memo.shoots[s.id];
        compact(m);
        truncate(m, s.phytomers.size());  // nodes pruned
        for (unsigned k = 0; k < s.phytomers.size(); ++k) {
            const Phytomer& ph = s.phytomers[k];
            const std::uint32_t count = std::uint32_t(ph.petioles.size());
            if (k + 1 < m.nodeFirst.size() && m.nodeFirst[k + 1] - m.nodeFirst[k] != count)
                truncate(m, k);  // the node's petioles changed: it and the nodes above anew
            if (k + 1 == m.nodeFirst.size()) {  // a node new to the memo
                m.nodeFirst.push_back(m.nodeFirst[k] + count);
                m.petioles.resize(m.nodeFirst.back());
                m.trig.resize(m.nodeFirst.back());
            }
            for (unsigned j = 0; j < count; ++j) {
                const std::size_t index = m.nodeFirst[k] + j;
                PlantProxyMemo::Petiole& e = m.petioles[index];
                const Petiole& pt = ph.petioles[j];
                const PlantProxyMemo::Key key = petioleKey(ph, pt);
                ++visited;
                if (e.visit + 1 != visit) changed = true;  // not read at the last refresh
                e.visit = visit;
                vec3 start;
                if (!e.set || std::memcmp(e.key.data(), key.data(), sizeof key) != 0) {
                    if (e.leaves != pt.leaves.size()) {  // room for its leaves' sines
                        m.unusedLeaves += e.leaves;
                        e.leafFirst = std::uint32_t(m.leafTrig.size());
                        e.leaves = std::uint32_t(pt.leaves.size());
                        m.leafTrig.resize(m.leafTrig.size() + e.leaves);
                    }
                    m.trig[index].epoch = memo.epoch;
                    start = placer.leaves(s.id, k, j, m.trig[index],
                                          std::span(m.leafTrig).subspan(e.leafFirst, e.leaves),
                                          memo.leaves, e.side);
                    std::uint32_t corners = 0;
                    memo.leafOutlines.resize(memo.leaves.size());
                    for (std::size_t i = 0; i < memo.leaves.size(); ++i) {
                        const OrganPrototype* proto = memo.leaves[i].prototype;
                        memo.leafOutlines[i] =
                            proto ? &outlineOf(*proto) : nullptr;  // null: fallen or of zero size
                        if (proto) corners += std::uint32_t(memo.leafOutlines[i]->size());
                    }
                    if (corners != e.corners) {  // room for its proxies
                        m.unusedCorners += e.corners;
                        e.first = std::uint32_t(m.local.size());
                        e.corners = corners;
                        m.local.resize(m.local.size() + corners);
                    }
                    vec3* local = m.local.data() + e.first;
                    for (std::size_t i = 0; i < memo.leaves.size(); ++i) {
                        if (!memo.leafOutlines[i]) continue;
                        // As ProxySink::writeParts places the outline.
                        placeOutline(memo.leaves[i].transform, *memo.leafOutlines[i], start, local);
                        local += memo.leafOutlines[i]->size();
                    }
                    e.key = key;
                    e.set = true;
                    changed = true;
                    ++memo.placements;
                } else {
                    start = placer.petioleStartOn(s.id, k, e.side);
                    changed = changed || !sameBits(start, e.start);
                }
                e.start = start;
                memo.runs.push_back({s.id, k, e.first, e.corners, start});
                n += e.corners;
            }
        }
    }
    // The proxies in place, written once all are counted (storage kept: the caller's buffers
    // are reused, and growing them as they fill would zero what is written over).
    out.resize(n);
    tags.resize(n / 3);
    vec3* o = out.data();
    OrganTag* tag = tags.data();
    for (const PlantProxyMemo::Run& r : memo.runs) {
        moveBy(memo.shoots[r.shoot].local.data() + r.first, r.corners, r.start, o);
        std::fill_n(tag, r.corners / 3, organTag(r.shoot, r.node));
        o += r.corners;
        tag += r.corners / 3;
    }
    if (visited != memo.visited) changed = true;  // petioles gone
    memo.visited = visited;
    memo.reads += visited;
    return changed;
}

}  // namespace

bool buildProxies(const Worker& worker, PlantInstance& plant, const CollisionOrgans& organs,
                  PlantProxyMemo& memo, TriangleSoup& out, std::vector<OrganTag>& tags) {
    if (organs.leaves && !organs.internodes && !organs.petioles && !organs.flowers && !organs.fruit)
        return buildLeafProxies(worker, plant, memo, out, tags);
    out.clear();
    tags.clear();
    if (organs.internodes || organs.petioles || organs.flowers || organs.fruit) {
        ProxySink sink(worker.proxies, organs, out, tags);
        tessellatePlant(worker.store, worker.prototypes, sink, plant);
    }
    return true;
}

bool ProxySink::wants(OrganKind kind) const {
    switch (kind) {
        case OrganKind::Internode:
            return organs_.internodes;
        case OrganKind::Petiole:
            return organs_.petioles;
        case OrganKind::Leaf:
            return organs_.leaves;
        case OrganKind::Peduncle:
            return organs_.petioles;
        case OrganKind::FlowerClosed:
        case OrganKind::FlowerOpen:
            return organs_.flowers;
        case OrganKind::Fruit:
            return organs_.fruit;
    }
    return false;
}

void ProxySink::write(ObjectID&, const Mesh& mesh, const Material&, const OrganLabels& labels) {
    for (std::uint32_t i : mesh.indices) out_.push_back(mesh.positions[i]);
    tags_.resize(out_.size() / 3, organTag(labels.shoot->id, unsigned(labels.node)));
}

void ProxySink::writeParts(std::vector<ObjectID>&, const OrganPrototype& proto, const mat4& xf,
                           const OrganLabels& labels) {
    if (&proto != lastPrototype_) {  // leaves of a plant mostly share a few prototypes
        lastPrototype_ = &proto;
        lastShape_ = &cache_.shape(proto);
    }
    const PrototypeShape& s = *lastShape_;
    appendTransformed(labels.kind == OrganKind::Leaf ? s.outline : s.box, xf, out_);
    tags_.resize(out_.size() / 3, organTag(labels.shoot->id, unsigned(labels.node)));
}

// ---- overlap tests (separating axes) ---------------------------------------------------

namespace {

// Projections of a point set on an axis.
template <std::size_t N>
void project(const vec3 (&pts)[N], vec3 axis, float& lo, float& hi) {
    lo = hi = glm::dot(pts[0], axis);
    for (std::size_t i = 1; i < N; ++i) {
        const float d = glm::dot(pts[i], axis);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
}

}  // namespace

bool boxTriangleOverlap(const OrientedBox& box, vec3 a, vec3 b, vec3 c, float tol) {
    // In box coordinates the box is [-half, half]; triangle corners relative to the centre.
    const vec3 v[3] = {
        {glm::dot(a - box.center, box.axis[0]), glm::dot(a - box.center, box.axis[1]),
         glm::dot(a - box.center, box.axis[2])},
        {glm::dot(b - box.center, box.axis[0]), glm::dot(b - box.center, box.axis[1]),
         glm::dot(b - box.center, box.axis[2])},
        {glm::dot(c - box.center, box.axis[0]), glm::dot(c - box.center, box.axis[1]),
         glm::dot(c - box.center, box.axis[2])}};
    const vec3 h = box.half;
    auto separated = [&](vec3 axis) {
        const float len = glm::length(axis);
        if (len < 1e-12f) return false;
        axis /= len;
        float lo, hi;
        project(v, axis, lo, hi);
        const float r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
        return lo >= r - tol || hi <= -r + tol;
    };
    for (int i = 0; i < 3; ++i) {
        vec3 e(0.0f);
        e[i] = 1.0f;
        if (separated(e)) return false;
    }
    const vec3 edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    if (separated(glm::cross(edges[0], edges[1]))) return false;
    for (int i = 0; i < 3; ++i)
        for (const vec3& e : edges) {
            vec3 u(0.0f);
            u[i] = 1.0f;
            if (separated(glm::cross(u, e))) return false;
        }
    return true;
}

bool triangleTriangleOverlap(const std::array<vec3, 3>& t, vec3 a, vec3 b, vec3 c, float tol) {
    const vec3 p[3] = {t[0], t[1], t[2]};
    const vec3 q[3] = {a, b, c};
    auto separated = [&](vec3 axis) {
        const float len = glm::length(axis);
        if (len < 1e-12f) return false;
        axis /= len;
        float plo, phi, qlo, qhi;
        project(p, axis, plo, phi);
        project(q, axis, qlo, qhi);
        return plo >= qhi - tol || qlo >= phi - tol;
    };
    const vec3 ep[3] = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};
    const vec3 eq[3] = {q[1] - q[0], q[2] - q[1], q[0] - q[2]};
    if (separated(glm::cross(ep[0], ep[1])) || separated(glm::cross(eq[0], eq[1]))) return false;
    for (const vec3& e : ep)
        for (const vec3& f : eq)
            if (separated(glm::cross(e, f))) return false;
    return true;
}

}  // namespace plantarch::collision
