// Leaf blades: meshing an outline, the deformations, and building from a LeafPrototype.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/math.h"
#include "geometry/polygon_mesh.h"
#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"

namespace plantarch {

namespace {

using glm::dvec2;
using glm::dvec3;
constexpr unsigned kMinRows = 4;

// Spacing of a blade mesh's rows (fraction of the length) for `subdivisions` rows.
double rowSpacing(unsigned subdivisions) {
    return 1.0 / std::max(subdivisions, kMinRows);
}
constexpr double kPetioluleLength = 0.08;  // of the blade length, as in the reference (0.07)

std::vector<dvec2> toDouble(const std::vector<vec2>& poly) {
    std::vector<dvec2> out;
    out.reserve(poly.size());
    for (const vec2& p : poly) out.emplace_back(p.x, p.y);
    return out;
}

// Drops repeated consecutive vertices (a traced or user outline may have them).
std::vector<dvec2> withoutRepeats(std::vector<dvec2> poly) {
    std::vector<dvec2> out;
    for (const dvec2& p : poly)
        if (out.empty() || glm::length(p - out.back()) > 1e-12) out.push_back(p);
    while (out.size() > 1 && glm::length(out.front() - out.back()) <= 1e-12) out.pop_back();
    return out;
}

// The upper half of a symmetric outline as a counter-clockwise polygon closed along the
// midrib: base, tip, then the upper margin back to the base. Empty when `full` is not
// symmetric in the way leafOutline() makes it.
std::vector<dvec2> upperHalf(const std::vector<dvec2>& full) {
    const std::size_t n = full.size();
    if (n < 4 || n % 2 != 0 || std::abs(full[0].y) > 1e-7) return {};
    const std::size_t tipIndex = n / 2;
    if (std::abs(full[tipIndex].y) > 1e-7 || full[tipIndex].x <= full[0].x) return {};
    for (std::size_t i = 1; i < tipIndex; ++i) {
        const dvec2 lower = full[i], upper = full[n - i];
        if (!(lower.y < 0) || std::abs(lower.x - upper.x) > 1e-6 ||
            std::abs(lower.y + upper.y) > 1e-6)
            return {};
    }
    std::vector<dvec2> half{full[0], full[tipIndex]};
    for (std::size_t i = tipIndex + 1; i < n; ++i) half.push_back(full[i]);
    return half;
}

void appendPlanar(Mesh& mesh, const polygon::Triangulation& tri, bool mirror) {
    const auto base = std::uint32_t(mesh.positions.size());
    for (const dvec2& p : tri.points)
        mesh.positions.emplace_back(float(p.x), float(mirror ? -p.y : p.y), 0.0f);
    for (const auto& t : tri.triangles) {
        if (mirror)
            mesh.indices.insert(mesh.indices.end(), {base + t[0], base + t[2], base + t[1]});
        else
            mesh.indices.insert(mesh.indices.end(), {base + t[0], base + t[1], base + t[2]});
    }
}

// Merges vertices at identical positions (the midrib shared by the two halves).
void weld(Mesh& mesh) {
    std::vector<std::uint32_t> order(mesh.positions.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    auto less = [&](std::uint32_t a, std::uint32_t b) {
        const vec3 &p = mesh.positions[a], &q = mesh.positions[b];
        if (p.x != q.x) return p.x < q.x;
        if (p.y != q.y) return p.y < q.y;
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    std::vector<std::uint32_t> remap(mesh.positions.size());
    std::vector<std::uint32_t> keepFirst(mesh.positions.size(), 0);
    for (std::size_t k = 0; k < order.size(); ++k) {
        const bool same = k > 0 && mesh.positions[order[k]] == mesh.positions[order[k - 1]];
        remap[order[k]] = same ? remap[order[k - 1]] : order[k];
    }
    // Compact, keeping the first occurrence order.
    std::vector<std::uint32_t> newIndex(mesh.positions.size(), UINT32_MAX);
    std::vector<vec3> positions;
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i)
        if (remap[i] == i) {
            newIndex[i] = std::uint32_t(positions.size());
            positions.push_back(mesh.positions[i]);
        }
    for (std::uint32_t& idx : mesh.indices) idx = newIndex[remap[idx]];
    mesh.positions = std::move(positions);
}

void setPlanarUVs(Mesh& mesh) {
    float lo = 0.0f, hi = 0.0f;
    for (const vec3& p : mesh.positions) {
        lo = std::min(lo, p.y);
        hi = std::max(hi, p.y);
    }
    const float width = std::max(2.0f * std::max(-lo, hi), 1e-6f);
    mesh.uvs.clear();
    for (const vec3& p : mesh.positions) mesh.uvs.emplace_back(p.x, 0.5f + p.y / width);
}

// ---- deformation pieces -------------------------------------------------------------------

// The bent midrib: its angle to +x as a function of the flat x, integrated into a table of
// (x, z) positions so that its length is unchanged.
//
// The bend: the blade point at flat x drops by c x^4 and turns down about the base by c x^4
// radians more (c the longitudinal curvature), so the two add and the tip ends near 2c below
// the base in a bend that gathers toward it. That curve is longer than the flat blade (1.45
// times at c = -0.45), so here it is followed at unchanged length: the angle at a fraction of
// the blade's length is the curve's at the same fraction of its own length. A leaf's scale
// stays its length along the blade.
class Midrib {
public:
    Midrib(const LeafDeformation& d, double xLo, double xHi)
        : buckle_(d.leaf_buckle_length > 0 ? radians(double(d.leaf_buckle_angle)) : 0.0),
          buckleAt_(d.leaf_buckle_length),
          lo_(xLo),
          step_(std::max(xHi - xLo, 1e-6) / kSteps) {
        bendTable(d.longitudinal_curvature);
        // Integrate from x = 0 both ways, so the base stays at the origin.
        table_.assign(kSteps + 1, dvec2(0.0));
        const int zero = int(std::clamp(std::round(-lo_ / step_), 0.0, double(kSteps)));
        table_[zero] = {lo_ + zero * step_, 0.0};
        for (int i = zero + 1; i <= kSteps; ++i) {
            const double a = angle(lo_ + (i - 0.5) * step_);
            table_[i] = table_[i - 1] + step_ * dvec2(std::cos(a), std::sin(a));
        }
        for (int i = zero - 1; i >= 0; --i) {
            const double a = angle(lo_ + (i + 0.5) * step_);
            table_[i] = table_[i + 1] - step_ * dvec2(std::cos(a), std::sin(a));
        }
    }
    /// Angle of the midrib to +x at flat x, radians (+ turns up).
    double angle(double x) const {
        double a = bend(x);
        if (buckle_ != 0.0) {
            const double t = std::clamp((x - (buckleAt_ - kRamp)) / (2.0 * kRamp), 0.0, 1.0);
            a -= buckle_ * t * t * (3.0 - 2.0 * t);
        }
        return a;
    }
    /// Position (x, z) of the midrib at flat x.
    dvec2 point(double x) const {
        const double f = std::clamp((x - lo_) / step_, 0.0, double(kSteps));
        const int i = std::min(int(f), kSteps - 1);
        return glm::mix(table_[i], table_[i + 1], f - i);
    }

private:
    static constexpr int kSteps = 4096;
    static constexpr int kBendSteps = 512;
    static constexpr double kRamp = 0.025;  // half-length of the buckle crease

    // bend_[j]: the curve's angle at the fraction j / kBendSteps of its length.
    void bendTable(double c) {
        if (c == 0.0) return;
        // The curve (x cos t + z sin t, z cos t - x sin t), z = c x^4, t = -c x^4,
        // finely sampled: its segments' angles at their arc-length midpoints.
        constexpr int n = 4 * kBendSteps;
        std::vector<double> at(n), ang(n);
        dvec2 prev(0.0);
        double length = 0.0;
        for (int i = 1; i <= n; ++i) {
            const double x = double(i) / n, z = c * x * x * x * x, t = -z;
            const dvec2 q(x * std::cos(t) + z * std::sin(t), z * std::cos(t) - x * std::sin(t));
            const dvec2 seg = q - prev;
            const double l = glm::length(seg);
            at[i - 1] = length + 0.5 * l;
            ang[i - 1] = std::atan2(seg.y, seg.x);
            // Unwrapped, so a blade curled past the vertical turns on without a jump.
            if (i > 1)
                ang[i - 1] -= 2.0 * std::numbers::pi *
                              std::round((ang[i - 1] - ang[i - 2]) / (2.0 * std::numbers::pi));
            length += l;
            prev = q;
        }
        bend_.assign(kBendSteps + 1, 0.0);
        int k = 0;
        for (int j = 0; j <= kBendSteps; ++j) {
            const double u = length * j / kBendSteps;
            while (k + 1 < n - 1 && at[k + 1] < u) ++k;
            const double f = std::clamp((u - at[k]) / (at[k + 1] - at[k]), 0.0, 1.0);
            bend_[j] = ang[k] + f * (ang[k + 1] - ang[k]);
        }
    }
    // The bend's angle at flat x (a fraction of the blade's length; beyond the tip, the tip's).
    double bend(double x) const {
        if (bend_.empty()) return 0.0;
        const double f = std::clamp(x, 0.0, 1.0) * kBendSteps;
        const int i = std::min(int(f), kBendSteps - 1);
        return bend_[i] + (f - i) * (bend_[i + 1] - bend_[i]);
    }

    double buckle_, buckleAt_, lo_, step_;
    std::vector<double> bend_;
    std::vector<dvec2> table_;
};

// Radial pleats about a centre on the midrib (see deformLeafMesh()): flat panels between
// straight creases, a ridge on the midrib and every 2 pi / n about the centre, a furrow
// halfway between. At folded angle u a point rises by A s(u) of its distance, s the triangle
// wave (2 / pi) asin(cos(n u)) (1 on a ridge, -1 in a furrow); its slope across the panels,
// 2 A n / pi, is the same everywhere, so arcs about the centre keep their length when the flat
// angle phi folds to u = phi / g, g = sqrt(1 + (2 A n / pi)^2).
class Pleats {
public:
    Pleats(int count, double depth)
        : n_(count),
          a_(depth),
          g_(std::sqrt(1.0 + std::pow(2.0 * depth * count / std::numbers::pi, 2.0))) {}
    bool active() const { return n_ > 0 && a_ != 0.0; }
    /// The flat angle that folds to `u`.
    double flatAngle(double u) const { return g_ * u; }
    /// The folded (x, y, z) of the flat point (x, y) about the centre (cx, 0).
    dvec3 fold(double x, double y, double cx) const {
        const double dx = x - cx, r = std::hypot(dx, y);
        if (r == 0.0) return {x, y, 0.0};
        const double u = std::atan2(y, dx) / g_;
        const double c = a_ * 2.0 / std::numbers::pi * std::asin(std::cos(n_ * u));
        const double r2 = r / std::sqrt(1.0 + c * c);  // each ray keeps its length
        return {cx + r2 * std::cos(u), r2 * std::sin(u), c * r2};
    }
    /// Vertices for a blade about (cx, 0) whose rows are `spacing` apart, out to `reach`: on
    /// rings `spacing` apart, on every crease where neighbouring creases lie at least half a
    /// spacing apart on the ring, and halfway between creases where they lie more than 1.6
    /// spacings apart.
    std::vector<vec2> vertices(double cx, double spacing, double reach) const {
        const double step = std::numbers::pi / n_;  // ridge to furrow, in folded angle
        const double gap = flatAngle(step);         // the same, flat
        std::vector<vec2> out;
        for (double r = spacing; r < reach; r += spacing)
            for (int k = -2 * n_; k <= 2 * n_; ++k) {
                const double phi = flatAngle(0.5 * k * step);
                if (std::abs(phi) >= std::numbers::pi) continue;  // beyond the blade's back
                if (k % 2 == 0 ? r * gap < 0.5 * spacing : r * gap <= 1.6 * spacing) continue;
                out.emplace_back(float(cx + r * std::cos(phi)), float(r * std::sin(phi)));
            }
        return out;
    }

private:
    int n_;
    double a_, g_;
};

// The extent in x of a mesh's vertices.
struct ExtentX {
    float lo = 0.0f, hi = 0.0f;
};

ExtentX extentX(const std::vector<vec3>& positions) {
    AABB box;
    for (const vec3& p : positions) box.add(p);
    return {box.min.x, box.max.x};
}

// Scales uniformly about the origin and shifts in x so that `e` becomes [0, 1]. Given the
// extent of a flat blade, this makes its length along the blade 1 whatever the bending did to
// its projection.
void normalizeLength(Mesh& mesh, ExtentX e) {
    const float length = e.hi - e.lo;
    if (!(length > 1e-6f)) return;
    const float scale = 1.0f / length;
    for (vec3& p : mesh.positions) p = vec3(p.x - e.lo, p.y, p.z) * scale;
}

Mesh petiolule(double length, double radius) {
    constexpr unsigned sides = 6, rings = 4;
    Mesh m;
    for (unsigned i = 0; i <= rings; ++i) {
        const double t = double(i) / rings;
        const double r = radius * (1.0 - 0.35 * t);
        for (unsigned k = 0; k < sides; ++k) {
            const double a = 2.0 * std::numbers::pi * k / sides;
            m.positions.emplace_back(float(t * length), float(r * std::cos(a)),
                                     float(r * std::sin(a)));
            m.uvs.emplace_back(0.02f, 0.5f);
        }
    }
    for (unsigned i = 0; i < rings; ++i)
        for (unsigned k = 0; k < sides; ++k) {
            const std::uint32_t a = i * sides + k, b = i * sides + (k + 1) % sides;
            m.indices.insert(m.indices.end(), {a, b, b + sides, a, b + sides, a + sides});
        }
    return m;
}

float clampedDraw(const RandomFloat& value, Rng& rng, float lo, float hi) {
    const float v = value.sample(rng);
    return std::isfinite(v) ? std::clamp(v, lo, hi) : lo;
}

}  // namespace

// ---- meshing -----------------------------------------------------------------------------

Mesh meshLeafOutline(const std::vector<vec2>& outline, const LeafMeshOptions& options) {
    std::vector<dvec2> poly = withoutRepeats(toDouble(outline));
    if (poly.size() < 3) throw Error("leaf outline has fewer than 3 vertices");
    if (polygon::signedArea(poly) < 0) std::reverse(poly.begin(), poly.end());
    if (!polygon::isSimple(poly)) throw Error("leaf outline is not a simple polygon");
    const double spacing = rowSpacing(options.subdivisions);

    Mesh mesh;
    const std::vector<dvec2> half = options.symmetric ? upperHalf(poly) : std::vector<dvec2>{};
    std::vector<dvec2> interior;
    for (const vec2& q : options.interior_points)
        if (half.empty() || q.y > 0.0f) interior.emplace_back(q);
    if (!half.empty()) {
        const polygon::Triangulation tri = polygon::triangulate(half, spacing, interior);
        appendPlanar(mesh, tri, false);
        appendPlanar(mesh, tri, true);
        weld(mesh);
    } else {
        appendPlanar(mesh, polygon::triangulate(poly, spacing, interior), false);
    }
    setPlanarUVs(mesh);
    return mesh;
}

// ---- deformation -------------------------------------------------------------------------

void deformLeafMesh(Mesh& mesh, const LeafDeformation& d) {
    if (mesh.positions.empty()) return;
    float xLo = 0.0f, xHi = 1.0f, yMax = 0.0f;
    for (const vec3& p : mesh.positions) {
        xLo = std::min(xLo, p.x);
        xHi = std::max(xHi, p.x);
        yMax = std::max(yMax, std::abs(p.y));
    }
    const double width = d.blade_width > 0 ? d.blade_width : 2.0 * yMax;
    const double foldBase =
        std::clamp(double(d.midrib_fold_fraction), -1.0, 1.0) * 0.5 * std::numbers::pi;
    const double roll = radians(double(d.petiole_roll));
    const bool waves = d.wave_period > 1e-6f && d.wave_amplitude != 0.0f;
    const Midrib midrib(d, xLo, xHi);
    const ExtentX flat = extentX(mesh.positions);
    const Pleats pleats(d.pleats, d.pleat_depth);

    for (vec3& v : mesh.positions) {
        double x = v.x, y = v.y, pleat = 0.0;
        if (pleats.active()) {
            const dvec3 f = pleats.fold(x, y, d.pleat_center_x);
            x = f.x;
            y = f.y;
            pleat = f.z;
        }
        const double side = y < 0 ? -1.0 : 1.0, across = std::abs(y);
        // Cross-section in the blade's own frame: (across, z).
        double z = v.z + pleat + d.lateral_curvature * (y / width) * (y / width) / 4.0;
        if (waves)
            z += d.wave_amplitude * 2.0 * across *
                 std::sin(std::numbers::pi * x / d.wave_period +
                          (side > 0 ? std::numbers::pi : 0.0));
        const double fold = foldBase + roll * std::exp(-std::max(x, 0.0) / 0.05);
        const double a = across * std::cos(fold) - z * std::sin(fold);
        const double b = across * std::sin(fold) + z * std::cos(fold);
        // Place the cross-section on the bent midrib.
        const dvec2 m = midrib.point(x);
        const double theta = midrib.angle(x);
        const dvec2 normal(-std::sin(theta), std::cos(theta));  // in the (x, z) plane
        v = vec3(float(m.x + b * normal.x), float(side * a), float(m.y + b * normal.y));
    }
    if (d.normalize_length) normalizeLength(mesh, flat);
}

// ---- from a LeafPrototype ----------------------------------------------------------------

std::string leafTextureFile(const LeafPrototype& proto, int leafletIndex) {
    auto it = proto.leaf_texture_file.find(leafletIndex);
    if (it == proto.leaf_texture_file.end()) it = proto.leaf_texture_file.find(0);
    return it == proto.leaf_texture_file.end() ? std::string() : it->second;
}

RealizedLeafShape realizeLeafShape(const LeafPrototype& proto, Rng& rng, int leafletIndex) {
    RealizedLeafShape r;
    LeafOutlineParams& o = r.outline;
    leafShapeName(proto.shape);  // throws for a value that is not a declared family
    o.shape = proto.shape;
    o.aspect_ratio = clampedDraw(proto.leaf_aspect_ratio, rng, 0.01f, 4.0f);
    o.widest_point = clampedDraw(proto.widest_point, rng, 0.05f, 0.95f);
    o.tip_angle = clampedDraw(proto.tip_angle, rng, 1.0f, 180.0f);
    o.base_angle = clampedDraw(proto.base_angle, rng, 1.0f, 360.0f);
    o.base_width = clampedDraw(proto.base_width, rng, 0.0f, 0.95f);
    o.sinus_depth = clampedDraw(proto.sinus_depth, rng, 0.01f, 0.6f);
    o.lobes = std::clamp(proto.lobes.sample(rng), 0, 31);
    o.lobe_depth = clampedDraw(proto.lobe_depth, rng, 0.0f, 0.9f);
    o.serrations = std::clamp(proto.serrations.sample(rng), 0, 200);
    o.serration_depth = clampedDraw(proto.serration_depth, rng, 0.0f, 0.1f);

    LeafDeformation& d = r.deformation;
    d.midrib_fold_fraction = clampedDraw(proto.midrib_fold_fraction, rng, -1.0f, 1.0f);
    d.longitudinal_curvature = clampedDraw(proto.longitudinal_curvature, rng, -2.0f, 2.0f);
    d.lateral_curvature = clampedDraw(proto.lateral_curvature, rng, -5.0f, 5.0f);
    d.petiole_roll = clampedDraw(proto.petiole_roll, rng, -180.0f, 180.0f);
    d.wave_period = clampedDraw(proto.wave_period, rng, 0.0f, 1.0f);
    d.wave_amplitude = clampedDraw(proto.wave_amplitude, rng, 0.0f, 0.5f);
    d.leaf_buckle_length = clampedDraw(proto.leaf_buckle_length, rng, 0.0f, 1.0f);
    d.leaf_buckle_angle = clampedDraw(proto.leaf_buckle_angle, rng, -180.0f, 180.0f);
    d.pleats = std::clamp(proto.pleats.sample(rng), 0, 31);
    d.pleat_depth = clampedDraw(proto.pleat_depth, rng, -0.5f, 0.5f);
    d.blade_width = o.aspect_ratio;

    r.subdivisions = proto.subdivisions;
    r.build_petiolule = proto.build_petiolule;
    r.leaf_offset = proto.leaf_offset;
    r.texture_file = leafTextureFile(proto, leafletIndex);
    return r;
}

Mesh buildLeafMesh(const RealizedLeafShape& leaf) {
    Mesh mesh;
    LeafDeformation deformation = leaf.deformation;
    LeafMeshOptions options{.subdivisions = leaf.subdivisions};
    vec2 attach(0.0f);  // where the petiole meets the blade (the sinus of notched outlines)
    if (!leaf.texture_file.empty()) {
        const TracedLeafOutline traced = traceLeafImage(leaf.texture_file);
        options.symmetric = false;
        mesh = meshLeafOutline(traced.outline, options);
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            mesh.uvs[i] = traced.uvAt(vec2(mesh.positions[i]));
        deformation.blade_width = 0.0f;  // the traced width
    } else {
        // The outline is kept as close to the curve as the mesh resolution can show: about
        // a twentieth of a row's spacing (never coarser than 1 % of the length), so a coarse
        // leaf does not carry hundreds of margin vertices into every copy.
        LeafOutlineParams params = leaf.outline;
        const double row = 1.0 / std::max(1u, leaf.subdivisions);
        params.tolerance =
            float(std::clamp(0.05 * row * row * 4.0, double(params.tolerance), 0.01));
        const std::vector<vec2> outline = leafOutline(params);
        attach = outline.front();
        deformation.pleat_center_x = attach.x;
        const Pleats pleats(deformation.pleats, deformation.pleat_depth);
        if (pleats.active()) {
            double reach = 0.0;
            for (const vec2& q : outline)
                reach = std::max(reach, double(glm::length(q - vec2(attach.x, 0.0f))));
            options.interior_points =
                pleats.vertices(attach.x, rowSpacing(leaf.subdivisions), reach);
        }
        mesh = meshLeafOutline(outline, options);
        // Texture space is the blade's bounding box of width leaf_aspect_ratio.
        const float width = std::max(leaf.outline.aspect_ratio, 1e-6f);
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            mesh.uvs[i] = {mesh.positions[i].x, 0.5f + mesh.positions[i].y / width};
    }
    // Follow the attachment point through the deformation as an extra vertex that no
    // triangle uses.
    mesh.positions.emplace_back(attach.x, attach.y, 0.0f);
    mesh.uvs.emplace_back(0.0f, 0.5f);
    // The flat blade, normalized as deformLeafMesh normalizes the bent one: on its stalk it
    // gives a stalked leaf's length (below).
    Mesh flat;
    if (leaf.build_petiolule) {
        flat.positions = mesh.positions;
        normalizeLength(flat, extentX(flat.positions));
    }
    deformation.normalize_length = true;
    deformLeafMesh(mesh, deformation);
    const vec3 attached = mesh.positions.back();
    mesh.positions.pop_back();
    mesh.uvs.pop_back();

    if (leaf.build_petiolule) {
        // The stalk runs along +x from the origin into the attachment point. The leaf's length
        // along it is that of the flat blade on its stalk, whatever the bending.
        const Mesh stalk = petiolule(kPetioluleLength + 0.01, 0.012);
        for (vec3& p : mesh.positions) p += vec3(float(kPetioluleLength), 0.0f, 0.0f) - attached;
        const vec3 flatAttached = flat.positions.back();
        flat.positions.pop_back();
        for (vec3& p : flat.positions)
            p += vec3(float(kPetioluleLength), 0.0f, 0.0f) - flatAttached;
        flat.positions.insert(flat.positions.end(), stalk.positions.begin(), stalk.positions.end());
        mesh.append(stalk);
        normalizeLength(mesh, extentX(flat.positions));
    }
    for (vec3& p : mesh.positions) p += leaf.leaf_offset;
    return mesh;
}

Mesh buildLeafPrototype(const LeafPrototype& proto, Rng& rng, int leafletIndex) {
    return buildLeafMesh(realizeLeafShape(proto, rng, leafletIndex));
}

}  // namespace plantarch
