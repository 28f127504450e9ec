// Levels of detail of an exported scene (scene_lod.h): objects simplified one at a time by
// meshoptimizer, or replaced by cards fitted to their main directions.

#include "scene_io/scene_lod.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh_simplify.h"
#include "core/parallel.h"
#include "core/symmetric_eigen.h"
#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch {

const char* gltfLevelName(GltfLevel::Kind kind) {
    return kind == GltfLevel::Kind::Cards ? "cards" : "reduced";
}

float gltfLevelCoverage(const std::vector<GltfLevel>& levels, std::size_t i) {
    if (levels.at(i).coverage != 0.0f) return levels[i].coverage;
    return float(0.4 / std::pow(3.0, double(i)));
}

void checkGltfLevels(const std::vector<GltfLevel>& levels) {
    float above = 1.0f;
    for (std::size_t i = 0; i < levels.size(); ++i) {
        const GltfLevel& l = levels[i];
        const float coverage = gltfLevelCoverage(levels, i);
        const std::string at = "levels/" + std::to_string(i);
        if (l.kind == GltfLevel::Kind::Reduced && !(l.share > 0.0f && l.share < 1.0f))
            throw Error("not a share of triangles", {.parameter = at + "/share",
                                                     .value = text::formatDouble(l.share),
                                                     .validRange = "above 0 and below 1"});
        if (!(coverage > 0.0f && coverage < above))
            throw Error("screen coverages must fall from level to level",
                        {.parameter = at + "/coverage",
                         .value = text::formatDouble(coverage),
                         .validRange = "above 0 and below " + text::formatDouble(above)});
        above = coverage;
    }
}

namespace io {

namespace {

using glm::dmat3;
using glm::dvec3;

// The object's meshes of a level, made on all threads (each object on its own), then set in
// object order: the same bytes whatever the thread count.
template <class Make>
Context eachObject(const Context& ctx, Make make) {
    Context out(ctx);
    const std::vector<ObjectID> ids = ctx.objectIDs();
    std::vector<Mesh> meshes(ids.size());
    ParallelErrors errors;
    const std::ptrdiff_t n = std::ptrdiff_t(ids.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t i = 0; i < n; ++i)
        errors.run(i, [&] {
            const ObjectID id = ids[std::size_t(i)];
            meshes[std::size_t(i)] = make(ctx.objectMesh(id), id);
        });
    errors.rethrow();
    for (std::size_t i = 0; i < ids.size(); ++i)
        if (!meshes[i].empty()) out.setObjectMesh(ids[i], meshes[i]);
    return out;
}

// The symmetric 3x3 matrix's eigenvectors, ordered by decreasing eigenvalue.
std::array<dvec3, 3> mainDirections(const dmat3& m) {
    std::array<std::array<double, 3>, 3> a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[std::size_t(i)][std::size_t(j)] = m[i][j];
    const SymmetricEigen<3> e = symmetricEigen<3>(a);
    std::array<dvec3, 3> v;
    for (std::size_t k = 0; k < 3; ++k)
        v[k] = dvec3(e.vectors[k][0], e.vectors[k][1], e.vectors[k][2]);
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](int i, int j) { return e.values[std::size_t(i)] > e.values[std::size_t(j)]; });
    std::array<dvec3, 3> out;
    for (int k = 0; k < 3; ++k)
        out[std::size_t(k)] = glm::normalize(v[std::size_t(order[std::size_t(k)])]);
    // Right-handed, each pointing to its positive side, so that the cards do not flip.
    for (dvec3& d : out) {
        const int big = std::abs(d.x) >= std::abs(d.y) && std::abs(d.x) >= std::abs(d.z)
                            ? 0
                            : (std::abs(d.y) >= std::abs(d.z) ? 1 : 2);
        if (d[big] < 0) d = -d;
    }
    out[2] = glm::cross(out[0], out[1]);
    return out;
}

// One quad of corners (s, t) along directions a and b from c (counter-clockwise), its UVs
// fitted to the object's.
void addQuad(Mesh& card, const Mesh& m, dvec3 c, dvec3 a, dvec3 b,
             const std::array<glm::dvec2, 4>& corners) {
    const std::uint32_t first = std::uint32_t(card.positions.size());
    for (const glm::dvec2& q : corners) card.positions.push_back(vec3(c + q.x * a + q.y * b));
    if (m.hasUVs()) {
        // uv = u0 + U s + V t by least squares over the object's vertices (s, t along a, b).
        dmat3 n(0.0);
        dvec3 ru(0.0), rv(0.0);
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            const dvec3 d = dvec3(m.positions[i]) - c;
            const dvec3 x(1.0, glm::dot(d, a), glm::dot(d, b));
            n += glm::outerProduct(x, x);
            ru += x * double(m.uvs[i].x);
            rv += x * double(m.uvs[i].y);
        }
        const bool solvable = std::abs(glm::determinant(n)) > 1e-18 * std::pow(n[0][0], 3.0);
        const dmat3 inv = solvable ? glm::inverse(n) : dmat3(0.0);
        dvec3 cu = inv * ru, cv = inv * rv;
        if (!solvable) {  // the mean UV
            cu = {ru.x / std::max(n[0][0], 1.0), 0.0, 0.0};
            cv = {rv.x / std::max(n[0][0], 1.0), 0.0, 0.0};
        }
        for (const glm::dvec2& q : corners) {
            const dvec3 x(1.0, q.x, q.y);
            card.uvs.emplace_back(float(glm::dot(cu, x)), float(glm::dot(cv, x)));
        }
    }
    for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) card.indices.push_back(first + k);
}

std::array<glm::dvec2, 4> box(double s0, double t0, double s1, double t1) {
    return {glm::dvec2(s0, t0), glm::dvec2(s1, t0), glm::dvec2(s1, t1), glm::dvec2(s0, t1)};
}

Mesh cardOf(const Mesh& m, bool leaf, bool textured) {
    if (m.empty()) return m;
    // Area-weighted centre and second moments of the surface (vertices of each triangle
    // weighted by a third of its area).
    double area = 0.0;
    dvec3 c(0.0);
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const dvec3 p0(m.positions[m.indices[t]]), p1(m.positions[m.indices[t + 1]]),
            p2(m.positions[m.indices[t + 2]]);
        const double a = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        area += a;
        c += a * (p0 + p1 + p2) / 3.0;
    }
    if (!(area > 0.0)) return Mesh{};  // nothing to see: the object keeps its mesh
    c /= area;
    dmat3 cov(0.0);
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const dvec3 p0(m.positions[m.indices[t]]), p1(m.positions[m.indices[t + 1]]),
            p2(m.positions[m.indices[t + 2]]);
        const double a = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0)) / 3.0;
        for (const dvec3& p : {p0, p1, p2}) cov += a * glm::outerProduct(p - c, p - c);
    }
    const std::array<dvec3, 3> dir = mainDirections(cov);
    dvec3 lo(1e300), hi(-1e300);
    for (const vec3& p : m.positions) {
        const dvec3 d = dvec3(p) - c;
        const dvec3 q(glm::dot(d, dir[0]), glm::dot(d, dir[1]), glm::dot(d, dir[2]));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    const dvec3 size = hi - lo;
    Mesh card;
    if (leaf || size.z <= 0.75 * size.y) {
        // Flat: one quad in its plane. With a texture image, over its whole extent (the
        // texture's alpha draws the outline); without, a rhombus whose widest point is at the
        // organ's centre of area, no larger than the organ's own area, so that the colour
        // covers what the organ covered.
        const dvec3 mid = c + dir[2] * (0.5 * (lo.z + hi.z));
        if (textured) {
            addQuad(card, m, mid, dir[0], dir[1], box(lo.x, lo.y, hi.x, hi.y));
        } else {
            const double k =
                std::min(1.0, std::sqrt(area / std::max(0.5 * size.x * size.y, 1e-300)));
            addQuad(card, m, mid, dir[0], dir[1],
                    {glm::dvec2(k * lo.x, 0.0), glm::dvec2(0.0, k * lo.y),
                     glm::dvec2(k * hi.x, 0.0), glm::dvec2(0.0, k * hi.y)});
        }
    } else {
        // Round or long: two crossed quads through its middle along its main direction.
        addQuad(card, m, c + dir[2] * (0.5 * (lo.z + hi.z)), dir[0], dir[1],
                box(lo.x, lo.y, hi.x, hi.y));
        addQuad(card, m, c + dir[1] * (0.5 * (lo.y + hi.y)), dir[0], dir[2],
                box(lo.x, lo.z, hi.x, hi.z));
    }
    if (!m.hasUVs()) card.uvs.clear();
    return card;
}

}  // namespace

Context reducedLevel(const Context& ctx, float share) {
    return eachObject(ctx, [share](const Mesh& m, ObjectID) {
        const std::size_t target =
            std::max<std::size_t>(1, std::size_t(double(m.triangleCount()) * double(share) + 0.5));
        if (m.triangleCount() <= target) return Mesh{};
        return meshes::simplified(m, {.targetTriangles = target, .maxError = 0.1f});
    });
}

Context cardLevel(const Context& ctx) {
    return eachObject(ctx, [&ctx](const Mesh& m, ObjectID id) {
        Mesh card = cardOf(m, ctx.objectDataString(id, "organ").value_or("") == "leaf",
                           !ctx.material(ctx.objectMaterial(id)).texture.empty());
        // A card never has more triangles than the object it stands for.
        return card.triangleCount() < m.triangleCount() ? card : Mesh{};
    });
}

Context lodLevel(const Context& ctx, const GltfLevel& level) {
    return level.kind == GltfLevel::Kind::Cards ? cardLevel(ctx) : reducedLevel(ctx, level.share);
}

}  // namespace io

}  // namespace plantarch

namespace plantarch {

std::vector<GltfLevel> parseGltfLevels(std::string_view text, const std::string& option) {
    std::vector<GltfLevel> levels;
    if (text.empty() || text == "none") return levels;
    const std::string form =
        "none, or comma-separated reduced, reduced:SHARE (0 < SHARE < 1) or cards, each "
        "optionally @COVERAGE, e.g. reduced,cards or reduced:0.1@0.3,cards@0.05";
    auto bad = [&](const std::string& why) {
        return Error(why, {.parameter = option, .value = std::string(text), .validRange = form});
    };
    auto number = [&](std::string_view t) {
        float v = 0.0f;
        if (!text::readNumber(t, v) || !std::isfinite(v)) throw bad("not a number");
        return v;
    };
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        std::string_view item = text.substr(start, comma - start);
        start = comma + 1;
        GltfLevel level;
        if (const std::size_t at = item.find('@'); at != std::string_view::npos) {
            level.coverage = number(item.substr(at + 1));
            if (level.coverage == 0.0f) throw bad("a screen coverage of 0");
            item = item.substr(0, at);
        }
        if (item == "cards") {
            level.kind = GltfLevel::Kind::Cards;
        } else if (item == "reduced") {
            level.kind = GltfLevel::Kind::Reduced;
        } else if (item.starts_with("reduced:")) {
            level.kind = GltfLevel::Kind::Reduced;
            level.share = number(item.substr(8));
        } else {
            throw bad("unknown level of detail");
        }
        levels.push_back(level);
        if (levels.size() > 8) throw bad("more than 8 levels of detail");
    }
    try {
        checkGltfLevels(levels);
    } catch (const Error& e) {
        throw bad(e.message());
    }
    return levels;
}

}  // namespace plantarch
