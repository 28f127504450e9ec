// Polygon utilities and the constrained Delaunay triangulation used for leaf blades.
//
// The triangulation keeps, per triangle, its three vertices (counter-clockwise) and the
// neighbour across each edge (edge i is the one opposite vertex i; -1 on the boundary).
// Boundary edges are never flipped, so Lawson flipping yields the constrained Delaunay
// triangulation, and inserting a point (split + flips) keeps it one.

#include "geometry/polygon_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "plantarch/Error.h"

namespace plantarch::polygon {

namespace {

double cross(dvec2 a, dvec2 b) {
    return a.x * b.y - a.y * b.x;
}
double orient(dvec2 a, dvec2 b, dvec2 c) {
    return cross(b - a, c - a);
}

// Do segments ab and cd share a point?
bool segmentsTouch(dvec2 a, dvec2 b, dvec2 c, dvec2 d) {
    const double d1 = orient(c, d, a), d2 = orient(c, d, b);
    const double d3 = orient(a, b, c), d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    auto onSegment = [](dvec2 p, dvec2 q, dvec2 r) {  // r on pq, given collinear
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) &&
               std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
    };
    return (d1 == 0 && onSegment(c, d, a)) || (d2 == 0 && onSegment(c, d, b)) ||
           (d3 == 0 && onSegment(a, b, c)) || (d4 == 0 && onSegment(a, b, d));
}

void simplifyRange(const std::vector<dvec2>& line, std::size_t first, std::size_t last,
                   double tolerance, std::vector<bool>& keep) {
    // Iterative to bound the stack on long traced contours.
    std::vector<std::pair<std::size_t, std::size_t>> stack{{first, last}};
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        double worst = -1.0;
        std::size_t worstIndex = a;
        for (std::size_t i = a + 1; i < b; ++i) {
            const double d = segmentDistance(line[i], line[a], line[b]);
            if (d > worst) {
                worst = d;
                worstIndex = i;
            }
        }
        if (worst > tolerance) {
            keep[worstIndex] = true;
            stack.push_back({a, worstIndex});
            stack.push_back({worstIndex, b});
        }
    }
}

// ---- triangulation state ------------------------------------------------------------------

struct Tri {
    std::array<std::uint32_t, 3> v;
    std::array<int, 3> n;  // neighbour across the edge opposite v[i]
};

class Mesher {
public:
    explicit Mesher(std::vector<dvec2> points) : pts_(std::move(points)) {}

    void earClip(std::size_t count);
    void buildAdjacency();
    void delaunayFlips();
    /// Inserts p; returns false when it coincides with a vertex or lies on the boundary.
    bool insert(dvec2 p);
    /// Splits the boundary edge (a, b) at p (which lies on it).
    void splitBoundaryEdge(std::uint32_t a, std::uint32_t b, dvec2 p);

    /// Delaunay refinement: inserts circumcentres of triangles whose smallest angle is below
    /// `minAngle` (radians), splitting boundary edges they would encroach instead. Triangles
    /// whose small angle sits at a sharp polygon corner are left alone (nothing can fix
    /// them), as are triangles with a circumradius below `minSize` (no cascades into sharp
    /// tips); at most `budget` points are added.
    void refine(const std::vector<dvec2>& poly, double minAngle, double minSize,
                std::size_t budget);

    Triangulation result() const;
    std::size_t pointCount() const { return pts_.size(); }

private:
    dvec2 at(std::uint32_t i) const { return pts_[i]; }
    // Rotates triangle t so that the edge of interest (opposite v[i]) becomes edge 0.
    void rotate(int t, int i);
    void replaceNeighbour(int t, int oldN, int newN);
    bool shouldFlip(int t) const;  // edge 0 of t
    bool flip(int t);              // flips edge 0 of t; false if not allowed
    void legalize(int t);          // edge 0 of t, opposite the new point
    int locate(dvec2 p) const;
    int splitTriangle(int t, dvec2 p);
    void splitEdge(int t, int edge, dvec2 p);

    std::vector<dvec2> pts_;
    std::vector<Tri> tris_;
    mutable int hint_ = 0;
};

void Mesher::earClip(std::size_t count) {
    const std::size_t n = count;
    std::vector<std::size_t> prev(n), next(n);
    for (std::size_t i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    auto convex = [&](std::size_t i) {
        const dvec2 a = pts_[prev[i]], b = pts_[i], c = pts_[next[i]];
        const double scale = glm::length(b - a) * glm::length(c - b);
        return orient(a, b, c) > 1e-12 * scale;
    };
    auto isEar = [&](std::size_t i) {
        if (!convex(i)) return false;
        const dvec2 a = pts_[prev[i]], b = pts_[i], c = pts_[next[i]];
        for (std::size_t j = next[next[i]]; j != prev[i]; j = next[j]) {
            const dvec2 p = pts_[j];
            if (p == a || p == b || p == c) continue;
            if (convex(j)) continue;  // only reflex or flat vertices can block an ear
            if (orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0) return false;
        }
        return true;
    };
    std::size_t remaining = n, i = 0, misses = 0;
    while (remaining > 3) {
        if (isEar(i)) {
            tris_.push_back(
                {{std::uint32_t(prev[i]), std::uint32_t(i), std::uint32_t(next[i])}, {-1, -1, -1}});
            next[prev[i]] = next[i];
            prev[next[i]] = prev[i];
            i = prev[i];
            --remaining;
            misses = 0;
        } else {
            i = next[i];
            if (++misses > remaining) {
                // Round-off left no clean ear: clip the most convex vertex.
                std::size_t best = i;
                double bestValue = -1e300;
                std::size_t j = i;
                for (std::size_t k = 0; k < remaining; ++k, j = next[j]) {
                    const double o = orient(pts_[prev[j]], pts_[j], pts_[next[j]]);
                    if (o > bestValue) {
                        bestValue = o;
                        best = j;
                    }
                }
                if (bestValue <= 0) throw Error("polygon triangulation failed: no convex vertex");
                tris_.push_back(
                    {{std::uint32_t(prev[best]), std::uint32_t(best), std::uint32_t(next[best])},
                     {-1, -1, -1}});
                next[prev[best]] = next[best];
                prev[next[best]] = prev[best];
                i = prev[best];
                --remaining;
                misses = 0;
            }
        }
    }
    tris_.push_back(
        {{std::uint32_t(prev[i]), std::uint32_t(i), std::uint32_t(next[i])}, {-1, -1, -1}});
}

void Mesher::buildAdjacency() {
    // Sort directed edges so that (a, b) and (b, a) meet.
    struct Edge {
        std::uint64_t key;
        int tri;
        int index;
    };
    std::vector<Edge> edges;
    edges.reserve(tris_.size() * 3);
    for (int t = 0; t < int(tris_.size()); ++t)
        for (int i = 0; i < 3; ++i) {
            std::uint32_t a = tris_[t].v[(i + 1) % 3], b = tris_[t].v[(i + 2) % 3];
            if (a > b) std::swap(a, b);
            edges.push_back({(std::uint64_t(a) << 32) | b, t, i});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        return x.key != y.key ? x.key < y.key : x.tri < y.tri;
    });
    for (std::size_t k = 0; k + 1 < edges.size(); ++k)
        if (edges[k].key == edges[k + 1].key) {
            tris_[edges[k].tri].n[edges[k].index] = edges[k + 1].tri;
            tris_[edges[k + 1].tri].n[edges[k + 1].index] = edges[k].tri;
            ++k;
        }
}

void Mesher::rotate(int t, int i) {
    Tri& tri = tris_[t];
    std::rotate(tri.v.begin(), tri.v.begin() + i, tri.v.end());
    std::rotate(tri.n.begin(), tri.n.begin() + i, tri.n.end());
}

void Mesher::replaceNeighbour(int t, int oldN, int newN) {
    if (t < 0) return;
    for (int& n : tris_[t].n)
        if (n == oldN) {
            n = newN;
            return;
        }
}

// Delaunay criterion on angles (scale-free): flip when the two angles opposite the shared
// edge sum to more than pi.
bool Mesher::shouldFlip(int t) const {
    const Tri& tri = tris_[t];
    const int u = tri.n[0];
    if (u < 0) return false;
    const Tri& other = tris_[u];
    int j = 0;
    while (j < 3 && other.n[j] != t) ++j;
    if (j == 3) return false;
    const dvec2 c = at(tri.v[0]), a = at(tri.v[1]), b = at(tri.v[2]);
    const dvec2 d = at(other.v[j]);
    auto angle = [](dvec2 apex, dvec2 p, dvec2 q) {
        const dvec2 e = p - apex, f = q - apex;
        return std::atan2(std::abs(cross(e, f)), glm::dot(e, f));
    };
    if (angle(c, a, b) + angle(d, b, a) <= std::numbers::pi + 1e-9) return false;
    // The flipped triangles must keep their orientation (convex quadrilateral).
    const double s = glm::length(d - c);
    return orient(c, a, d) > 1e-12 * s * glm::length(a - c) &&
           orient(c, d, b) > 1e-12 * s * glm::length(b - c);
}

bool Mesher::flip(int t) {
    const int u = tris_[t].n[0];
    int j = 0;
    while (tris_[u].n[j] != t) ++j;
    rotate(u, j);
    // t = (c, a, b), u = (d, b, a)  ->  t = (c, a, d), u = (d, b, c)
    const std::uint32_t c = tris_[t].v[0], a = tris_[t].v[1], b = tris_[t].v[2];
    const std::uint32_t d = tris_[u].v[0];
    const int ntA = tris_[t].n[1], ntB = tris_[t].n[2];  // across (b,c) and (c,a)
    const int nuB = tris_[u].n[1], nuA = tris_[u].n[2];  // across (a,d) and (d,b)
    tris_[t] = {{c, a, d}, {nuB, u, ntB}};
    tris_[u] = {{d, b, c}, {ntA, t, nuA}};
    replaceNeighbour(nuB, u, t);
    replaceNeighbour(ntA, t, u);
    return true;
}

void Mesher::delaunayFlips() {
    for (int pass = 0; pass < 10000; ++pass) {
        bool changed = false;
        for (int t = 0; t < int(tris_.size()); ++t)
            for (int i = 0; i < 3; ++i) {
                if (shouldFlip(t)) {
                    flip(t);
                    changed = true;
                }
                rotate(t, 1);  // next edge
            }
        if (!changed) return;
    }
}

void Mesher::legalize(int t) {
    // Iterative: a stack of triangles whose edge 0 (opposite the new point) needs checking.
    std::vector<int> stack{t};
    const std::uint32_t p = tris_[t].v[0];
    while (!stack.empty()) {
        const int s = stack.back();
        stack.pop_back();
        int i = 0;
        while (i < 3 && tris_[s].v[i] != p) ++i;
        if (i == 3) continue;
        rotate(s, i);
        if (!shouldFlip(s)) continue;
        const int u = tris_[s].n[0];
        flip(s);
        // s = (p, a, d), u = (d, b, p): both new edges opposite p need checking.
        stack.push_back(s);
        stack.push_back(u);
    }
}

int Mesher::locate(dvec2 p) const {
    auto inside = [&](int t, int& exitEdge) {
        const Tri& tri = tris_[t];
        for (int i = 0; i < 3; ++i) {
            const dvec2 a = at(tri.v[(i + 1) % 3]), b = at(tri.v[(i + 2) % 3]);
            if (orient(a, b, p) < -1e-12 * glm::length(b - a)) {
                exitEdge = i;
                return false;
            }
        }
        return true;
    };
    int t = std::min(hint_, int(tris_.size()) - 1);
    for (std::size_t steps = 0; steps < tris_.size(); ++steps) {
        int e = -1;
        if (inside(t, e)) return hint_ = t;
        const int next = tris_[t].n[e];
        if (next < 0) break;  // the walk left the polygon: search everything
        t = next;
    }
    for (int s = 0; s < int(tris_.size()); ++s) {
        int e = -1;
        if (inside(s, e)) return hint_ = s;
    }
    return -1;
}

int Mesher::splitTriangle(int t, dvec2 p) {
    const std::uint32_t pi = std::uint32_t(pts_.size());
    pts_.push_back(p);
    const Tri old = tris_[t];
    const int t1 = int(tris_.size()), t2 = t1 + 1;
    // t = (p, v1, v2), t1 = (p, v2, v0), t2 = (p, v0, v1)
    tris_[t] = {{pi, old.v[1], old.v[2]}, {old.n[0], t1, t2}};
    tris_.push_back({{pi, old.v[2], old.v[0]}, {old.n[1], t2, t}});
    tris_.push_back({{pi, old.v[0], old.v[1]}, {old.n[2], t, t1}});
    replaceNeighbour(old.n[1], t, t1);
    replaceNeighbour(old.n[2], t, t2);
    legalize(t);
    legalize(t1);
    legalize(t2);
    return int(pi);
}

void Mesher::splitEdge(int t, int edge, dvec2 p) {
    rotate(t, edge);
    const std::uint32_t pi = std::uint32_t(pts_.size());
    pts_.push_back(p);
    const Tri old = tris_[t];  // (c, a, b), edge (a, b)
    const std::uint32_t c = old.v[0], a = old.v[1], b = old.v[2];
    const int u = old.n[0];
    const int t2 = int(tris_.size());
    // t = (p, c, a), t2 = (p, b, c)
    tris_[t] = {{pi, c, a}, {old.n[2], -1, t2}};
    tris_.push_back({{pi, b, c}, {old.n[1], t, -1}});
    replaceNeighbour(old.n[1], t, t2);
    if (u >= 0) {
        int j = 0;
        while (tris_[u].n[j] != t) ++j;
        rotate(u, j);
        const Tri ou = tris_[u];  // (d, b, a)
        const std::uint32_t d = ou.v[0];
        const int u2 = int(tris_.size());
        // u = (p, a, d), u2 = (p, d, b)
        tris_[u] = {{pi, a, d}, {ou.n[1], u2, t}};
        tris_.push_back({{pi, d, b}, {ou.n[2], t2, u}});
        replaceNeighbour(ou.n[2], u, u2);
        tris_[t].n[1] = u;
        tris_[t2].n[2] = u2;
        legalize(u);
        legalize(u2);
    }
    legalize(t);
    legalize(t2);
}

bool Mesher::insert(dvec2 p) {
    const int t = locate(p);
    if (t < 0) return false;
    const Tri& tri = tris_[t];
    for (int i = 0; i < 3; ++i)
        if (glm::length(at(tri.v[i]) - p) < 1e-9) return false;
    for (int i = 0; i < 3; ++i) {
        const dvec2 a = at(tri.v[(i + 1) % 3]), b = at(tri.v[(i + 2) % 3]);
        if (std::abs(orient(a, b, p)) <= 1e-9 * glm::length(b - a)) {
            if (tri.n[i] < 0) return false;  // on the boundary: leave the outline alone
            splitEdge(t, i, p);
            return true;
        }
    }
    splitTriangle(t, p);
    return true;
}

void Mesher::splitBoundaryEdge(std::uint32_t a, std::uint32_t b, dvec2 p) {
    for (int t = 0; t < int(tris_.size()); ++t)
        for (int i = 0; i < 3; ++i)
            if (tris_[t].n[i] < 0 && tris_[t].v[(i + 1) % 3] == a && tris_[t].v[(i + 2) % 3] == b) {
                splitEdge(t, i, p);
                return;
            }
}

void Mesher::refine(const std::vector<dvec2>& poly, double minAngle, double minSize,
                    std::size_t budget) {
    const std::size_t corners = poly.size();
    std::vector<double> cornerAngle(corners);
    for (std::size_t i = 0; i < corners; ++i) {
        const dvec2 a = poly[(i + corners - 1) % corners] - poly[i];
        const dvec2 b = poly[(i + 1) % corners] - poly[i];
        double angle = std::atan2(cross(b, a), glm::dot(b, a));
        if (angle < 0) angle += 2.0 * std::numbers::pi;
        cornerAngle[i] = angle;
    }
    auto angleAt = [&](dvec2 apex, dvec2 p, dvec2 q) {
        const dvec2 e = p - apex, f = q - apex;
        return std::atan2(std::abs(cross(e, f)), glm::dot(e, f));
    };
    auto sorted = [](std::array<std::uint32_t, 3> v) {
        std::sort(v.begin(), v.end());
        return v;
    };
    // A boundary edge of triangle t (or of its neighbours) whose diametral circle holds p.
    auto encroached = [&](int t, dvec2 p, int& edgeT, int& edgeI) {
        std::array<int, 4> near{t, tris_[t].n[0], tris_[t].n[1], tris_[t].n[2]};
        for (int u : near) {
            if (u < 0) continue;
            for (int i = 0; i < 3; ++i) {
                if (tris_[u].n[i] >= 0) continue;
                const dvec2 a = pts_[tris_[u].v[(i + 1) % 3]], b = pts_[tris_[u].v[(i + 2) % 3]];
                if (glm::length(p - 0.5 * (a + b)) < 0.5 * glm::length(b - a)) {
                    edgeT = u, edgeI = i;
                    return true;
                }
            }
        }
        return false;
    };
    std::vector<std::array<std::uint32_t, 3>> skipped;  // sorted, kept sorted
    std::size_t added = 0;
    for (int pass = 0; pass < 64 && added < budget; ++pass) {
        // Bad triangles that refinement can improve, worst first.
        struct Bad {
            double angle;
            int tri;
            std::array<std::uint32_t, 3> v;
        };
        std::vector<Bad> bad;
        for (int t = 0; t < int(tris_.size()); ++t) {
            const auto& v = tris_[t].v;
            double smallest = 1e9;
            int at = 0;
            for (int k = 0; k < 3; ++k) {
                const double a = angleAt(pts_[v[k]], pts_[v[(k + 1) % 3]], pts_[v[(k + 2) % 3]]);
                if (a < smallest) smallest = a, at = k;
            }
            if (smallest >= minAngle) continue;
            if (v[at] < corners && cornerAngle[v[at]] < 3.0 * minAngle) continue;
            if (std::binary_search(skipped.begin(), skipped.end(), sorted(v))) continue;
            bad.push_back({smallest, t, v});
        }
        if (bad.empty()) return;
        std::sort(bad.begin(), bad.end(),
                  [](const Bad& x, const Bad& y) { return x.angle < y.angle; });
        auto skip = [&](const std::array<std::uint32_t, 3>& v) {
            const auto key = sorted(v);
            skipped.insert(std::upper_bound(skipped.begin(), skipped.end(), key), key);
        };
        for (const Bad& b : bad) {
            if (added >= budget) return;
            if (b.tri >= int(tris_.size()) || sorted(tris_[b.tri].v) != sorted(b.v)) continue;
            const dvec2 a = pts_[b.v[0]], p1 = pts_[b.v[1]], p2 = pts_[b.v[2]];
            const dvec2 ab = p1 - a, ac = p2 - a;
            const double d = 2.0 * cross(ab, ac);
            const dvec2 centre = a + dvec2(ac.y * glm::dot(ab, ab) - ab.y * glm::dot(ac, ac),
                                           ab.x * glm::dot(ac, ac) - ac.x * glm::dot(ab, ab)) /
                                         d;
            if (glm::length(centre - a) < minSize) {
                skip(b.v);
                continue;
            }
            // Walk toward the centre; a boundary edge in the way is split instead.
            int cur = b.tri, edgeT = -1, edgeI = -1;
            for (std::size_t steps = 0; steps < tris_.size(); ++steps) {
                int exit = -1;
                for (int i = 0; i < 3 && exit < 0; ++i) {
                    const dvec2 e0 = pts_[tris_[cur].v[(i + 1) % 3]],
                                e1 = pts_[tris_[cur].v[(i + 2) % 3]];
                    if (orient(e0, e1, centre) < -1e-12 * glm::length(e1 - e0)) exit = i;
                }
                if (exit < 0) break;
                if (tris_[cur].n[exit] < 0) {
                    edgeT = cur, edgeI = exit;
                    break;
                }
                cur = tris_[cur].n[exit];
            }
            if (edgeT < 0) encroached(cur, centre, edgeT, edgeI);
            if (edgeT >= 0) {
                const dvec2 e0 = pts_[tris_[edgeT].v[(edgeI + 1) % 3]];
                const dvec2 e1 = pts_[tris_[edgeT].v[(edgeI + 2) % 3]];
                if (glm::length(e1 - e0) < 2.0 * minSize) {
                    skip(b.v);
                    continue;
                }
                splitEdge(edgeT, edgeI, 0.5 * (e0 + e1));
                ++added;
                continue;
            }
            hint_ = cur;
            if (!contains(poly, centre) || !insert(centre)) {
                skip(b.v);
                continue;
            }
            ++added;
        }
    }
}

Triangulation Mesher::result() const {
    Triangulation out;
    out.points = pts_;
    out.triangles.reserve(tris_.size());
    for (const Tri& t : tris_) out.triangles.push_back(t.v);
    return out;
}

}  // namespace

// ---- public functions --------------------------------------------------------------------

double signedArea(const std::vector<dvec2>& poly) {
    double sum = 0.0;
    for (std::size_t i = 0, n = poly.size(); i < n; ++i) sum += cross(poly[i], poly[(i + 1) % n]);
    return 0.5 * sum;
}

bool contains(const std::vector<dvec2>& poly, dvec2 p) {
    bool in = false;
    for (std::size_t i = 0, n = poly.size(), j = n - 1; i < n; j = i++) {
        const dvec2 a = poly[i], b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            in = !in;
    }
    return in;
}

double segmentDistance(dvec2 p, dvec2 a, dvec2 b) {
    const dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

double boundaryDistance(const std::vector<dvec2>& poly, dvec2 p) {
    double best = 1e300;
    for (std::size_t i = 0, n = poly.size(); i < n; ++i)
        best = std::min(best, segmentDistance(p, poly[i], poly[(i + 1) % n]));
    return best;
}

bool isSimple(const std::vector<dvec2>& poly) {
    const std::size_t n = poly.size();
    if (n < 3) return false;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            if (poly[i] == poly[j]) return false;
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if (adjacent) continue;
            if (segmentsTouch(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) return false;
        }
    return true;
}

std::vector<dvec2> simplifyPolyline(const std::vector<dvec2>& line, double tolerance,
                                    const std::vector<std::size_t>& forced) {
    if (line.size() < 3) return line;
    std::vector<bool> keep(line.size(), false);
    keep.front() = keep.back() = true;
    std::vector<std::size_t> anchors{0, line.size() - 1};
    for (std::size_t i : forced)
        if (i < line.size()) keep[i] = true, anchors.push_back(i);
    std::sort(anchors.begin(), anchors.end());
    anchors.erase(std::unique(anchors.begin(), anchors.end()), anchors.end());
    for (std::size_t k = 0; k + 1 < anchors.size(); ++k)
        simplifyRange(line, anchors[k], anchors[k + 1], tolerance, keep);
    std::vector<dvec2> out;
    for (std::size_t i = 0; i < line.size(); ++i)
        if (keep[i]) out.push_back(line[i]);
    return out;
}

Triangulation triangulate(const std::vector<dvec2>& poly, double spacing,
                          const std::vector<dvec2>& interior) {
    if (poly.size() < 3) throw Error("polygon has fewer than 3 vertices");
    if (!(signedArea(poly) > 0)) throw Error("polygon is not counter-clockwise or has no area");
    Mesher mesher(poly);
    mesher.earClip(poly.size());
    mesher.buildAdjacency();
    mesher.delaunayFlips();
    if (!(spacing > 0)) return mesher.result();

    // Boundary edges no longer than `spacing`.
    for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
        const dvec2 a = poly[i], b = poly[(i + 1) % n];
        const int pieces = int(std::ceil(glm::length(b - a) / spacing - 1e-9));
        std::uint32_t from = std::uint32_t(i);
        for (int k = 1; k < pieces; ++k) {
            const dvec2 p = a + (b - a) * (double(k) / pieces);
            mesher.splitBoundaryEdge(from, std::uint32_t((i + 1) % n), p);
            // The new point is the last one added: the rest of the edge runs from it to b.
            from = std::uint32_t(mesher.pointCount() - 1);
        }
    }

    // Interior points: the ones given, else a lattice with rows at y = j * h * sqrt(3) / 2
    // (one on y = 0), odd rows offset; each inserted where it lies at least h / 2 inside.
    const double h = spacing;
    std::vector<dvec2> lattice;
    if (interior.empty()) {
        dvec2 lo(1e300), hi(-1e300);
        for (const dvec2& p : poly) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const double rowStep = h * std::sqrt(3.0) / 2.0;
        const long jLo = long(std::floor(lo.y / rowStep)), jHi = long(std::ceil(hi.y / rowStep));
        for (long j = jLo; j <= jHi; ++j) {
            const double offset = (j % 2 != 0) ? 0.5 * h : 0.0;
            const long iLo = long(std::floor((lo.x - offset) / h)),
                       iHi = long(std::ceil((hi.x - offset) / h));
            for (long i = iLo; i <= iHi; ++i)
                lattice.emplace_back(double(i) * h + offset, double(j) * rowStep);
        }
    }
    for (const dvec2& p : interior.empty() ? lattice : interior)
        if (contains(poly, p) && boundaryDistance(poly, p) >= 0.5 * h) mesher.insert(p);
    // Smallest angle 20 degrees where the outline allows it.
    double shortest = spacing;
    for (std::size_t i = 0, n = poly.size(); i < n; ++i)
        shortest = std::min(shortest, glm::length(poly[(i + 1) % n] - poly[i]));
    mesher.refine(poly, 20.0 * std::numbers::pi / 180.0, std::min(0.1 * spacing, 0.5 * shortest),
                  2 * mesher.pointCount() + 200);
    return mesher.result();
}

}  // namespace plantarch::polygon
