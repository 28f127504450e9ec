// Tests for plantarch/LeafShapes.h: outline families, meshing to the outline, deformations,
// PNG tracing and building from a LeafPrototype.
//
// Geometry is checked with helpers written here (segment intersection, containment, areas)
// rather than with the library's own polygon code, so a bug there cannot hide itself.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace {

using namespace plantarch;
using glm::dvec2;

// ---- geometry helpers ----------------------------------------------------------------------

double cross(dvec2 a, dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

double shoelace(const std::vector<vec2>& poly) {
    double sum = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        sum += cross(a, b);
    }
    return 0.5 * sum;
}

bool segmentsIntersect(dvec2 a, dvec2 b, dvec2 c, dvec2 d) {
    auto orient = [](dvec2 p, dvec2 q, dvec2 r) { return cross(q - p, r - p); };
    const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c),
                 d4 = orient(a, b, d);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    auto on = [](dvec2 p, dvec2 q, dvec2 r) {
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) &&
               std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
    };
    return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) ||
           (d4 == 0 && on(a, b, d));
}

// Every pair of non-adjacent edges is disjoint.
bool isSimplePolygon(const std::vector<vec2>& poly) {
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;
            if (segmentsIntersect(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]))
                return false;
        }
    return true;
}

bool inside(const std::vector<vec2>& poly, dvec2 p) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const dvec2 a = poly[i], b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            in = !in;
    }
    return in;
}

double distanceToBoundary(const std::vector<vec2>& poly, dvec2 p) {
    double best = 1e300;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        const double t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
        best = std::min(best, glm::length(p - (a + t * (b - a))));
    }
    return best;
}

AABB bounds(const Mesh& m) {
    AABB box;
    for (const vec3& p : m.positions) box.add(p);
    return box;
}

double smallestAngleDegrees(const Mesh& m, std::size_t t) {
    const glm::dvec3 p[3] = {m.positions[m.indices[t]], m.positions[m.indices[t + 1]],
                             m.positions[m.indices[t + 2]]};
    double smallest = 180.0;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = glm::normalize(p[(k + 1) % 3] - p[k]);
        const glm::dvec3 f = glm::normalize(p[(k + 2) % 3] - p[k]);
        smallest = std::min(
            smallest, std::acos(std::clamp(glm::dot(e, f), -1.0, 1.0)) * 180 / std::numbers::pi);
    }
    return smallest;
}

// Presets plus variants that exercise teeth, lobes and truncate bases on several forms.
std::vector<std::pair<std::string, LeafOutlineParams>> outlineCases() {
    std::vector<std::pair<std::string, LeafOutlineParams>> cases;
    for (LeafShape s : allLeafShapes())
        cases.push_back({std::string(leafShapeName(s)), leafShapePreset(s)});
    LeafOutlineParams p = leafShapePreset(LeafShape::Ovate);
    p.serrations = 14;
    p.serration_depth = 0.02f;
    cases.push_back({"ovate serrate", p});
    p = leafShapePreset(LeafShape::Ovate);
    p.lobes = 7;
    p.lobe_depth = 0.5f;
    cases.push_back({"ovate pinnately lobed", p});
    p = leafShapePreset(LeafShape::Reniform);
    p.lobes = 7;
    p.lobe_depth = 0.15f;
    p.serrations = 25;
    p.serration_depth = 0.012f;
    cases.push_back({"reniform lobed crenate", p});
    p = leafShapePreset(LeafShape::Palmate);
    p.lobes = 3;
    p.lobe_depth = 0.7f;
    cases.push_back({"palmate 3 deep", p});
    p = leafShapePreset(LeafShape::Oblong);
    p.base_width = 0.6f;
    cases.push_back({"oblong truncate", p});
    p = leafShapePreset(LeafShape::Cordate);
    p.serrations = 40;
    p.serration_depth = 0.03f;
    p.sinus_depth = 0.4f;
    cases.push_back({"cordate deep sinus serrate", p});
    return cases;
}

// ---- outlines ----------------------------------------------------------------------------

TEST(LeafOutline, EveryFamilyIsSimpleCounterClockwiseAndSpansUnitLength) {
    for (const auto& [name, params] : outlineCases()) {
        SCOPED_TRACE(name);
        const std::vector<vec2> poly = leafOutline(params);
        ASSERT_GE(poly.size(), 8u);
        EXPECT_TRUE(isSimplePolygon(poly));
        EXPECT_GT(shoelace(poly), 0.0);  // counter-clockwise
        float lo = 1e9f, hi = -1e9f, top = 0.0f;
        for (const vec2& p : poly) {
            lo = std::min(lo, p.x);
            hi = std::max(hi, p.x);
            top = std::max(top, std::abs(p.y));
        }
        EXPECT_NEAR(lo, 0.0f, 1e-5f);
        EXPECT_NEAR(hi, 1.0f, 1e-5f);
        EXPECT_NEAR(2.0f * top, params.aspect_ratio, 1e-3f * params.aspect_ratio);
        // The base vertex is on the midrib and the tip is (1, 0).
        EXPECT_NEAR(poly.front().y, 0.0f, 1e-6f);
        EXPECT_TRUE(std::any_of(poly.begin(), poly.end(), [](vec2 p) {
            return std::abs(p.x - 1.0f) < 1e-5f && std::abs(p.y) < 1e-6f;
        }));
    }
}

TEST(LeafOutline, RandomParametersStaySimple) {
    Rng rng(7);
    const auto& shapes = allLeafShapes();
    for (int i = 0; i < 120; ++i) {
        LeafOutlineParams p;
        p.shape = shapes[std::size_t(rng.uniformInt(0, int(shapes.size()) - 1))];
        p.aspect_ratio = rng.uniform(0.05f, 1.5f);
        p.widest_point = rng.uniform(0.2f, 0.8f);
        p.tip_angle = rng.uniform(10.0f, 180.0f);
        p.base_angle = rng.uniform(10.0f, 350.0f);
        p.sinus_depth = rng.uniform(0.05f, 0.4f);
        p.lobes = rng.uniformInt(0, 9);
        p.lobe_depth = rng.uniform(0.0f, 0.7f);
        p.serrations = rng.uniformInt(0, 40);
        p.serration_depth = rng.uniform(0.0f, 0.04f);
        SCOPED_TRACE(std::string(leafShapeName(p.shape)) + " case " + std::to_string(i));
        const std::vector<vec2> poly = leafOutline(p);
        EXPECT_TRUE(isSimplePolygon(poly));
        EXPECT_GT(shoelace(poly), 0.0);
    }
}

TEST(LeafOutline, WidestPointIsWhereAsked) {
    for (LeafShape s :
         {LeafShape::Elliptic, LeafShape::Ovate, LeafShape::Obovate, LeafShape::Lanceolate,
          LeafShape::Oblanceolate, LeafShape::Cordate, LeafShape::Reniform}) {
        for (float widest : {0.3f, 0.45f, 0.6f, 0.75f}) {
            LeafOutlineParams p = leafShapePreset(s);
            p.widest_point = widest;
            SCOPED_TRACE(std::string(leafShapeName(s)) + " " + std::to_string(widest));
            const std::vector<vec2> poly = leafOutline(p);
            const auto it = std::max_element(poly.begin(), poly.end(), [](vec2 a, vec2 b) {
                return std::abs(a.y) < std::abs(b.y);
            });
            EXPECT_NEAR(it->x, widest, 0.02f);
        }
    }
}

TEST(LeafOutline, NarrowTipAngleGivesDrawnOutTip) {
    // The half-width 10 % of the length behind the tip: an acuminate tip is much narrower.
    auto widthNearTip = [](float tipAngle) {
        LeafOutlineParams p = leafShapePreset(LeafShape::Ovate);
        p.tip_angle = tipAngle;
        double w = 0.0;
        for (vec2 q : leafOutline(p))
            if (std::abs(q.x - 0.9f) < 0.02f) w = std::max(w, double(std::abs(q.y)));
        return w;
    };
    EXPECT_LT(widthNearTip(20.0f), 0.6 * widthNearTip(120.0f));
}

// Teeth are counted as notches: runs of outline vertices that lie well inside the untoothed
// outline, between vertices on it (tooth tips).
int countNotches(const LeafOutlineParams& toothed) {
    LeafOutlineParams smooth = toothed;
    smooth.serrations = 0;
    smooth.tolerance = 1e-5f;
    const std::vector<vec2> reference = leafOutline(smooth);
    const std::vector<vec2> poly = leafOutline(toothed);
    int notches = 0;
    bool inNotch = false;
    for (const vec2& p : poly) {
        const double depth = distanceToBoundary(reference, p);
        if (!inNotch && depth > 0.5 * toothed.serration_depth) {
            inNotch = true;
            ++notches;
        } else if (inNotch && depth < 0.15 * toothed.serration_depth) {
            inNotch = false;
        }
    }
    return notches;
}

TEST(LeafOutline, SerrationsCutTheRequestedNumberOfTeeth) {
    for (int teeth : {5, 12, 30}) {
        for (LeafShape s :
             {LeafShape::Ovate, LeafShape::Oblong, LeafShape::Cordate, LeafShape::Palmate}) {
            LeafOutlineParams p = leafShapePreset(s);
            p.serrations = teeth;
            p.serration_depth = s == LeafShape::Palmate ? 0.02f : 0.012f;
            SCOPED_TRACE(std::string(leafShapeName(s)) + " " + std::to_string(teeth));
            EXPECT_EQ(countNotches(p), 2 * teeth);  // each margin
        }
    }
}

TEST(LeafOutline, LobesAddSinuses) {
    // Palmate: the radius from the petiole attachment has one deep minimum per sinus.
    for (int lobes : {3, 5, 7}) {
        LeafOutlineParams p = leafShapePreset(LeafShape::Palmate);
        p.lobes = lobes;
        p.lobe_depth = 0.5f;
        p.serrations = 0;
        const std::vector<vec2> poly = leafOutline(p);
        const dvec2 origin(p.sinus_depth, 0.0);
        // Walk the upper margin from the sinus to the tip and count deep dips of the radius.
        std::vector<double> radius;
        for (std::size_t i = poly.size() / 2 + 1; i < poly.size(); ++i)
            radius.push_back(glm::length(dvec2(poly[i]) - origin));
        std::reverse(radius.begin(), radius.end());
        int dips = 0;
        double peak = 0.0;
        bool falling = false;
        for (double r : radius) {
            peak = std::max(peak, r);
            if (!falling && r < 0.75 * peak) falling = true, ++dips;
            if (falling && r > 0.9 * peak) falling = false, peak = r;
        }
        SCOPED_TRACE(lobes);
        // One sinus between neighbouring lobes on each margin (the walk starts in the
        // petiolar sinus).
        EXPECT_EQ(dips, (lobes - 1) / 2);
    }
}

TEST(LeafOutline, UnknownShapeNameListsValidNames) {
    try {
        leafShapeFromName("heart");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.value(), "heart");
        EXPECT_NE(e.validRange().find("cordate"), std::string::npos);
    }
    // One set of names: the table's (an old alias is not among them).
    EXPECT_THROW(leafShapeFromName("palmately_lobed"), Error);
    for (LeafShape s : allLeafShapes()) EXPECT_EQ(leafShapeFromName(leafShapeName(s)), s);
}

// ---- meshing -----------------------------------------------------------------------------

TEST(LeafMesh, TrianglesLieInsideTheOutlineAndAreWellFormed) {
    for (const auto& [name, params] : outlineCases()) {
        for (unsigned sub : {1u, 8u, 30u}) {
            SCOPED_TRACE(name + " subdivisions " + std::to_string(sub));
            const std::vector<vec2> poly = leafOutline(params);
            const Mesh m = meshLeafOutline(poly, {.subdivisions = sub});
            ASSERT_NO_THROW(m.validate());
            ASSERT_EQ(m.uvs.size(), m.positions.size());
            for (const vec3& v : m.positions) {
                EXPECT_EQ(v.z, 0.0f);
                EXPECT_TRUE(inside(poly, dvec2(v)) || distanceToBoundary(poly, dvec2(v)) < 1e-5)
                    << v.x << " " << v.y;
            }
            double smallestArea = 1e9, smallestAngle = 180.0;
            for (std::size_t t = 0; t < m.indices.size(); t += 3) {
                const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                                 c = m.positions[m.indices[t + 2]];
                const dvec2 centroid = dvec2((a + b + c) / 3.0);
                EXPECT_TRUE(inside(poly, centroid)) << centroid.x << " " << centroid.y;
                const double area2 = cross(dvec2(b - a), dvec2(c - a));
                EXPECT_GT(area2, 0.0);  // counter-clockwise seen from +z
                smallestArea = std::min(smallestArea, 0.5 * area2);
                smallestAngle = std::min(smallestAngle, smallestAngleDegrees(m, t));
            }
            EXPECT_GT(smallestArea, 1e-7);
            EXPECT_GT(smallestAngle, 1.0);
        }
    }
}

TEST(LeafMesh, AreaMatchesTheOutline) {
    for (const auto& [name, params] : outlineCases()) {
        SCOPED_TRACE(name);
        const std::vector<vec2> poly = leafOutline(params);
        const Mesh m = meshLeafOutline(poly);  // default resolution
        EXPECT_NEAR(m.area(), shoelace(poly), 1e-4 * shoelace(poly));
        // And the polygon is within 1 % of the exact curve (a much finer outline).
        LeafOutlineParams fine = params;
        fine.tolerance = 2e-5f;
        EXPECT_NEAR(m.area(), shoelace(leafOutline(fine)), 0.01 * shoelace(poly));
    }
}

TEST(LeafMesh, ResolutionFollowsSubdivisions) {
    const std::vector<vec2> poly = leafOutline(leafShapePreset(LeafShape::Elliptic));
    std::size_t previous = 0;
    for (unsigned sub : {10u, 20u, 40u, 80u}) {
        const std::size_t count = meshLeafOutline(poly, {.subdivisions = sub}).triangleCount();
        EXPECT_GT(count, previous);
        previous = count;
    }
    // About two triangles per lattice cell of the blade's area at fine resolution.
    const double area = shoelace(poly);
    const double cell = std::sqrt(3.0) / 2.0 / (80.0 * 80.0);
    EXPECT_NEAR(double(previous), 2.0 * area / cell, 0.3 * 2.0 * area / cell);
}

TEST(LeafMesh, MidribIsALineOfEdges) {
    // Symmetric meshing: no triangle has vertices on both sides of the midrib.
    const Mesh m =
        meshLeafOutline(leafOutline(leafShapePreset(LeafShape::Ovate)), {.subdivisions = 12});
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        bool below = false, above = false;
        for (int k = 0; k < 3; ++k) {
            below |= m.positions[m.indices[t + k]].y < -1e-7f;
            above |= m.positions[m.indices[t + k]].y > 1e-7f;
        }
        EXPECT_FALSE(below && above);
    }
}

TEST(LeafMesh, UVsMapTheBladeBoundingBox) {
    const LeafOutlineParams p = leafShapePreset(LeafShape::Ovate);
    const Mesh m = meshLeafOutline(leafOutline(p));
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(m.uvs[i].x, m.positions[i].x, 1e-6f);
        EXPECT_NEAR(m.uvs[i].y, 0.5f + m.positions[i].y / p.aspect_ratio, 1e-4f);
        EXPECT_GE(m.uvs[i].y, -1e-5f);
        EXPECT_LE(m.uvs[i].y, 1.0f + 1e-5f);
    }
}

// Interior points given in the options replace the lattice: each one at least half a row's
// spacing inside the outline is a vertex of the mesh (a pleated blade's creases).
TEST(LeafMesh, InteriorPointsReplaceTheLattice) {
    const std::vector<vec2> poly = leafOutline(leafShapePreset(LeafShape::Orbicular));
    const Mesh lattice = meshLeafOutline(poly, {.subdivisions = 8});
    std::vector<vec2> points;
    // (A point of the symmetric mesh must also lie half a spacing from the midrib, which
    // bounds the half that is meshed.)
    for (int k = 2; k <= 6; ++k)
        for (double r : {0.15, 0.25, 0.35}) {
            const double a = k * std::numbers::pi / 8;
            points.emplace_back(float(0.5 + r * std::cos(a)), float(r * std::sin(a)));
        }
    points.emplace_back(0.999f, 0.01f);  // too close to the outline: left out
    const Mesh given = meshLeafOutline(poly, {.subdivisions = 8, .interior_points = points});
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const vec2 q = points[i];
        const bool found = std::any_of(given.positions.begin(), given.positions.end(),
                                       [&](const vec3& v) { return vec2(v) == q; });
        EXPECT_TRUE(found) << "point " << i;
        // The symmetric mesh mirrors the upper half: the point's mirror image too.
        EXPECT_TRUE(std::any_of(given.positions.begin(), given.positions.end(),
                                [&](const vec3& v) { return vec2(v) == vec2(q.x, -q.y); }));
    }
    EXPECT_FALSE(std::any_of(given.positions.begin(), given.positions.end(),
                             [&](const vec3& v) { return vec2(v) == points.back(); }));
    EXPECT_NE(given.positions.size(), lattice.positions.size());
    EXPECT_NEAR(
        shoelace(poly),
        [&] {
            double a = 0;
            for (std::size_t t = 0; t + 2 < given.indices.size(); t += 3)
                a += cross(dvec2(vec2(given.positions[given.indices[t + 1]]) -
                                 vec2(given.positions[given.indices[t]])),
                           dvec2(vec2(given.positions[given.indices[t + 2]]) -
                                 vec2(given.positions[given.indices[t]]))) /
                     2;
            return a;
        }(),
        1e-4);
}

TEST(LeafMesh, RejectsBadPolygons) {
    EXPECT_THROW(meshLeafOutline({{0, 0}, {1, 0}}), Error);
    // A bow tie crosses itself.
    EXPECT_THROW(meshLeafOutline({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), Error);
    // A clockwise polygon is accepted (reversed).
    const Mesh m =
        meshLeafOutline({{0, 0}, {0, 0.2f}, {1, 0}, {0.5f, -0.2f}}, {.symmetric = false});
    EXPECT_NEAR(m.area(), 0.2, 1e-5);
}

// ---- deformations ----------------------------------------------------------------------

// The bent midrib's curve for longitudinal curvature c, as arc length and tangent angle at
// n + 1 points: the blade point at flat x drops by c x^4 and turns about the base by -c x^4
// radians, P(x) = (x cos t + z sin t, z cos t - x sin t), z = c x^4, t = -z. Written with
// the derivative of P (the library samples P itself), so the two are separate computations.
struct BendCurve {
    std::vector<double> s, angle;  // arc length along P, tangent angle (radians)
    dvec2 tip;                     // P(1)
    double length() const { return s.back(); }
    // Angle at the fraction u of the length.
    double angleAt(double u) const {
        const double target = std::clamp(u, 0.0, 1.0) * length();
        const auto it = std::lower_bound(s.begin(), s.end(), target);
        const std::size_t i = std::clamp<std::size_t>(std::size_t(it - s.begin()), 1, s.size() - 1);
        const double f = (target - s[i - 1]) / (s[i] - s[i - 1]);
        return angle[i - 1] + f * (angle[i] - angle[i - 1]);
    }
};
BendCurve bendCurve(double c, int n = 20000) {
    BendCurve b;
    auto derivative = [c](double x) {
        const double z = c * x * x * x * x, dz = 4.0 * c * x * x * x, t = -z, dt = -dz;
        return dvec2(std::cos(t) - x * std::sin(t) * dt + dz * std::sin(t) + z * std::cos(t) * dt,
                     dz * std::cos(t) - z * std::sin(t) * dt - std::sin(t) - x * std::cos(t) * dt);
    };
    double length = 0.0;
    dvec2 previous = derivative(0.0);
    for (int i = 0; i <= n; ++i) {
        const dvec2 d = derivative(double(i) / n);
        if (i > 0) length += 0.5 * (glm::length(d) + glm::length(previous)) / n;
        b.s.push_back(length);
        b.angle.push_back(std::atan2(d.y, d.x));
        previous = d;
    }
    const double t = -c;
    b.tip = dvec2(std::cos(t) + c * std::sin(t), c * std::cos(t) - std::sin(t));
    return b;
}

struct Deformed {
    Mesh flat;
    Mesh bent;
};

Deformed deform(LeafShape shape, LeafDeformation d, unsigned sub = 24) {
    const LeafOutlineParams p = leafShapePreset(shape);
    Deformed out;
    out.flat = meshLeafOutline(leafOutline(p), {.subdivisions = sub});
    out.bent = out.flat;
    if (d.blade_width <= 0) d.blade_width = p.aspect_ratio;
    deformLeafMesh(out.bent, d);
    return out;
}

TEST(LeafDeform, FoldRaisesTheMarginsAndKeepsTheMidrib) {
    const Deformed r = deform(LeafShape::Elliptic, {.midrib_fold_fraction = 0.4f});
    float marginZ = 0.0f;
    for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
        const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
        if (std::abs(f.y) < 1e-7f) {
            EXPECT_NEAR(b.z, 0.0f, 1e-6f);
        } else {
            EXPECT_GT(b.z, 0.0f);
        }
        // Each half turns rigidly about the midrib by 0.4 * 90 degrees.
        EXPECT_NEAR(b.z, std::abs(f.y) * std::sin(0.2 * std::numbers::pi), 1e-5);
        EXPECT_NEAR(std::abs(b.y), std::abs(f.y) * std::cos(0.2 * std::numbers::pi), 1e-5);
        marginZ = std::max(marginZ, b.z);
    }
    EXPECT_GT(marginZ, 0.05f);
    EXPECT_NEAR(r.bent.area(), r.flat.area(), 1e-4 * r.flat.area());  // folding is rigid
}

TEST(LeafDeform, LongitudinalCurvatureLiftsOrLowersTheTip) {
    for (float c : {0.3f, -0.3f}) {
        SCOPED_TRACE(c);
        const Deformed r =
            deform(LeafShape::Lanceolate, {.longitudinal_curvature = c, .normalize_length = false});
        const BendCurve bend = bendCurve(c);
        const dvec2 tip = bend.tip / bend.length();
        for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
            const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
            if (std::abs(f.x - 1.0f) < 1e-6f && std::abs(f.y) < 1e-6f) {
                // The tip ends where the curve's does, scaled to the blade's length (about
                // 2c above the base: 0.47 for 0.3).
                EXPECT_GT(b.z * c, 0.0f);
                EXPECT_NEAR(b.x, tip.x, 0.01f);
                EXPECT_NEAR(b.z, tip.y, 0.01f);
            }
        }
        // Bending keeps the midrib's length: the tip is 1 from the base along the midrib.
        std::vector<std::pair<float, vec3>> midrib;  // flat x, bent position
        for (std::size_t i = 0; i < r.flat.positions.size(); ++i)
            if (std::abs(r.flat.positions[i].y) < 1e-7f)
                midrib.push_back({r.flat.positions[i].x, r.bent.positions[i]});
        std::sort(midrib.begin(), midrib.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        double length = 0.0;
        for (std::size_t i = 1; i < midrib.size(); ++i)
            length += glm::length(midrib[i].second - midrib[i - 1].second);
        EXPECT_NEAR(length, 1.0, 0.01);
    }
}

// A blade curled past the vertical (the range's ends, +-2: the tip turns back behind the base)
// follows the same curve without a kink where its direction passes straight back.
TEST(LeafDeform, LongitudinalCurvatureCurlsPastTheVerticalSmoothly) {
    for (float c : {2.0f, -2.0f, -1.2f}) {
        SCOPED_TRACE(c);
        const Deformed r = deform(LeafShape::Lanceolate,
                                  {.longitudinal_curvature = c, .normalize_length = false}, 48);
        const BendCurve bend = bendCurve(c);
        const dvec2 tip = bend.tip / bend.length();
        bool found = false;
        for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
            const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
            if (std::abs(f.x - 1.0f) < 1e-6f && std::abs(f.y) < 1e-6f) {
                found = true;
                EXPECT_NEAR(b.x, tip.x, 5e-4f);
                EXPECT_NEAR(b.z, tip.y, 5e-4f);
            }
        }
        EXPECT_TRUE(found);
    }
}

TEST(LeafDeform, BuckleBendsDownAtTheGivenFraction) {
    const float at = 0.5f;
    const Deformed r = deform(
        LeafShape::Linear,
        {.leaf_buckle_length = at, .leaf_buckle_angle = 45.0f, .normalize_length = false}, 40);
    std::vector<std::pair<float, float>> midrib;  // flat x, bent z
    for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
        const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
        if (f.x < at - 0.03f) {  // before the crease: untouched
            EXPECT_NEAR(b.x, f.x, 1e-5f);
            EXPECT_NEAR(b.z, f.z, 1e-5f);
        }
        if (std::abs(f.y) < 1e-7f) midrib.push_back({f.x, b.z});
    }
    std::sort(midrib.begin(), midrib.end());
    for (std::size_t i = 1; i < midrib.size(); ++i)
        if (midrib[i].first > at + 0.03f) {
            EXPECT_LT(midrib[i].second, midrib[i - 1].second);  // going down
            // Beyond the crease the midrib descends at the buckle angle.
            const float slope =
                (midrib[i].second - midrib[i - 1].second) / (midrib[i].first - midrib[i - 1].first);
            EXPECT_NEAR(slope, -std::sin(float(std::numbers::pi) / 4.0f), 0.02f);
        }
    EXPECT_NEAR(midrib.back().second, -(1.0f - at) * std::sin(float(std::numbers::pi) / 4.0f),
                0.03f);
}

TEST(LeafDeform, LateralCurvatureCupsTheBlade) {
    for (float c : {1.0f, -1.0f}) {
        SCOPED_TRACE(c);
        const Deformed r = deform(LeafShape::Orbicular, {.lateral_curvature = c});
        for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
            const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
            if (std::abs(f.y) < 1e-7f) {
                EXPECT_NEAR(b.z, 0.0f, 1e-6f);
            } else {
                EXPECT_GT(b.z * c, 0.0f);  // margins above (below) the midrib
            }
        }
        // The margin at the widest point moves by c / 16.
        const auto widest = std::max_element(r.flat.positions.begin(), r.flat.positions.end(),
                                             [](vec3 a, vec3 b) { return a.y < b.y; });
        const std::size_t i = std::size_t(widest - r.flat.positions.begin());
        EXPECT_NEAR(r.bent.positions[i].z, c / 16.0f, 1e-3f);
    }
}

TEST(LeafDeform, WavesAlternateAlongTheMarginWithTheGivenPeriod) {
    const float period = 0.2f;
    const LeafOutlineParams p = leafShapePreset(LeafShape::Oblong);
    const std::vector<vec2> poly = leafOutline(p);
    Mesh flat = meshLeafOutline(poly, {.subdivisions = 40});
    Mesh bent = flat;
    deformLeafMesh(bent, {.wave_period = period,
                          .wave_amplitude = 0.05f,
                          .blade_width = p.aspect_ratio,
                          .normalize_length = false});
    // Upper margin vertices, by x.
    std::vector<std::pair<float, float>> margin;
    for (std::size_t i = 0; i < flat.positions.size(); ++i) {
        const vec3 f = flat.positions[i];
        if (f.y > 0.02f && distanceToBoundary(poly, dvec2(f)) < 1e-6)
            margin.push_back({f.x, bent.positions[i].z});
    }
    std::sort(margin.begin(), margin.end());
    std::vector<float> changes;
    for (std::size_t i = 1; i < margin.size(); ++i)
        if ((margin[i].second > 0) != (margin[i - 1].second > 0))
            changes.push_back(0.5f * (margin[i].first + margin[i - 1].first));
    ASSERT_GE(changes.size(), 3u);
    for (float x : changes) {
        // Sign changes sit on multiples of the period.
        const float k = std::round(x / period);
        EXPECT_NEAR(x, k * period, 0.03f);
    }
    for (std::size_t i = 1; i < changes.size(); ++i)
        EXPECT_NEAR(changes[i] - changes[i - 1], period, 0.05f);
    // The lower margin is in antiphase.
    for (std::size_t i = 0; i < flat.positions.size(); ++i) {
        const vec3 f = flat.positions[i];
        const float phase = std::sin(float(std::numbers::pi) * f.x / period);
        if (std::abs(f.y) > 0.02f && std::abs(phase) > 0.3f) {
            EXPECT_GT(bent.positions[i].z * (f.y > 0 ? -1.0f : 1.0f) * phase, 0.0f);
        }
    }
}

namespace {

double surfaceArea(const Mesh& m) {
    double a = 0.0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 p = m.positions[m.indices[t]], q = m.positions[m.indices[t + 1]],
                         r = m.positions[m.indices[t + 2]];
        a += 0.5 * glm::length(glm::cross(q - p, r - p));
    }
    return a;
}

}  // namespace

// Pleats fold a round blade like a fan about the petiole's attachment (the sinus): ridges
// along the midrib and every 360 / n degrees, the blade drawn in so that it keeps its area,
// and every point its distance from the attachment.
TEST(LeafDeform, PleatsFoldTheBladeAboutTheAttachmentAndKeepItsArea) {
    LeafOutlineParams p = leafShapePreset(LeafShape::Reniform);
    const std::vector<vec2> poly = leafOutline(p);
    const Mesh flat = meshLeafOutline(poly, {.subdivisions = 60});
    const int n = 7;
    const float depth = 0.12f, centre = p.sinus_depth;
    Mesh folded = flat;
    deformLeafMesh(folded, {.pleats = n,
                            .pleat_depth = depth,
                            .pleat_center_x = centre,
                            .blade_width = p.aspect_ratio,
                            .normalize_length = false});
    // The folded surface has the flat blade's area (the mesh's chords across the folds lose a
    // little of it).
    EXPECT_NEAR(surfaceArea(folded) / surfaceArea(flat), 1.0, 0.01);
    double flatSpan = 0.0, foldedSpan = 0.0, ridge = 0.0;
    int furrows = 0;
    for (std::size_t i = 0; i < flat.positions.size(); ++i) {
        const glm::dvec3 f(flat.positions[i]), g(folded.positions[i]);
        const glm::dvec3 c(centre, 0.0, 0.0);
        // Every point keeps its distance from the attachment.
        EXPECT_NEAR(glm::length(g - c), glm::length(f - c), 1e-5);
        flatSpan = std::max(flatSpan, std::abs(std::atan2(f.y, f.x - centre)));
        foldedSpan = std::max(foldedSpan, std::abs(std::atan2(g.y, g.x - centre)));
        // On the midrib beyond the attachment: a ridge, rising by depth / sqrt(1 + depth^2)
        // of the distance.
        if (f.y == 0.0 && f.x > centre + 0.1) {
            EXPECT_NEAR(g.z / (f.x - centre), depth / std::sqrt(1.0 + depth * depth), 1e-5);
            EXPECT_EQ(g.y, 0.0);
            ridge = std::max(ridge, g.z);
        }
        // Half a pleat off the midrib: a furrow.
        const double a = std::atan2(g.y, g.x - centre);
        if (std::abs(std::abs(a) - std::numbers::pi / n) < 0.02 && glm::length(g - c) > 0.1) {
            EXPECT_LT(g.z, 0.0) << "at angle " << a;
            ++furrows;
        }
    }
    EXPECT_GT(ridge, 0.05);
    EXPECT_GT(furrows, 5);
    // Drawn in: the folded blade spans a smaller angle about the attachment.
    EXPECT_LT(foldedSpan, flatSpan - 0.2);
    // No pleats, or pleats of no depth: the blade as it was.
    for (const auto& [count, d] : {std::pair{0, depth}, std::pair{n, 0.0f}}) {
        Mesh same = flat;
        deformLeafMesh(same, {.pleats = count, .pleat_depth = d, .pleat_center_x = centre});
        Mesh plain = flat;
        deformLeafMesh(plain, {});
        EXPECT_EQ(same.positions, plain.positions);
    }
}

// Any number and depth of pleats, on every family, with the other deformations drawn at
// random: a finite mesh of the same triangles, none of them degenerate.
TEST(LeafDeform, PleatsOfAnyDepthKeepTheMeshWellFormed) {
    Rng rng(11);
    for (int family = 0; family <= int(LeafShape::Palmate); ++family)
        for (int trial = 0; trial < 12; ++trial) {
            LeafPrototype proto;
            proto.shape = LeafShape(family);
            proto.pleats = trial < 6 ? rng.uniformInt(1, 31) : 31;
            proto.pleat_depth = trial < 6 ? rng.uniform(-0.5f, 0.5f) : (trial % 2 ? 0.5f : -0.5f);
            proto.lateral_curvature = rng.uniform(-1.0f, 1.0f);
            proto.longitudinal_curvature = rng.uniform(-0.5f, 0.5f);
            proto.subdivisions = 6;
            Rng draw(std::uint64_t(family * 100 + trial));
            const Mesh m = buildLeafMesh(realizeLeafShape(proto, draw));
            SCOPED_TRACE(std::string(leafShapeName(proto.shape)) + " pleats " +
                         proto.pleats.describe() + " depth " + proto.pleat_depth.describe());
            ASSERT_FALSE(m.indices.empty());
            for (const vec3& v : m.positions)
                ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
            for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
                const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                                 c = m.positions[m.indices[t + 2]];
                const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
                const double edge2 = std::max(
                    {glm::dot(b - a, b - a), glm::dot(c - a, c - a), glm::dot(c - b, c - b)});
                EXPECT_GT(area, 1e-4 * edge2) << "triangle " << t / 3;
            }
        }
}

TEST(LeafDeform, PetioleRollCurlsOnlyTheBase) {
    const Deformed r =
        deform(LeafShape::Oblong, {.petiole_roll = 60.0f, .normalize_length = false});
    for (std::size_t i = 0; i < r.flat.positions.size(); ++i) {
        const vec3 f = r.flat.positions[i], b = r.bent.positions[i];
        if (std::abs(f.y) < 0.05f) continue;
        if (f.x < 0.05f) {
            EXPECT_GT(b.z, 0.3f * std::abs(f.y));
        }
        if (f.x > 0.4f) {
            EXPECT_LT(b.z, 0.01f * std::abs(f.y));
        }
    }
}

// The length of the bent midrib: the vertices on the flat blade's midrib (y = z = 0: not a
// petiolule's), in the order of their flat x.
double midribLength(const Mesh& flat, const Mesh& bent) {
    std::vector<std::pair<float, vec3>> midrib;
    for (std::size_t i = 0; i < flat.positions.size(); ++i)
        if (std::abs(flat.positions[i].y) < 1e-7f && std::abs(flat.positions[i].z) < 1e-7f)
            midrib.emplace_back(flat.positions[i].x, bent.positions[i]);
    std::sort(midrib.begin(), midrib.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    double length = 0.0;
    for (std::size_t i = 1; i < midrib.size(); ++i)
        length += glm::length(glm::dvec3(midrib[i].second) - glm::dvec3(midrib[i - 1].second));
    return length;
}

// Normalization makes the blade's length along the midrib 1, whatever the bending did to its
// projection: a curled grass blade keeps its base at the origin and its midrib 1 long, and
// its projection on x is shorter.
TEST(LeafDeform, NormalizationGivesTheMidribUnitLength) {
    const LeafDeformation grass{.midrib_fold_fraction = 0.3f,
                                .longitudinal_curvature = -0.4f,
                                .lateral_curvature = -0.3f,
                                .wave_period = 0.1f,
                                .wave_amplitude = 0.1f,
                                .leaf_buckle_length = 0.5f,
                                .leaf_buckle_angle = 45.0f};
    const Deformed r = deform(LeafShape::Linear, grass, 50);
    EXPECT_NEAR(midribLength(r.flat, r.bent), 1.0, 0.01);
    const AABB box = bounds(r.bent);
    EXPECT_NEAR(box.min.x, 0.0f, 1e-3f);
    EXPECT_LT(box.max.x, 0.95f);  // the projection is not stretched back to 1
    // Unbent (fold, cupping and waves only), the blade spans x in [0, 1] as the flat one does.
    LeafDeformation unbent = grass;
    unbent.longitudinal_curvature = 0.0f;
    unbent.leaf_buckle_length = 0.0f;
    const AABB straight = bounds(deform(LeafShape::Linear, unbent, 50).bent);
    EXPECT_EQ(straight.min.x, 0.0f);
    EXPECT_EQ(straight.max.x, 1.0f);
}

// ---- building from a LeafPrototype ---------------------------------------------------------

LeafPrototype maizeLike() {
    LeafPrototype proto;
    proto.shape = LeafShape::Linear;
    proto.leaf_aspect_ratio = 0.1f;
    proto.widest_point = 0.4f;
    proto.tip_angle = 12.0f;
    proto.base_angle = 20.0f;
    proto.base_width = 0.5f;
    proto.midrib_fold_fraction = 0.3f;
    proto.longitudinal_curvature = RandomFloat::uniform(-0.45f, -0.3f);
    proto.lateral_curvature = -0.3f;
    proto.wave_period = 0.1f;
    proto.wave_amplitude = 0.1f;
    proto.leaf_buckle_length = RandomFloat::uniform(0.4f, 0.6f);
    proto.leaf_buckle_angle = RandomFloat::uniform(40.0f, 50.0f);
    proto.petiole_roll = 30.0f;
    proto.subdivisions = 50;
    return proto;
}

// A realized shape with only some of its deformations.
RealizedLeafShape withDeformation(const RealizedLeafShape& r, const LeafDeformation& d) {
    RealizedLeafShape out = r;
    out.deformation = d;
    out.deformation.blade_width = r.deformation.blade_width;
    return out;
}

// The area the deformations give a flat blade mesh of unit length, from the surface they
// describe (LeafShapes.h): cupping and waves lift the blade to z(x, y) = lateral_curvature
// (y / w)^2 / 4 + wave_amplitude 2 |y| sin(pi x / wave_period + phase); the fold f turns each
// half about the midrib, putting a point at height b = |y| sin f + z cos f over it; the midrib
// bends at curvature kappa(x) = d/dx (the bend curve's angle at x, bendCurve(), minus
// the buckle's smoothstep), keeping its length. With
// the midrib's tangent T and normal N, d/dx = (1 - kappa b) T + z_x (...) and
// d/dy = (...) of length sqrt(1 + z_y^2), so the area element is
// sqrt((1 - kappa b)^2 (1 + z_y^2) + z_x^2). Summed over the flat triangles at their centroids;
// the petiole roll (a twist of the basal 5 %) is left out.
double deformedArea(const Mesh& flat, const LeafDeformation& d) {
    const double w = d.blade_width, pi = std::numbers::pi;
    const bool waves = d.wave_period > 0.0f && d.wave_amplitude != 0.0f;
    const double k = waves ? pi / d.wave_period : 0.0;
    const double fold = d.midrib_fold_fraction * 0.5 * pi;
    const double buckle = d.leaf_buckle_length > 0.0f ? d.leaf_buckle_angle * pi / 180.0 : 0.0;
    constexpr double ramp = 0.025;  // half-length of the buckle's crease
    std::optional<BendCurve> bend;
    if (d.longitudinal_curvature != 0.0f) bend = bendCurve(d.longitudinal_curvature, 4000);
    double area = 0.0;
    for (std::size_t t = 0; t < flat.indices.size(); t += 3) {
        const glm::dvec3 a = flat.positions[flat.indices[t]],
                         b = flat.positions[flat.indices[t + 1]],
                         c = flat.positions[flat.indices[t + 2]];
        const glm::dvec3 m = (a + b + c) / 3.0;
        const double side = m.y < 0 ? -1.0 : 1.0, phase = side > 0 ? pi : 0.0;
        double z = d.lateral_curvature * (m.y / w) * (m.y / w) / 4.0;
        double zy = d.lateral_curvature * m.y / (2.0 * w * w), zx = 0.0;
        if (waves) {
            z += 2.0 * d.wave_amplitude * std::abs(m.y) * std::sin(k * m.x + phase);
            zy += 2.0 * d.wave_amplitude * side * std::sin(k * m.x + phase);
            zx = 2.0 * d.wave_amplitude * std::abs(m.y) * k * std::cos(k * m.x + phase);
        }
        const double height = std::abs(m.y) * std::sin(fold) + z * std::cos(fold);
        const double s = std::clamp((m.x - (d.leaf_buckle_length - ramp)) / (2.0 * ramp), 0.0, 1.0);
        // The midrib's curvature: the bend curve's turn per length (at unit length),
        // then the buckle's.
        double bendRate = 0.0;
        if (bend && m.x > 0.0 && m.x < 1.0) {
            const double h = 1e-3, lo = std::max(m.x - h, 0.0), hi = std::min(m.x + h, 1.0);
            bendRate = (bend->angleAt(hi) - bend->angleAt(lo)) / (hi - lo);
        }
        const double kappa = bendRate - buckle * 6.0 * s * (1.0 - s) / (2.0 * ramp);
        const double stretch = 1.0 - kappa * height;
        area += 0.5 * glm::length(glm::cross(b - a, c - a)) *
                std::sqrt(stretch * stretch * (1.0 + zy * zy) + zx * zx);
    }
    return area;
}

// A leaf's scale is its length along the blade: curled, buckled and wavy grass blades and a
// curved, folded dicot leaf have a midrib of length 1 (within the 1 % its chords may lose),
// and their area is the flat blade's up to the stretching the curl itself makes: bent on a
// flat cross-section, the blade keeps its area (0.5 %: chords of the bend); with every
// deformation, its area is deformedArea() (1 %: centroid sampling, chords, the petiole roll).
// Normalizing the projected length to 1 instead made such blades 1.2 to 1.9 times too large.
TEST(LeafPrototypeBuild, CurledBladesKeepTheirLengthAndTheAreaTheirCurlGives) {
    LeafPrototype wavy = maizeLike();  // fold, cupping and waves, no bend
    wavy.longitudinal_curvature = 0.0f;
    wavy.leaf_buckle_length = 0.0f;
    LeafPrototype dicot;  // a curved, folded dicot leaf
    dicot.shape = LeafShape::Elliptic;
    dicot.leaf_aspect_ratio = 0.5f;
    dicot.midrib_fold_fraction = 0.2f;
    dicot.longitudinal_curvature = 0.4f;
    dicot.subdivisions = 20;
    const std::vector<std::pair<std::string, LeafPrototype>> blades = {
        {"maize-like", maizeLike()}, {"wavy", wavy}, {"dicot", dicot}};
    Rng rng(11);
    for (const auto& [name, proto] : blades)
        for (int draw = 0; draw < 3; ++draw) {
            SCOPED_TRACE(name + ", draw " + std::to_string(draw));
            const RealizedLeafShape shape = realizeLeafShape(proto, rng);
            const LeafDeformation& d = shape.deformation;
            const Mesh bent = buildLeafMesh(shape),
                       flat = buildLeafMesh(withDeformation(shape, {}));
            EXPECT_NEAR(midribLength(flat, bent), 1.0, 0.01);
            const Mesh bentOnly = buildLeafMesh(
                withDeformation(shape, {.longitudinal_curvature = d.longitudinal_curvature,
                                        .leaf_buckle_length = d.leaf_buckle_length,
                                        .leaf_buckle_angle = d.leaf_buckle_angle}));
            EXPECT_NEAR(bentOnly.area() / flat.area(), 1.0, 0.005);
            EXPECT_NEAR(bent.area() / deformedArea(flat, d), 1.0, 0.01)
                << "flat " << flat.area() << ", bent " << bent.area();
        }
}

TEST(LeafPrototypeBuild, SameStreamSameBytes) {
    const LeafPrototype proto = maizeLike();
    Rng a(42, 3), b(42, 3);
    const Mesh m1 = buildLeafPrototype(proto, a);
    const Mesh m2 = buildLeafPrototype(proto, b);
    ASSERT_EQ(m1.positions.size(), m2.positions.size());
    EXPECT_EQ(0, std::memcmp(m1.positions.data(), m2.positions.data(),
                             m1.positions.size() * sizeof(vec3)));
    EXPECT_EQ(0, std::memcmp(m1.uvs.data(), m2.uvs.data(), m1.uvs.size() * sizeof(vec2)));
    EXPECT_EQ(m1.indices, m2.indices);
    EXPECT_EQ(a, b);
    // Another draw differs.
    const Mesh m3 = buildLeafPrototype(proto, a);
    EXPECT_NE(0, std::memcmp(m1.positions.data(), m3.positions.data(),
                             m1.positions.size() * sizeof(vec3)));
}

TEST(LeafPrototypeBuild, DrawsEveryRandomFieldOnceWhateverTheShape) {
    LeafPrototype proto = maizeLike();
    proto.widest_point = RandomFloat::uniform(0.3f, 0.5f);
    proto.lobes = RandomInt::uniform(3, 5);
    Rng first(9), second(9);
    const RealizedLeafShape r1 = realizeLeafShape(proto, first);
    proto.shape = LeafShape::Palmate;
    realizeLeafShape(proto, second);
    EXPECT_EQ(first, second);  // same number of draws
    EXPECT_GE(r1.outline.widest_point, 0.3f);
    EXPECT_LE(r1.outline.widest_point, 0.5f);
    EXPECT_GE(r1.deformation.leaf_buckle_angle, 40.0f);
    EXPECT_LE(r1.deformation.leaf_buckle_angle, 50.0f);
    EXPECT_GE(r1.outline.lobes, 3);
    EXPECT_LE(r1.outline.lobes, 5);
    EXPECT_EQ(r1.outline.shape, LeafShape::Linear);
    // Out-of-range draws are clamped.
    proto.leaf_aspect_ratio = RandomFloat::normal(-5.0f, 0.1f);
    EXPECT_GE(realizeLeafShape(proto, first).outline.aspect_ratio, 0.01f);
    proto.shape = static_cast<LeafShape>(99);  // not a declared family
    EXPECT_THROW(realizeLeafShape(proto, first), Error);
}

// Every family: unbent, the prototype spans x in [0, 1]; bent up or down, its midrib keeps the
// length it has in the flat blade (from the base, or the sinus of a notched outline, to the
// tip) and the base stays at the origin.
TEST(LeafPrototypeBuild, EveryFamilySpansUnitLengthAlongTheBlade) {
    Rng rng(5);
    for (LeafShape s : allLeafShapes()) {
        for (float curvature : {0.0f, 0.4f, -0.4f}) {
            LeafPrototype proto;
            const LeafOutlineParams p = leafShapePreset(s);
            proto.shape = s;
            proto.leaf_aspect_ratio = p.aspect_ratio;
            proto.widest_point = p.widest_point;
            proto.tip_angle = p.tip_angle;
            proto.base_angle = p.base_angle;
            proto.sinus_depth = p.sinus_depth;
            proto.midrib_fold_fraction = 0.2f;
            proto.longitudinal_curvature = curvature;
            proto.lateral_curvature = -0.3f;
            proto.wave_period = 0.3f;
            proto.wave_amplitude = 0.05f;
            proto.subdivisions = 6;
            SCOPED_TRACE(std::string(leafShapeName(s)) + ", curvature " +
                         std::to_string(curvature));
            const RealizedLeafShape shape = realizeLeafShape(proto, rng);
            RealizedLeafShape unbent = shape;
            unbent.deformation = {};
            const Mesh m = buildLeafMesh(shape), flat = buildLeafMesh(unbent);
            ASSERT_NO_THROW(m.validate());
            ASSERT_EQ(m.positions.size(), flat.positions.size());
            const AABB box = bounds(m), flatBox = bounds(flat);
            EXPECT_NEAR(flatBox.min.x, 0.0f, 1e-5f);
            EXPECT_NEAR(flatBox.max.x, 1.0f, 1e-5f);
            if (curvature == 0.0f) {
                EXPECT_NEAR(box.min.x, 0.0f, 1e-5f);
                EXPECT_NEAR(box.max.x, 1.0f, 1e-5f);
            } else {
                EXPECT_NEAR(box.min.x, 0.0f, 0.01f);
                EXPECT_LT(box.max.x, 1.0f);
            }
            AABB flatMidrib;
            for (const vec3& v : flat.positions)
                if (std::abs(v.y) < 1e-7f) flatMidrib.add(v);
            EXPECT_NEAR(midribLength(flat, m), flatMidrib.max.x - flatMidrib.min.x, 0.01);
        }
    }
}

TEST(LeafPrototypeBuild, MeasuredAspectRatioEqualsTheParameter) {
    Rng rng(1);
    for (float aspect : {0.06f, 0.25f, 0.6f, 1.0f}) {
        LeafPrototype proto;
        proto.shape = LeafShape::Elliptic;
        proto.leaf_aspect_ratio = aspect;
        const Mesh m = buildLeafPrototype(proto, rng);
        const AABB box = bounds(m);
        EXPECT_NEAR((box.max.y - box.min.y) / (box.max.x - box.min.x), aspect, 1e-3f * aspect);
    }
}

TEST(LeafPrototypeBuild, PetioluleAndOffset) {
    Rng rng(3);
    LeafPrototype proto;
    proto.shape = LeafShape::Ovate;
    proto.leaf_aspect_ratio = 0.6f;
    const Mesh plain = buildLeafPrototype(proto, rng);
    proto.build_petiolule = true;
    const Mesh stalked = buildLeafPrototype(proto, rng);
    EXPECT_GT(stalked.positions.size(), plain.positions.size());
    EXPECT_NEAR(bounds(stalked).min.x, 0.0f, 1e-5f);
    EXPECT_NEAR(bounds(stalked).max.x, 1.0f, 1e-5f);
    // The stalk fills the first 8 % of the blade length: the blade starts there.
    float bladeStart = 1.0f;
    for (std::size_t i = 0; i < stalked.positions.size(); ++i)
        if (std::abs(stalked.positions[i].y) > 0.05f)
            bladeStart = std::min(bladeStart, stalked.positions[i].x);
    EXPECT_GT(bladeStart, 0.07f);
    proto.build_petiolule = false;
    proto.leaf_offset = vec3(-0.3f, 0.0f, 0.01f);
    const AABB shifted = bounds(buildLeafPrototype(proto, rng));
    EXPECT_NEAR(shifted.min.x, -0.3f, 1e-5f);
    EXPECT_NEAR(shifted.max.x, 0.7f, 1e-5f);
}

// ---- PNG outlines ------------------------------------------------------------------------

class LeafImage : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("plantarch_leaf_test_" +
                std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // An RGBA image with an opaque ellipse (semi-axes a, b pixels) centred in it.
    std::string writeEllipse(const std::string& name, int w, int h, double a, double b) {
        std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4, 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double dx = (x + 0.5 - 0.5 * w) / a, dy = (y + 0.5 - 0.5 * h) / b;
                std::uint8_t* p = &rgba[(std::size_t(y) * w + x) * 4];
                p[0] = 40;
                p[1] = std::uint8_t(100 + x % 100);
                p[2] = 30;
                p[3] = dx * dx + dy * dy <= 1.0 ? 255 : 0;
            }
        const std::string path = (dir_ / name).string();
        EXPECT_NE(0, stbi_write_png(path.c_str(), w, h, 4, rgba.data(), w * 4));
        return path;
    }

    std::filesystem::path dir_;
};

TEST_F(LeafImage, TracedEllipseHasTheEllipsesArea) {
    const double a = 180.0, b = 60.0;
    const std::string path = writeEllipse("ellipse.png", 400, 200, a, b);
    const TracedLeafOutline traced = traceLeafImage(path);
    const std::vector<vec2>& poly = traced.outline;
    EXPECT_TRUE(isSimplePolygon(poly));
    EXPECT_GT(shoelace(poly), 0.0);
    // Prototype units: the opaque width (2a pixels) is the unit length.
    const double expected = std::numbers::pi * a * b / (2.0 * a * 2.0 * a);
    EXPECT_NEAR(shoelace(poly), expected, 0.02 * expected);
    float lo = 1e9f, hi = -1e9f, top = -1e9f, bottom = 1e9f;
    for (vec2 p : poly) {
        lo = std::min(lo, p.x);
        hi = std::max(hi, p.x);
        top = std::max(top, p.y);
        bottom = std::min(bottom, p.y);
    }
    EXPECT_NEAR(lo, 0.0f, 1e-5f);
    EXPECT_NEAR(hi, 1.0f, 1e-5f);
    EXPECT_NEAR(top, -bottom, 0.01f);  // centred on the midrib
    EXPECT_NEAR(traced.aspect_ratio, b / a, 0.02);
    EXPECT_EQ(traceLeafOutlinePNG(path).size(), poly.size());
    // Texture coordinates: the base (left of the ellipse) and the tip (right).
    EXPECT_NEAR(traced.uvAt({0, 0}).x, (200.0 - a) / 400.0, 0.005);
    EXPECT_NEAR(traced.uvAt({1, 0}).x, (200.0 + a) / 400.0, 0.005);
    EXPECT_NEAR(traced.uvAt({0.5f, 0}).y, 0.5f, 1e-6f);
    // The top of the ellipse, b pixels above the image's centre row.
    EXPECT_NEAR(traced.uvAt({0.5f, float(b / (2 * a))}).y, 0.5 + b / 200.0, 1e-4);
}

TEST_F(LeafImage, LeafBuiltFromAnImageFollowsItsAlpha) {
    const std::string path = writeEllipse("leaf.png", 300, 300, 140.0, 90.0);
    LeafPrototype proto;
    proto.leaf_texture_file = {{0, path}};
    proto.subdivisions = 10;
    Rng rng(2);
    const Mesh m = buildLeafPrototype(proto, rng, 1);  // leaflet 1 falls back to [0]
    ASSERT_NO_THROW(m.validate());
    const AABB box = bounds(m);
    EXPECT_NEAR(box.min.x, 0.0f, 1e-5f);
    EXPECT_NEAR(box.max.x, 1.0f, 1e-5f);
    EXPECT_NEAR(box.max.y - box.min.y, 90.0f / 140.0f, 0.02f);  // the image's own proportions
    // Every UV lands on an opaque pixel of the image (the ellipse, slightly shrunk).
    for (const vec2& uv : m.uvs) {
        const double dx = (uv.x * 300.0 - 150.0) / 140.0,
                     dy = ((1.0 - uv.y) * 300.0 - 150.0) / 90.0;
        EXPECT_LE(dx * dx + dy * dy, 1.03);
    }
    EXPECT_NEAR(m.area(), std::numbers::pi * 140.0 * 90.0 / (280.0 * 280.0),
                0.03 * std::numbers::pi * 140 * 90 / (280.0 * 280.0));
}

TEST_F(LeafImage, ErrorsNameTheFile) {
    const std::string missing = (dir_ / "missing.png").string();
    try {
        traceLeafOutlinePNG(missing);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), missing);
    }
    // RGB without alpha.
    const std::string rgb = (dir_ / "rgb.png").string();
    std::vector<std::uint8_t> pixels(16 * 16 * 3, 200);
    ASSERT_NE(0, stbi_write_png(rgb.c_str(), 16, 16, 3, pixels.data(), 16 * 3));
    try {
        traceLeafOutlinePNG(rgb);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), rgb);
        EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos);
    }
    // Fully transparent.
    const std::string empty = (dir_ / "empty.png").string();
    std::vector<std::uint8_t> clear(16 * 16 * 4, 0);
    ASSERT_NE(0, stbi_write_png(empty.c_str(), 16, 16, 4, clear.data(), 16 * 4));
    EXPECT_THROW(traceLeafOutlinePNG(empty), Error);
    // Not a PNG at all.
    const std::string text = (dir_ / "text.png").string();
    std::FILE* f = std::fopen(text.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("not an image", f);
    std::fclose(f);
    try {
        traceLeafOutlinePNG(text);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), text);
    }
    // The builder reports the same error.
    LeafPrototype proto;
    proto.leaf_texture_file = {{0, missing}};
    Rng rng(1);
    EXPECT_THROW(buildLeafPrototype(proto, rng), Error);
}

}  // namespace
