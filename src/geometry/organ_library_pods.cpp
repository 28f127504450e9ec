// Pod and drupe families of the organ library: legume pods, flattened hulls (closed or split),
// round hulls, single drupes and drupe clusters.
//
// Frame: the organ hangs from its stalk, which starts at the origin and runs along +x; the
// sutures of pods and hulls are at the top (+z) and bottom, their flat faces face +-y.

#include <algorithm>
#include <cmath>

#include "geometry/organ_library_internal.h"

namespace plantarch::organs {

namespace {

const vec3 kPodStalkGreen{0.30f, 0.40f, 0.16f};

// ---- legume_pod ---------------------------------------------------------------------------------

FloralFamilyInfo podInfo() {
    FloralFamilyInfo f;
    f.name = "legume_pod";
    f.fruit = true;
    f.description =
        "Legume pod: a long, laterally flattened pod on a short stalk with a small calyx, "
        "bulging over each seed and ending in a thin beak; curved upward like a sickle, "
        "optionally hairy: long and green, very long and thin, short and hairy, or flat and "
        "thin with a lens-shaped section.";
    f.defaultColor = {0.45f, 0.60f, 0.24f};
    f.parts = {"pod", "calyx", "hairs"};
    auto& t = f.parameters;
    t.push_back(real("width", 0.11f, 0.02f, 0.6f,
                     "Pod width from suture to suture (along z) / pod length"));
    t.push_back(real("thickness", 0.07f, 0.005f, 0.5f,
                     "Pod thickness across the flat faces (along y) / pod length"));
    t.push_back(real("curvature", 20.0f, -180.0f, 180.0f,
                     "Total bend of the pod from base to tip, degrees (positive curls up)"));
    t.push_back(whole("seed_count", 5, 0, 20, "Seeds, each a bulge (0 = smooth pod)"));
    t.push_back(real("seed_bump", 0.25f, 0.0f, 0.6f,
                     "Constriction between seeds, fraction of the thickness"));
    t.push_back(real("beak_length", 0.07f, 0.0f, 0.3f,
                     "Length of the tapering beak at the tip / pod length"));
    t.push_back(real("stalk_length", 0.05f, 0.0f, 0.3f, "Stalk length / pod length"));
    t.push_back(real("section_lens", 0.0f, 0.0f, 1.0f,
                     "Cross-section: 0 oval, 1 lens with sharp sutures (flat pods)"));
    t.push_back(
        real("hairs", 0.0f, 0.0f, 1.0f, "Density of short appressed hairs (1 = densely hairy)"));
    addColor(t, "hair", {0.74f, 0.62f, 0.42f}, "Hair");
    return f;
}

struct PodShape {
    float width, thickness, bump, beak, lens;
    int seeds;

    // Half-sizes (y, z) of the cross-section at fraction u of the body.
    vec2 halfSize(float u) const {
        const float beakLen = std::max(beak, 0.04f);
        float taper = ppow(std::sin(0.5f * kPi * std::min(u / 0.1f, 1.0f)), 0.5f);
        if (u > 1.0f - beakLen) taper *= ppow((1.0f - u) / beakLen, 0.9f);
        float seedY = 1.0f, seedZ = 1.0f;
        if (seeds > 0) {
            const float a = 0.08f, b = 1.0f - beakLen - 0.02f;
            const float us = std::clamp((u - a) / (b - a), 0.0f, 1.0f);
            const float pinch = 0.5f + 0.5f * std::cos(2.0f * kPi * float(seeds) * us);
            seedY = 1.0f - bump * pinch;
            seedZ = 1.0f - 0.3f * bump * pinch;
        }
        return {0.5f * thickness * taper * seedY, 0.5f * width * taper * seedZ};
    }
    vec2 section(float u, float th) const {
        const vec2 h = halfSize(u);
        const float c = std::cos(th), s = std::sin(th);
        const float y = glm::mix(std::abs(c), 1.0f - std::abs(s), lens);
        return {h.x * (c < 0 ? -y : y), h.y * s};
    }
};

Mesh podHairs(const PodShape& shape, const std::vector<vec3>& path, float density, Rng& rng) {
    Mesh m;
    const int count = int(std::lround(density * 350.0f));
    for (int k = 0; k < count; ++k) {
        const float u = rng.uniform(0.05f, 0.95f), th = rng.uniform(0.0f, 2.0f * kPi);
        const PathPoint at = pathAt(path, kZ, u);
        const vec2 s = shape.section(u, th);
        const vec3 p = at.position + s.x * at.side + s.y * at.normal;
        const vec3 out = glm::normalize(std::cos(th) * at.side + std::sin(th) * at.normal);
        const std::uint32_t base = std::uint32_t(m.positions.size());
        m.positions.push_back(p - at.tangent * 0.003f);
        m.positions.push_back(p + at.tangent * 0.003f);
        m.positions.push_back(p + out * 0.012f + at.tangent * 0.014f);
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    }
    return m;
}

OrganPrototype buildPod(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("pod", req.color);
    parts.declare("calyx", kPodStalkGreen);
    parts.declare("hairs", p.color("hair"));
    const PodShape shape{p("width"),       p("thickness"),    p("seed_bump"),
                         p("beak_length"), p("section_lens"), p.count("seed_count")};
    const float stalk = std::max(p("stalk_length"), 0.01f);
    const unsigned rows = resolution(s, 3.0f, 4) + 3u * unsigned(shape.seeds);
    const std::vector<vec3> path =
        arcPath({stalk, 0, 0}, kX, kZ, 1.0f - stalk, p("curvature"), rows);
    parts.add("pod", sweptBody(path, kZ, rows, resolution(s, 1.5f, 6),
                               [&](float u, float th) { return shape.section(u, th); }));
    const float r = 0.12f * std::min(shape.width, shape.thickness * 2.0f) + 0.006f;
    parts.add("calyx", tube({0, 0, 0}, {stalk + 0.01f, 0, 0}, r * 0.8f, r, resolution(s, 0.5f, 3)));
    parts.add("calyx", sepalStar(5, stalk - 0.005f, r, 2.5f * r, 1.5f * r, 40.0f, 20.0f, 0.3f,
                                 resolution(s, 0.25f, 1), 1));
    if (p("hairs") > 0.0f) parts.add("hairs", podHairs(shape, path, p("hairs"), rng));
    return parts.finish();
}

// ---- flat_hull ----------------------------------------------------------------------------------

FloralFamilyInfo flatHullInfo() {
    FloralFamilyInfo f;
    f.name = "flat_hull";
    f.fruit = true;
    f.description =
        "Flattened hull: a pointed, velvety grey-green hull, flat from side to side, with a "
        "groove along its ventral suture; when split, the two halves of the hull gape open "
        "along the suture and show the pitted brown shell inside.";
    f.defaultColor = {0.46f, 0.54f, 0.34f};
    f.parts = {"hull", "shell", "stem"};
    auto& t = f.parameters;
    t.push_back(real("width", 0.72f, 0.3f, 1.2f, "Hull height from suture to back (z) / length"));
    t.push_back(real("thickness", 0.6f, 0.2f, 1.2f, "Hull thickness across (y) / length"));
    t.push_back(real("tip", 0.6f, 0.0f, 1.0f, "Pointedness of the far end"));
    t.push_back(
        real("asymmetry", 0.1f, 0.0f, 0.4f, "Straighter ventral (suture) side, more convex back"));
    t.push_back(real("suture_depth", 0.06f, 0.0f, 0.2f, "Depth of the suture groove"));
    t.push_back(
        real("split", 0.0f, 0.0f, 1.0f, "Hull split: 0 closed, 1 both halves folded fully open"));
    addColor(t, "shell", {0.50f, 0.36f, 0.24f}, "Shell");
    t.push_back(real("stem_length", 0.05f, 0.0f, 0.3f, "Stem length / length"));
    return f;
}

// Point of a pointed, possibly asymmetric drupe surface: u from stem to tip, theta around
// (pi/2 = top).
vec3 drupePoint(float x0, float length, float ry, float rz, float tip, float asym, float u,
                float th) {
    const float round = 0.5f * (1.0f - std::cos(kPi * u));
    const float x = x0 + length * (u < 0.5f ? round : glm::mix(round, u, tip));
    const float env = std::sin(kPi * u);
    const float zc = -asym * rz * env;
    return {x, ry * env * std::cos(th),
            zc + rz * env * std::sin(th) * (1.0f + asym * std::sin(th))};
}

OrganPrototype buildFlatHull(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("hull", req.color);
    parts.declare("shell", p.color("shell"));
    parts.declare("stem", {0.38f, 0.34f, 0.20f});
    const float x0 = std::max(p("stem_length"), 0.01f), length = 1.0f - x0;
    const float ry = 0.5f * p("thickness"), rz = 0.5f * p("width");
    const float tip = p("tip"), asym = p("asymmetry"), groove = p("suture_depth");
    const auto outer = [&](float u, float th) {
        vec3 q = drupePoint(x0, length, ry, rz, tip, asym, u, th);
        const float d = std::remainder(th - 0.5f * kPi, 2.0f * kPi) / 0.22f;
        const vec3 c = drupePoint(x0, length, 0, 0, tip, asym, u, th);
        return c + (q - c) * (1.0f - groove * std::exp(-d * d));
    };
    const unsigned rows = resolution(s, 2.0f, 4), sides = resolution(s, 2.0f, 6);
    parts.add("stem", tube({0, 0, 0}, {x0 + 0.02f, 0, 0}, 0.02f, 0.025f, resolution(s, 0.5f, 3)));
    const float split = p("split");
    if (split <= 0.0f) {
        parts.add("hull", closedBody(rows, sides, outer));
        return parts.finish();
    }
    // Two valves, each a closed shell (outer surface, rim, inner surface), turned open about
    // the hinge along the back.
    const unsigned half = std::max(sides / 2, 2u);
    for (int side : {1, -1}) {
        const float a0 = side > 0 ? -0.5f * kPi : 0.5f * kPi;
        Mesh valve =
            gridMesh({rows, 2 * (half + 1), true, true, true}, [&](unsigned i, unsigned j) {
                const float u = float(i) / float(rows);
                const bool inner = j > half;
                const unsigned k = inner ? 2 * half + 1 - j : j;
                const float th = a0 + kPi * float(k) / float(half);
                const vec3 q = outer(u, th);
                if (!inner) return q;
                const vec3 c = drupePoint(x0, length, 0, 0, tip, asym, u, th);
                return c + (q - c) * 0.78f;
            });
        if (signedVolume(valve) < 0.0) flipWinding(valve);
        const vec3 hinge{0, 0, -rz * (1.0f + asym)};
        const float angle = -float(side) * split * 80.0f * kDeg;
        for (vec3& v : valve.positions) v = hinge + rotateAbout(v - hinge, kX, angle);
        parts.add("hull", valve);
    }
    parts.add("shell", closedBody(rows, sides, [&](float u, float th) {
                  const vec3 c =
                      drupePoint(x0 + 0.06f * length, 0.86f * length, 0, 0, 0.8f, asym, u, th);
                  const vec3 q = drupePoint(x0 + 0.06f * length, 0.86f * length, 0.68f * ry,
                                            0.72f * rz, 0.8f, asym, u, th);
                  const float pits = 1.0f + 0.025f * std::sin(23.0f * u) * std::sin(7.0f * th);
                  return c + (q - c) * pits;
              }));
    return parts.finish();
}

// ---- round_hull ---------------------------------------------------------------------------------

FloralFamilyInfo roundHullInfo() {
    FloralFamilyInfo f;
    f.name = "round_hull";
    f.fruit = true;
    f.description =
        "Round hull: a nearly round, smooth green hull, slightly longer than wide, with a "
        "small point at its far end, on a short stout stem.";
    f.defaultColor = {0.42f, 0.53f, 0.22f};
    f.parts = {"hull", "stem"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 1.12f, 0.7f, 1.8f, "Length / diameter"));
    t.push_back(real("tip", 0.04f, 0.0f, 0.2f, "Length of the point at the far end / length"));
    t.push_back(real("stem_length", 0.08f, 0.0f, 0.4f, "Stem length / diameter"));
    return f;
}

OrganPrototype buildRoundHull(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("hull", req.color);
    parts.declare("stem", {0.36f, 0.36f, 0.20f});
    const float length = p("aspect"), x0 = std::max(p("stem_length"), 0.02f), tip = p("tip");
    parts.add(
        "hull", closedBody(resolution(s, 2.0f, 4), resolution(s, 2.0f, 6), [&](float u, float th) {
            const float phi = kPi * u;
            const float e = (1.0f - u) / 0.08f;
            const float x = x0 + 0.5f * length * (1.0f - std::cos(phi)) +
                            tip * length * std::exp(-e * e) +
                            0.02f * std::exp(-(u / 0.1f) * (u / 0.1f));
            const float r =
                0.5f * std::sin(phi) * (1.0f - 0.06f * std::sin(2.0f * th) * std::sin(2.0f * th));
            return vec3(x, 0, 0) + r * radialDir(th);
        }));
    parts.add("stem", tube({0, 0, 0}, {x0 + 0.04f, 0, 0}, 0.04f, 0.05f, resolution(s, 0.5f, 3)));
    return parts.finish();
}

// ---- drupe --------------------------------------------------------------------------------------

FloralFamilyInfo drupeInfo() {
    FloralFamilyInfo f;
    f.name = "drupe";
    f.fruit = true;
    f.description =
        "Drupe: a smooth ellipsoidal stone fruit, slightly asymmetric and a little pointed at "
        "the far end, on a thin stem. Green when unripe, purple-black when ripe.";
    f.defaultColor = {0.55f, 0.62f, 0.24f};
    f.parts = {"fruit", "stem"};
    auto& t = f.parameters;
    t.push_back(real("aspect", 1.35f, 1.0f, 2.5f, "Length / diameter"));
    t.push_back(real("asymmetry", 0.08f, 0.0f, 0.3f, "One side more convex than the other"));
    t.push_back(real("tip", 0.25f, 0.0f, 1.0f, "Pointedness of the far end"));
    t.push_back(real("stem_length", 0.2f, 0.0f, 1.0f, "Stem length / diameter"));
    return f;
}

OrganPrototype buildDrupe(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("fruit", req.color);
    parts.declare("stem", {0.40f, 0.42f, 0.22f});
    const float length = p("aspect"), x0 = std::max(p("stem_length"), 0.02f);
    parts.add("fruit",
              closedBody(resolution(s, 2.0f, 4), resolution(s, 2.0f, 6), [&](float u, float th) {
                  return drupePoint(x0, length, 0.5f, 0.5f, p("tip"), p("asymmetry"), u, th);
              }));
    parts.add("stem", tube({0, 0, 0}, {x0 + 0.03f, 0, 0}, 0.025f, 0.035f, resolution(s, 0.5f, 3)));
    return parts.finish();
}

// ---- drupe_cluster ------------------------------------------------------------------------------

FloralFamilyInfo drupeClusterInfo() {
    FloralFamilyInfo f;
    f.name = "drupe_cluster";
    f.fruit = true;
    f.description =
        "Drupe cluster: small elongated drupes with rosy-ivory hulls on short stalks, "
        "hanging from the side branches of a drooping panicle.";
    f.defaultColor = {0.86f, 0.64f, 0.56f};
    f.parts = {"drupes", "rachis"};
    auto& t = f.parameters;
    t.push_back(whole("drupe_count", 30, 1, 150, "Number of drupes"));
    t.push_back(real("drupe_length", 0.13f, 0.04f, 0.4f, "Drupe length / cluster length"));
    t.push_back(real("drupe_aspect", 1.6f, 1.0f, 3.0f, "Drupe length / drupe diameter"));
    t.push_back(whole("branch_count", 7, 1, 20, "Side branches of the panicle"));
    t.push_back(real("cluster_width", 0.55f, 0.1f, 1.5f, "Cluster width / length"));
    return f;
}

OrganPrototype buildDrupeCluster(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("drupes", req.color);
    parts.declare("rachis", {0.55f, 0.50f, 0.30f});
    const int n = p.count("drupe_count"), branches = p.count("branch_count");
    const float len = p("drupe_length"), dr = 0.5f * len / p("drupe_aspect");
    const float half = 0.5f * p("cluster_width");
    const float axisEnd = 1.0f - len;
    parts.add("rachis",
              tube({0, 0, 0}, {axisEnd, 0, 0}, 0.014f, 0.008f, resolution(s, 0.5f, 3), 2));
    // Branches spiral around the rachis, longer near its base.
    struct Branch {
        vec3 base, dir;
        float length;
    };
    std::vector<Branch> arms;
    for (int b = 0; b < branches; ++b) {
        const float t = (float(b) + 0.5f) / float(branches);
        const float az = float(b) * 2.39996f;
        const vec3 dir = glm::normalize(0.75f * kX + 0.66f * radialDir(az));
        const vec3 base{0.12f + t * (axisEnd - 0.2f), 0, 0};
        arms.push_back({base, dir, std::max(half * (1.0f - 0.6f * t), 2.0f * dr)});
        parts.add("rachis", tube(base, base + dir * arms.back().length, 0.008f, 0.006f, 3));
    }
    arms.push_back({{axisEnd * 0.7f, 0, 0}, kX, axisEnd * 0.3f});
    const unsigned rows = resolution(s, 1.0f, 2), sides = resolution(s, 1.0f, 4);
    for (int k = 0; k < n; ++k) {
        const Branch& arm = arms[std::size_t(k) % arms.size()];
        const int slot = k / int(arms.size());
        const float f =
            0.3f + 0.7f * std::fmod(0.618034f * float(slot) + 0.2f * rng.uniform01(), 1.0f);
        const vec3 at = arm.base + arm.dir * (arm.length * f);
        const float az = rng.uniform(0.0f, 2.0f * kPi);
        const vec3 side = glm::normalize(glm::cross(arm.dir, radialDir(az)));
        const vec3 dir = glm::normalize(arm.dir + 0.9f * side);
        const vec3 stalkEnd = at + dir * (0.25f * len);
        parts.add("rachis", tube(at, stalkEnd + dir * 0.01f, 0.005f, 0.006f, 3));
        const vec3 across = glm::normalize(glm::cross(dir, std::abs(dir.z) < 0.9f ? kZ : kX));
        const vec3 up = glm::cross(dir, across);
        // The drupe is built along +x at the origin, then turned onto its stalk.
        Mesh drupe = closedBody(rows, sides, [&](float u, float th) {
            return drupePoint(0, len, dr, dr, 0.5f, 0.05f, u, th);
        });
        for (vec3& v : drupe.positions) v = stalkEnd + v.x * dir + v.y * across + v.z * up;
        parts.add("drupes", drupe);
    }
    return parts.finish();
}

}  // namespace

std::vector<Family> podAndDrupeFamilies() {
    return {{podInfo(), buildPod},
            {flatHullInfo(), buildFlatHull},
            {roundHullInfo(), buildRoundHull},
            {drupeInfo(), buildDrupe},
            {drupeClusterInfo(), buildDrupeCluster}};
}

}  // namespace plantarch::organs
