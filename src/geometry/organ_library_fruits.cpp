// Fleshy fruit families of the organ library: berries (smooth or ribbed, bare or in a husk),
// berry clusters, hollow berries, accessory fruit with achenes on the surface, and pomes.
//
// Frame: the fruit hangs from its stem, which starts at the origin and runs along +x into
// the fruit; the blossom end is at x = 1. Sizes are fractions of the fruit's diameter before
// the prototype is scaled to unit length.

#include <algorithm>
#include <cmath>

#include "geometry/organ_library_internal.h"

namespace plantarch::organs {

namespace {

const vec3 kCalyxGreen{0.26f, 0.42f, 0.14f};

// ---- berry --------------------------------------------------------------------------------------

FloralFamilyInfo berryInfo() {
    FloralFamilyInfo f;
    f.name = "berry";
    f.fruit = true;
    f.description =
        "Round fleshy fruit on a short stem under a star of sepals: oblate and ribbed, round "
        "and smooth, or elongated, bare or inside an inflated, papery, five-angled lantern "
        "husk (the enlarged calyx).";
    f.defaultColor = {0.85f, 0.14f, 0.07f};
    f.parts = {"fruit", "calyx", "husk"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 1.0f, 0.4f, 3.0f,
                     "Fruit length along the stem axis / diameter (below 1 = oblate)"));
    t.push_back(whole("ribs", 0, 0, 16, "Lobes around the fruit (0 = smooth)"));
    t.push_back(real("rib_depth", 0.06f, 0.0f, 0.3f,
                     "Depth of the grooves between lobes, fraction of the radius"));
    t.push_back(real("shoulder_dent", 0.04f, 0.0f, 0.2f,
                     "Depression around the stem, fraction of the diameter"));
    t.push_back(whole("sepal_count", 5, 0, 12, "Sepals of the calyx star (0 = none)"));
    t.push_back(
        real("sepal_length", 0.35f, 0.02f, 1.5f, "Sepal length, fraction of the fruit diameter"));
    t.push_back(real("sepal_width", 0.22f, 0.05f, 1.0f, "Sepal width / sepal length"));
    t.push_back(real("sepal_curl", 25.0f, -60.0f, 120.0f,
                     "Bend of the sepals away from the fruit from base to tip, degrees"));
    t.push_back(real("stem_length", 0.15f, 0.0f, 1.5f,
                     "Visible stem length, fraction of the fruit diameter"));
    t.push_back(whole("husk", 0, 0, 1, "1 = enclose the berry in a papery lantern husk"));
    t.push_back(real("husk_size", 1.5f, 1.1f, 3.0f, "Husk length / berry length"));
    addColor(t, "husk", {0.64f, 0.70f, 0.38f}, "Husk");
    return f;
}

OrganPrototype buildBerry(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("fruit", req.color);
    parts.declare("calyx", kCalyxGreen);
    parts.declare("husk", p.color("husk"));
    const float diameter = 1.0f, length = p("aspect") * diameter;
    const bool husk = p.flag("husk");
    const float stem = std::max(p("stem_length"), 0.02f) * diameter;
    const float dent = p("shoulder_dent") * diameter;
    const float x0 = stem - dent;  // the shoulders are at x = stem
    const int ribs = p.count("ribs");
    const float ribDepth = p("rib_depth");
    parts.add(
        "fruit", closedBody(resolution(s, 1.0f, 4), resolution(s, 2.0f, 6), [&](float u, float th) {
            const float phi = kPi * u;
            float r = 0.5f * diameter * std::sin(phi);
            if (ribs > 0) {
                const float groove = 0.5f - 0.5f * std::cos(float(ribs) * th);
                r *= 1.0f -
                     ribDepth * groove * groove * ppow(std::sin(phi), 0.5f) * (1.0f - 0.5f * u);
            }
            const float x = x0 + 0.5f * length * (1.0f - std::cos(phi)) +
                            dent * std::exp(-(u / 0.16f) * (u / 0.16f));
            return vec3(x, 0, 0) + r * radialDir(th);
        }));
    const unsigned sides = resolution(s, 0.5f, 3);
    parts.add("calyx", tube({0, 0, 0}, {x0 + dent + 0.01f, 0, 0}, 0.035f * diameter,
                            0.045f * diameter, sides, 2));
    const unsigned rows = resolution(s, 0.5f, 1), cols = resolution(s, 0.25f, 1);
    if (husk) {
        // The lantern: an inflated, five-angled, ten-ribbed papery bladder from a sunken
        // base around the stem to a point past the berry.
        const float hl = p("husk_size") * length;
        const float hr = 0.5f * diameter * 1.05f * std::max(1.0f, p("husk_size") * 0.8f);
        const float start = std::max(0.2f * stem, x0 + 0.5f * length - 0.45f * hl);
        parts.add(
            "husk",
            closedBody(resolution(s, 1.5f, 4), resolution(s, 3.0f, 10), [&](float u, float th) {
                const float angles = 0.5f + 0.5f * std::cos(5.0f * th);
                const float ribs = 0.5f + 0.5f * std::cos(10.0f * th);
                const float r = hr * ppow(std::sin(kPi * std::pow(u, 0.8f)), 0.8f) *
                                (0.86f + 0.2f * angles * angles + 0.03f * ribs);
                const float x = start + hl * u + 0.12f * hl * std::exp(-(u / 0.12f) * (u / 0.12f));
                return vec3(x, 0, 0) + r * radialDir(th);
            }));
    } else if (p.count("sepal_count") > 0) {
        const float sl = p("sepal_length") * diameter;
        parts.add("calyx", sepalStar(p.count("sepal_count"), x0 + dent * 0.7f, 0.04f * diameter, sl,
                                     p("sepal_width") * sl, 80.0f, 80.0f + p("sepal_curl"), 0.2f,
                                     rows, cols));
    }
    return parts.finish();
}

// ---- berry_cluster ------------------------------------------------------------------------------

FloralFamilyInfo berryClusterInfo() {
    FloralFamilyInfo f;
    f.name = "berry_cluster";
    f.fruit = true;
    f.description =
        "Berry cluster (bunch): round berries on short pedicels packed around a rachis into a "
        "cone that tapers from broad shoulders to the tip. The packing is random (from the "
        "stream).";
    f.defaultColor = {0.24f, 0.18f, 0.34f};
    f.parts = {"berries", "rachis"};
    auto& t = f.parameters;
    t.push_back(whole("berry_count", 60, 1, 300, "Number of berries"));
    t.push_back(real("berry_size", 0.12f, 0.03f, 0.4f, "Berry diameter / cluster length"));
    t.push_back(real("berry_aspect", 1.05f, 0.7f, 2.0f, "Berry length / berry diameter"));
    t.push_back(real("cluster_width", 0.55f, 0.1f, 1.5f, "Width at the shoulders / length"));
    t.push_back(real("taper", 0.7f, 0.0f, 1.0f,
                     "How much narrower the tip is than the shoulders (0 = cylinder)"));
    t.push_back(real("peduncle_length", 0.12f, 0.02f, 0.5f,
                     "Bare stalk before the first berries, fraction of the length"));
    t.push_back(real("size_variation", 0.08f, 0.0f, 0.4f, "Random berry size variation"));
    return f;
}

struct Berry {
    vec3 centre;
    float radius;
};

// Places berries one by one inside the cone, each at the best of several random spots (the
// first that overlaps nothing, else the one with the most room).
std::vector<Berry> packBerries(const Params& p, Rng& rng) {
    const int n = p.count("berry_count");
    const float r0 = 0.5f * p("berry_size"), x0 = p("peduncle_length");
    const float half = 0.5f * p("cluster_width"), taper = p("taper");
    const float xs = x0 + r0, xe = 1.0f - r0;
    auto envelope = [&](float x) {
        const float t = std::clamp((x - xs) / std::max(xe - xs, 1e-3f), 0.0f, 1.0f);
        return std::max(half * (1.0f - taper * t) * std::sqrt(std::min(1.0f, 0.25f + 4.0f * t)),
                        0.0f);
    };
    // Berries along x in proportion to the cone's cross-section (inverse of its CDF).
    std::vector<float> cdf(65, 0.0f);
    for (int i = 1; i <= 64; ++i) {
        const float x = xs + (xe - xs) * (float(i) - 0.5f) / 64.0f;
        cdf[i] = cdf[i - 1] + envelope(x) * envelope(x) + r0 * r0;
    }
    std::vector<Berry> placed;
    for (int k = 0; k < n; ++k) {
        const float target = (float(k) + rng.uniform01()) / float(n) * cdf.back();
        int i = 1;
        while (i < 64 && cdf[i] < target) ++i;
        const float frac = (target - cdf[i - 1]) / std::max(cdf[i] - cdf[i - 1], 1e-9f);
        const float x = xs + (xe - xs) * (float(i - 1) + frac) / 64.0f;
        const float radius = r0 * (1.0f + p("size_variation") * rng.uniform(-1.0f, 1.0f));
        Berry best{{x, 0, 0}, radius};
        float bestRoom = -1e9f;
        for (int attempt = 0; attempt < 40; ++attempt) {
            const float rho =
                std::max(envelope(x) - radius, 0.0f) * (0.35f + 0.65f * std::sqrt(rng.uniform01()));
            const float az = rng.uniform(0.0f, 2.0f * kPi);
            const vec3 c{x + rng.uniform(-0.5f, 0.5f) * radius, 0, 0};
            const Berry b{c + rho * radialDir(az), radius};
            float room = 1e9f;
            for (const Berry& o : placed)
                room = std::min(room, glm::length(o.centre - b.centre) - o.radius - b.radius);
            if (room > bestRoom) {
                bestRoom = room;
                best = b;
            }
            if (room >= 0.0f) break;
        }
        placed.push_back(best);
    }
    return placed;
}

OrganPrototype buildBerryCluster(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("berries", req.color);
    parts.declare("rachis", {0.45f, 0.48f, 0.24f});
    const std::vector<Berry> berries = packBerries(p, rng);
    const unsigned rows = resolution(s, 0.5f, 2), sides = resolution(s, 1.0f, 4);
    const float aspect = p("berry_aspect");
    float end = p("peduncle_length");
    for (const Berry& b : berries) {
        const vec3 axisPoint{std::max(b.centre.x - 0.6f * glm::length(vec2(b.centre.y, b.centre.z)),
                                      p("peduncle_length") * 0.8f),
                             0, 0};
        vec3 dir = b.centre - axisPoint;
        dir = glm::length(dir) > 1e-4f ? glm::normalize(dir) : kX;
        const vec3 side =
            glm::normalize(glm::cross(dir, std::abs(dir.z) < 0.9f ? vec3(0, 0, 1) : vec3(0, 1, 0)));
        const vec3 up = glm::cross(side, dir);
        parts.add("berries", ellipsoid(b.centre, dir * (b.radius * aspect), side * b.radius,
                                       up * b.radius, rows, sides));
        if (glm::length(b.centre - axisPoint) > b.radius * 0.5f)
            parts.add("rachis", tube(axisPoint, b.centre, 0.006f, 0.005f, 3));
        end = std::max(end, axisPoint.x);
    }
    parts.add("rachis",
              tube({0, 0, 0}, {end + 0.01f, 0, 0}, 0.014f, 0.008f, resolution(s, 0.5f, 3), 2));
    return parts.finish();
}

// ---- hollow_berry -------------------------------------------------------------------------------

FloralFamilyInfo hollowBerryInfo() {
    FloralFamilyInfo f;
    f.name = "hollow_berry";
    f.fruit = true;
    f.description =
        "Hollow berry hanging from a thick curved stem in a green calyx cap: a blocky bell "
        "with three or four lobes at its base, or an elongated, tapering (and hooked) horn.";
    f.defaultColor = {0.78f, 0.10f, 0.07f};
    f.parts = {"fruit", "calyx"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 1.1f, 0.5f, 8.0f, "Fruit length / diameter"));
    t.push_back(
        real("blockiness", 0.85f, 0.0f, 1.0f, "0 = tapering to a point (horn) .. 1 = blocky bell"));
    t.push_back(whole("lobes", 4, 0, 6, "Lobes around the fruit (0 = round)"));
    t.push_back(real("lobe_depth", 0.1f, 0.0f, 0.4f, "Depth of the lobes, fraction of radius"));
    t.push_back(real("tip_curl", 0.0f, -90.0f, 90.0f,
                     "Hook of the tip (elongated fruit), degrees; positive curls toward +z"));
    t.push_back(real("stem_length", 0.3f, 0.05f, 1.5f, "Stem length / fruit diameter"));
    t.push_back(real("calyx_size", 0.3f, 0.05f, 0.8f, "Calyx cap diameter / fruit diameter"));
    return f;
}

vec3 hollowBerryPoint(const Params& p, float xb, float u, float th) {
    const float block = p("blockiness"), length = p("aspect"), lobeDepth = p("lobe_depth");
    const int lobes = p.count("lobes");
    const float tau = std::abs(2.0f * u - 1.0f);
    const float bell = 0.5f * ppow(1.0f - std::pow(tau, 3.5f), 1.0f / 3.5f) * (1.0f - 0.1f * u);
    const float horn =
        0.5f * ppow(std::sin(0.5f * kPi * std::min(u / 0.14f, 1.0f)), 0.7f) * ppow(1.0f - u, 0.8f);
    float r = glm::mix(horn, bell, block);
    const float lobe = lobes > 0 ? std::cos(float(lobes) * th) : 0.0f;
    r *= 1.0f + lobeDepth * lobe * (0.4f + 0.6f * u);
    float x = xb + length * u;
    x += (0.05f + 0.1f * block) * std::exp(-(u / 0.1f) * (u / 0.1f));           // stem cavity
    x -= 0.08f * block * std::exp(-((1.0f - u) / 0.1f) * ((1.0f - u) / 0.1f));  // bottom dimple
    x += 0.35f * lobeDepth * block * lobe * smooth(0.7f, 1.0f, u) * std::sin(kPi * u);
    vec3 pt = vec3(x, 0, 0) + r * radialDir(th);
    // The hook bends the part beyond 40 % of the length.
    const float curl = p("tip_curl") * kDeg;
    if (curl != 0.0f && u > 0.4f) {
        const float t = (u - 0.4f) / 0.6f;
        pt.z += length * 0.6f * std::sin(curl) * 0.5f * t * t;
    }
    return pt;
}

OrganPrototype buildHollowBerry(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("fruit", req.color);
    parts.declare("calyx", {0.20f, 0.38f, 0.12f});
    const float stem = p("stem_length");
    const float xb = stem * 0.75f;
    parts.add("fruit",
              closedBody(resolution(s, 2.0f, 6), resolution(s, 3.0f, 8),
                         [&](float u, float th) { return hollowBerryPoint(p, xb, u, th); }));
    // Stem: thick, bending slightly, ending in the cavity.
    const float cavity = xb + 0.05f + 0.1f * p("blockiness");
    const std::vector<vec3> path = arcPath({0, 0, 0}, kX, {0, 0, 1}, cavity + 0.02f, 25.0f, 4);
    std::vector<float> radii(path.size(), 0.05f);
    radii.back() = 0.07f;
    parts.add("calyx", tube(path, radii, resolution(s, 0.5f, 4)));
    const float cs = 0.5f * p("calyx_size");
    parts.add("calyx",
              gridMesh({resolution(s, 0.25f, 1), resolution(s, 2.0f, 6), true, true, false},
                       [&](unsigned i, unsigned j) {
                           const float u = float(i) / float(resolution(s, 0.25f, 1));
                           const float th = 2.0f * kPi * float(j) / float(resolution(s, 2.0f, 6));
                           const float r = cs * u * (1.0f + 0.15f * std::cos(5 * th));
                           return vec3(cavity - 0.02f + 0.06f * u * u, 0, 0) + r * radialDir(th);
                       }));
    parts.add("calyx", sepalStar(5, cavity + 0.02f, cs * 0.8f, cs * 0.7f, cs * 0.5f, 80.0f, 75.0f,
                                 0.3f, resolution(s, 0.5f, 1), resolution(s, 0.25f, 1)));
    return parts.finish();
}

// ---- accessory_fruit ----------------------------------------------------------------------------

FloralFamilyInfo accessoryFruitInfo() {
    FloralFamilyInfo f;
    f.name = "accessory_fruit";
    f.fruit = true;
    f.description =
        "Accessory fruit: a red cone rounded at the shoulders, its surface dimpled around small "
        "yellow achenes (seeds), under a spreading star of green sepals on a thin stem.";
    f.defaultColor = {0.82f, 0.08f, 0.10f};
    f.parts = {"fruit", "achenes", "calyx"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 1.25f, 0.6f, 2.5f, "Fruit length / diameter"));
    t.push_back(real("shoulder", 0.28f, 0.05f, 0.6f,
                     "Position of the widest point, fraction of the length from the calyx"));
    t.push_back(
        real("tip", 1.1f, 0.4f, 3.0f, "Taper toward the tip: below 1 blunt, above 1 pointed"));
    t.push_back(whole("achene_count", 140, 0, 600, "Number of achenes (seeds)"));
    t.push_back(real("achene_size", 0.045f, 0.01f, 0.12f, "Achene length / fruit diameter"));
    t.push_back(real("dimple_depth", 0.018f, 0.0f, 0.06f,
                     "Depth of the pits the achenes sit in / fruit diameter"));
    addColor(t, "achene", {0.86f, 0.74f, 0.28f}, "Achene");
    t.push_back(whole("sepal_count", 10, 0, 16, "Sepals of the calyx (0 = none)"));
    t.push_back(real("sepal_length", 0.5f, 0.05f, 1.5f, "Sepal length / fruit diameter"));
    t.push_back(real("stem_length", 0.3f, 0.02f, 2.0f, "Stem length / fruit diameter"));
    return f;
}

// Radius profile (diameter 1) at fraction u from the calyx to the tip.
float accessoryFruitRadius(const Params& p, float u) {
    const float w = p("shoulder");
    if (u <= w) return 0.5f * ppow(std::sin(0.5f * kPi * u / w), 0.55f);
    return 0.5f * ppow(std::cos(0.5f * kPi * (u - w) / (1.0f - w)), p("tip"));
}

struct Achene {
    float u, theta;
};

// Achenes spread evenly over the surface: a golden-angle spiral with u drawn from the
// surface-area distribution.
std::vector<Achene> placeAchenes(const Params& p) {
    const int n = p.count("achene_count");
    const float length = p("aspect");
    std::vector<float> cdf(129, 0.0f);
    const float u0 = 0.1f, u1 = 0.97f;
    for (int i = 1; i <= 128; ++i) {
        const float a = u0 + (u1 - u0) * float(i - 1) / 128.0f,
                    b = u0 + (u1 - u0) * float(i) / 128.0f;
        const float ra = accessoryFruitRadius(p, a), rb = accessoryFruitRadius(p, b);
        cdf[i] = cdf[i - 1] + 0.5f * (ra + rb) * std::hypot(length * (b - a), rb - ra);
    }
    std::vector<Achene> out;
    for (int k = 0; k < n; ++k) {
        const float target = (float(k) + 0.5f) / float(n) * cdf.back();
        int i = 1;
        while (i < 128 && cdf[i] < target) ++i;
        const float frac = (target - cdf[i - 1]) / std::max(cdf[i] - cdf[i - 1], 1e-9f);
        out.push_back({u0 + (u1 - u0) * (float(i - 1) + frac) / 128.0f,
                       std::fmod(float(k) * 2.39996323f, 2.0f * kPi)});
    }
    return out;
}

OrganPrototype buildAccessoryFruit(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("fruit", req.color);
    parts.declare("achenes", p.color("achene"));
    parts.declare("calyx", {0.24f, 0.44f, 0.14f});
    const float length = p("aspect"), stem = p("stem_length"), depth = p("dimple_depth");
    const float xb = stem;
    const std::vector<Achene> achenes = placeAchenes(p);
    // Pit width from the mean spacing of the achenes over the surface (area ~ 2.3 d^2 L).
    const float spacing =
        std::sqrt(2.3f * length / float(std::max<std::size_t>(achenes.size(), 1)));
    const float sigma = 0.35f * spacing;
    auto surface = [&](float u, float th, bool pitted) {
        float r = accessoryFruitRadius(p, u);
        if (pitted && depth > 0.0f)
            for (const Achene& a : achenes) {
                const float du = (u - a.u) * length;
                const float dth = std::remainder(th - a.theta, 2.0f * kPi) * r;
                const float d2 = (du * du + dth * dth) / (sigma * sigma);
                if (d2 < 9.0f) r -= depth * std::exp(-d2);
            }
        const float x = xb + length * u + 0.04f * std::exp(-(u / 0.1f) * (u / 0.1f));
        return vec3(x, 0, 0) + std::max(r, 0.0f) * radialDir(th);
    };
    parts.add("fruit", closedBody(resolution(s, 3.0f, 6), resolution(s, 4.0f, 8),
                                  [&](float u, float th) { return surface(u, th, true); }));
    const float size = p("achene_size");
    const unsigned arows = resolution(s, 0.125f, 2);
    for (const Achene& a : achenes) {
        const vec3 c = surface(a.u, a.theta, false);
        const vec3 ahead = surface(std::min(a.u + 0.01f, 1.0f), a.theta, false) - c;
        const vec3 normal = radialDir(a.theta);
        const vec3 along = glm::normalize(ahead - normal * glm::dot(ahead, normal));
        const vec3 across = glm::cross(normal, along);
        parts.add("achenes", ellipsoid(c - normal * (0.6f * depth), along * (0.5f * size),
                                       across * (0.3f * size), normal * (0.25f * size), arows, 4));
    }
    parts.add("calyx", tube(arcPath({0, 0, 0}, kX, {0, 0, 1}, xb + 0.05f, 20.0f, 3),
                            std::vector<float>(4, 0.03f), resolution(s, 0.5f, 3)));
    if (p.count("sepal_count") > 0) {
        const float sl = p("sepal_length");
        parts.add("calyx",
                  sepalStar(p.count("sepal_count"), xb + 0.03f, 0.05f, sl, 0.3f * sl, 95.0f, 120.0f,
                            0.1f, resolution(s, 0.5f, 2), resolution(s, 0.25f, 1)));
    }
    return parts.finish();
}

// ---- pome ---------------------------------------------------------------------------------------

FloralFamilyInfo pomeInfo() {
    FloralFamilyInfo f;
    f.name = "pome";
    f.fruit = true;
    f.description =
        "Pome: a round fruit with a deep stem cavity holding a thin woody stem, a "
        "calyx basin with dried sepals at the far end, slight taper and ribbing.";
    f.defaultColor = {0.74f, 0.13f, 0.10f};
    f.parts = {"fruit", "stem", "calyx"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 0.9f, 0.6f, 1.5f, "Length (stem to calyx) / diameter"));
    t.push_back(real("cavity_depth", 0.1f, 0.0f, 0.3f, "Stem cavity depth / diameter"));
    t.push_back(real("basin_depth", 0.06f, 0.0f, 0.2f, "Calyx basin depth / diameter"));
    t.push_back(real("taper", 0.15f, 0.0f, 0.5f, "Narrowing toward the calyx end"));
    t.push_back(whole("ribs", 5, 0, 8, "Ribs (broad lobes) around the fruit"));
    t.push_back(real("rib_depth", 0.025f, 0.0f, 0.15f, "Rib height, fraction of the radius"));
    t.push_back(
        real("stem_length", 0.18f, 0.0f, 0.6f, "Stem length beyond the shoulders / diameter"));
    return f;
}

vec3 pomePoint(const Params& p, float u, float th) {
    const float length = p("aspect"), taper = p("taper");
    const int ribs = p.count("ribs");
    const float phi = kPi * u;
    float r = 0.5f * std::sin(phi) * (1.0f - taper * smooth(0.3f, 1.0f, u));
    float x = 0.5f * length * (1.0f - std::cos(phi));
    x += p("cavity_depth") * 1.6f * std::exp(-(phi / 0.38f) * (phi / 0.38f));
    x -= p("basin_depth") * 1.6f * std::exp(-((kPi - phi) / 0.38f) * ((kPi - phi) / 0.38f));
    if (ribs > 0) {
        const float rib = std::cos(float(ribs) * th) * std::sin(phi) * (0.4f + 0.6f * u);
        r *= 1.0f + p("rib_depth") * rib;
        x += 0.5f * p("rib_depth") * rib * smooth(0.6f, 0.95f, u);
    }
    return vec3(x, 0, 0) + r * radialDir(th);
}

OrganPrototype buildPome(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("fruit", req.color);
    parts.declare("stem", {0.36f, 0.25f, 0.14f});
    parts.declare("calyx", {0.30f, 0.24f, 0.14f});
    // Shift so the shoulders (smallest x of the body) sit at x = stem_length.
    float shoulder = 1e9f;
    for (int i = 0; i <= 200; ++i)
        shoulder = std::min(shoulder, pomePoint(p, float(i) / 200.0f, 0).x);
    const vec3 shift{p("stem_length") + 0.005f - shoulder, 0, 0};
    Mesh body = closedBody(resolution(s, 2.0f, 6), resolution(s, 2.0f, 8),
                           [&](float u, float th) { return shift + pomePoint(p, u, th); });
    parts.add("fruit", body);
    const vec3 cavity = shift + pomePoint(p, 0, 0);
    const std::vector<vec3> stemPath =
        arcPath({0, 0, 0}, kX, {0, 0.5f, 1}, cavity.x + 0.01f, 15.0f, 3);
    parts.add("stem", tube(stemPath, std::vector<float>{0.018f, 0.016f, 0.017f, 0.022f},
                           resolution(s, 0.5f, 3)));
    const vec3 basin = shift + pomePoint(p, 1, 0);
    parts.add("calyx", sepalStar(5, basin.x - 0.008f, 0.01f, 0.07f, 0.035f, 35.0f, 70.0f, 0.0f,
                                 resolution(s, 0.25f, 1), 1));
    return parts.finish();
}

}  // namespace

std::vector<Family> fruitFamilies() {
    return {{berryInfo(), buildBerry},
            {berryClusterInfo(), buildBerryCluster},
            {hollowBerryInfo(), buildHollowBerry},
            {accessoryFruitInfo(), buildAccessoryFruit},
            {pomeInfo(), buildPome}};
}

}  // namespace plantarch::organs
