// Built-in organ prototypes registered in every PlantArchitecture: a generic procedural leaf
// and simple flower and fruit shapes used when a species names none. All follow the
// prototype convention: unit length along +x, base at the origin, +z up.

#include "geometry/builtin_prototypes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/OrganLibrary.h"

namespace plantarch {

namespace {

// A closed surface of revolution about +x from x=0 to x=1 with radius profile r(t).
template <class Profile>
Mesh revolve(Profile r, unsigned rings, unsigned sides) {
    Mesh m;
    m.positions.push_back({0, 0, 0});
    m.uvs.push_back({0, 0.5f});
    for (unsigned i = 1; i < rings; ++i) {
        const float t = float(i) / float(rings);
        for (unsigned k = 0; k < sides; ++k) {
            const float a = 2.0f * kPi * float(k) / float(sides);
            m.positions.push_back({t, r(t) * std::cos(a), r(t) * std::sin(a)});
            m.uvs.push_back({t, float(k) / float(sides)});
        }
    }
    m.positions.push_back({1, 0, 0});
    m.uvs.push_back({1, 0.5f});
    const std::uint32_t last = std::uint32_t(m.positions.size() - 1);
    for (unsigned k = 0; k < sides; ++k) {
        const std::uint32_t a = 1 + k, b = 1 + (k + 1) % sides;
        m.indices.insert(m.indices.end(), {0, b, a});
    }
    for (unsigned i = 0; i + 2 < rings; ++i)
        for (unsigned k = 0; k < sides; ++k) {
            const std::uint32_t a = 1 + i * sides + k, b = 1 + i * sides + (k + 1) % sides;
            const std::uint32_t c = a + sides, d = b + sides;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    const std::uint32_t ringStart = 1 + (rings - 2) * sides;
    for (unsigned k = 0; k < sides; ++k) {
        const std::uint32_t a = ringStart + k, b = ringStart + (k + 1) % sides;
        m.indices.insert(m.indices.end(), {a, b, last});
    }
    return m;
}

OrganPrototype builtinFruit(const FloralPrototypeRequest& req, Rng&) {
    Mesh m = revolve(
        [](float t) { return 0.45f * std::sqrt(std::max(0.0f, t * (1.0f - t))) * 2.0f; }, 12, 12);
    return {{std::move(m), Material{req.color, "", "fruit"}}};
}

OrganPrototype builtinFlower(const FloralPrototypeRequest& req, Rng&) {
    const bool open = req.open;
    OrganPrototype proto;
    if (!open) {
        Mesh bud =
            revolve([](float t) { return 0.3f * std::sin(kPi * t) * (1.0f - 0.4f * t); }, 8, 8);
        proto.push_back({std::move(bud), Material{{0.92f, 0.92f, 0.80f}, "", "flower_bud"}});
        return proto;
    }
    // Five petals, each a flat ellipse (half-width 0.22) from the centre outward, fanned
    // around the +x axis and opened 60 degrees from it.
    Mesh petal;
    const unsigned seg = 8;
    petal.positions.push_back({0, 0, 0});
    for (unsigned k = 0; k <= seg; ++k) {
        const float t = kPi * float(k) / float(seg);
        petal.positions.push_back({0.5f - 0.5f * std::cos(t), 0.22f * std::sin(t), 0.0f});
    }
    for (unsigned k = 1; k < seg; ++k)
        petal.positions.push_back({petal.positions[k + 1].x, -petal.positions[k + 1].y, 0.0f});
    // Fan: centre 0, upper edge 1..seg+1, lower edge seg+2.. (mirrors of 2..seg).
    for (unsigned k = 1; k <= seg; ++k) petal.indices.insert(petal.indices.end(), {0, k, k + 1});
    const std::uint32_t lower = seg + 2;
    for (unsigned k = 1; k < seg; ++k) {
        const std::uint32_t a = k == 1 ? 1 : lower + k - 2, b = lower + k - 1;
        petal.indices.insert(petal.indices.end(), {0, b, a});
    }
    petal.indices.insert(petal.indices.end(), {0, seg + 1, lower + seg - 2});
    Mesh petals;
    const unsigned n = 5;
    for (unsigned p = 0; p < n; ++p) {
        const float around = 2.0f * kPi * float(p) / float(n);
        const float open60 = kPi / 3.0f;
        const vec3 radial{0.0f, std::cos(around), std::sin(around)};
        const vec3 axis =
            glm::normalize(std::cos(open60) * vec3(1, 0, 0) + std::sin(open60) * radial);
        const vec3 width = glm::normalize(glm::cross(vec3(1, 0, 0), radial));
        mat4 xf(1.0f);
        xf[0] = glm::vec4(axis, 0);
        xf[1] = glm::vec4(width, 0);
        xf[2] = glm::vec4(glm::cross(axis, width), 0);
        petals.append(petal, xf);
    }
    proto.push_back({std::move(petals), Material{req.color, "", "petals"}});
    Mesh centre = revolve([](float t) { return 0.12f * std::sin(kPi * t); }, 6, 8);
    centre.transform(glm::mat4(0.25f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1));
    proto.push_back({std::move(centre), Material{{0.95f, 0.8f, 0.1f}, "", "flower_centre"}});
    return proto;
}

// A slender needle (cladodes, conifer needles), in prototype units (length 1 along +x from
// the origin): a three-sided prism of diameter leaf_aspect_ratio that closes to a point over
// its last 5 %. Its faces are as wide in all as the round tube of that diameter is around
// (a perimeter of pi x diameter), so its surface is the tube's, the leaf area a needle counts.
// `subdivisions` sets the segments along the prism (at most 8): 10 to 52 triangles, where a
// flat needle outline meshed to its true shape takes about 150.
OrganPrototype taperedSpine(const LeafPrototype& p, Rng& rng, int) {
    constexpr int kSides = 3;
    constexpr float kPoint = 0.95f;  // where the point begins
    // An equilateral triangle of circumradius R has perimeter 3 sqrt(3) R.
    const float radius = kPi * p.leaf_aspect_ratio.sample(rng) / (3.0f * std::sqrt(3.0f));
    const int segments = int(std::clamp(p.subdivisions, 1u, 8u));
    Mesh m;
    for (int k = 0; k <= segments; ++k) {  // rings from the base to where the point begins
        const float x = kPoint * float(k) / float(segments);
        for (int j = 0; j < kSides; ++j) {
            const float a = 2.0f * kPi * float(j) / float(kSides);
            m.positions.push_back({x, radius * std::cos(a), radius * std::sin(a)});
        }
    }
    const auto tip = std::uint32_t(m.positions.size());
    m.positions.push_back({1.0f, 0.0f, 0.0f});
    auto ring = [](int k, int j) { return std::uint32_t(k * kSides + (j % kSides)); };
    for (int k = 0; k <= segments; ++k)
        for (int j = 0; j < kSides; ++j) {
            if (k < segments) {
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k, j + 1), ring(k + 1, j + 1)});
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k + 1, j + 1), ring(k + 1, j)});
            } else {
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k, j + 1), tip});
            }
        }
    m.indices.insert(m.indices.end(), {ring(0, 0), ring(0, 2), ring(0, 1)});  // the base
    return OrganPrototype{{std::move(m), Material{p.color, "", "leaf"}}};
}

}  // namespace

BuiltinPrototypes builtinPrototypes() {
    BuiltinPrototypes b;
    // Procedural leaves: the outline family (or a traced PNG, which then also textures the
    // leaf), meshed to the outline and deformed.
    b.leaves.emplace_back("procedural", [](const LeafPrototype& p, Rng& rng, int leaflet) {
        return OrganPrototype{{buildLeafPrototype(p, rng, leaflet),
                               Material{p.color, leafTextureFile(p, leaflet), "leaf"}}};
    });
    b.leaves.emplace_back("tapered_spine", taperedSpine);
    b.floral = floralFamilyFunctions();
    b.floral.emplace_back("builtin_fruit", builtinFruit);
    b.floral.emplace_back("builtin_flower", builtinFlower);
    return b;
}

}  // namespace plantarch
