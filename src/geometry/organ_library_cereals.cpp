// Grass inflorescence families of the organ library: two-rowed spikes, nodding and compact
// panicles, tassels and husked ears.
//
// Frame: the head's axis is +x from the top of its stalk at the origin; heads that nod or
// have drooping branches bend toward -z (the panicles) or back toward the stalk (the tassel's
// branches, which stay at x >= 0).

#include <algorithm>
#include <cmath>

#include "geometry/organ_library_internal.h"

namespace plantarch::organs {

namespace {

const vec3 kCerealStalkGreen{0.42f, 0.50f, 0.22f};

// A grain or floret: a closed body pointed at the far end, along `dir` from `base`.
Mesh grain(vec3 base, vec3 dir, vec3 up, float length, float width, float thickness, float point,
           unsigned rows, unsigned sides) {
    const vec3 across = glm::normalize(glm::cross(up, dir));
    const vec3 normal = glm::cross(dir, across);
    return closedBody(rows, sides, [&](float u, float th) {
        const float round = 0.5f * (1.0f - std::cos(kPi * u));
        const float x = length * glm::mix(round, u > 0.5f ? u : round, point);
        const float env = std::sin(kPi * u);
        return base + dir * x +
               env * (0.5f * width * std::cos(th) * across +
                      0.5f * thickness * std::sin(th) * normal);
    });
}

// Any unit vector perpendicular to d.
vec3 perpendicular(vec3 d) {
    return glm::normalize(glm::cross(d, std::abs(d.z) < 0.9f ? kZ : kY));
}

// ---- spike --------------------------------------------------------------------------------------

FloralFamilyInfo spikeInfo() {
    FloralFamilyInfo f;
    f.name = "spike";
    f.fruit = true;
    f.description =
        "Two-rowed spike (ear): spikelets set alternately in two rows along a straight rachis, "
        "each a fan of florets (grains in their glumes), with optional long awns.";
    f.defaultColor = {0.50f, 0.58f, 0.26f};
    f.parts = {"spikelets", "awns", "rachis"};
    auto& t = f.parameters;
    t.push_back(whole("spikelet_count", 18, 2, 40, "Spikelets, alternating sides"));
    t.push_back(whole("florets", 3, 1, 6, "Florets (grains) per spikelet"));
    t.push_back(real("spikelet_length", 0.14f, 0.03f, 0.4f, "Spikelet length / spike length"));
    t.push_back(
        real("spikelet_angle", 22.0f, 5.0f, 80.0f, "Spikelets' angle from the rachis, degrees"));
    t.push_back(real("awn_length", 0.35f, 0.0f, 1.5f, "Awn length / spike length (0 = awnless)"));
    t.push_back(real("stalk_length", 0.06f, 0.0f, 0.4f, "Bare stalk below the spike / length"));
    return f;
}

OrganPrototype buildSpike(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("spikelets", req.color);
    parts.declare("awns", tint(req.color, 0.25f));
    parts.declare("rachis", kCerealStalkGreen);
    const int n = p.count("spikelet_count"), florets = p.count("florets");
    const float stalk = p("stalk_length"), ls = p("spikelet_length");
    const float top = 1.0f - 0.6f * ls, spacing = (top - stalk) / float(n);
    const float angle = p("spikelet_angle") * kDeg, awn = p("awn_length");
    parts.add("rachis", tube({0, 0, 0}, {top, 0, 0}, 0.01f, 0.006f, resolution(s, 0.5f, 3), 2));
    const unsigned rows = resolution(s, 0.5f, 2), sides = resolution(s, 0.5f, 4);
    for (int k = 0; k < n; ++k) {
        const float side = k % 2 ? -1.0f : 1.0f;
        const vec3 base{stalk + spacing * (float(k) + 0.5f), 0.004f * side, 0};
        const vec3 dir = std::cos(angle) * kX + std::sin(angle) * side * kY;
        const vec3 fanAxis = glm::normalize(glm::cross(dir, kZ));  // florets fan about it
        // Spikelets shrink toward the tip of the spike.
        const float size = ls * (1.0f - 0.35f * smooth(0.6f, 1.0f, float(k) / float(n)));
        for (int j = 0; j < florets; ++j) {
            const float spread = (float(j) - 0.5f * float(florets - 1)) * 20.0f * kDeg;
            const vec3 fdir = rotateAbout(dir, fanAxis, spread + 0.03f * rng.uniform(-1.0f, 1.0f));
            const float fl = size * (1.0f - 0.12f * std::abs(float(j) - 0.5f * float(florets - 1)));
            parts.add("spikelets",
                      grain(base, fdir, kZ, fl, 0.42f * size, 0.3f * size, 0.7f, rows, sides));
            if (awn > 0.0f) {
                const vec3 tip = base + fdir * fl;
                const vec3 adir = glm::normalize(fdir + 0.15f * side * kY);
                const float al = awn * (1.0f - 0.3f * float(k) / float(n));
                const vec3 ap[2] = {tip - fdir * (0.1f * fl), tip + adir * al};
                const float ar[2] = {0.0035f, 0.0f};
                parts.add("awns", tube(ap, ar, 3));
            }
        }
    }
    return parts.finish();
}

// ---- nodding_panicle ----------------------------------------------------------------------------

FloralFamilyInfo noddingPanicleInfo() {
    FloralFamilyInfo f;
    f.name = "nodding_panicle";
    f.fruit = true;
    f.description =
        "Nodding panicle: a drooping main axis with primary branches spiralling from it, each "
        "arching down and carrying ribbed, pointed grains on short pedicels.";
    f.defaultColor = {0.80f, 0.68f, 0.36f};
    f.parts = {"grains", "branches"};
    auto& t = f.parameters;
    t.push_back(whole("branch_count", 10, 1, 30, "Primary branches"));
    t.push_back(whole("grains_per_branch", 8, 1, 40, "Grains on each branch"));
    t.push_back(real("droop", 80.0f, 0.0f, 180.0f,
                     "How far the panicle nods: bend of the main axis (toward -z), degrees"));
    t.push_back(real("spread", 30.0f, 5.0f, 90.0f, "Branch angle from the main axis, degrees"));
    t.push_back(
        real("branch_length", 0.4f, 0.1f, 0.8f, "Longest (lowest) branch / panicle length"));
    t.push_back(real("grain_length", 0.07f, 0.02f, 0.2f, "Grain length / panicle length"));
    return f;
}

OrganPrototype buildNoddingPanicle(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("grains", req.color);
    parts.declare("branches", kCerealStalkGreen);
    const int branches = p.count("branch_count"), grains = p.count("grains_per_branch");
    const float droop = p("droop"), gl = p("grain_length");
    const std::vector<vec3> axis = arcPath({0, 0, 0}, kX, -kZ, 1.0f, 0.6f * droop, 16);
    parts.add("branches",
              tube(axis, std::vector<float>(axis.size(), 0.009f), resolution(s, 0.5f, 3)));
    const unsigned rows = resolution(s, 0.5f, 2), sides = resolution(s, 0.5f, 4);
    for (int b = 0; b < branches; ++b) {
        const float f = 0.2f + 0.75f * float(b) / float(std::max(branches - 1, 1));
        const PathPoint at = pathAt(axis, kZ, f);
        const float az = float(b) * 2.39996f;
        const vec3 out = std::cos(az) * at.side + std::sin(az) * at.normal;
        const float spread = p("spread") * kDeg;
        const vec3 dir = glm::normalize(std::cos(spread) * at.tangent + std::sin(spread) * out);
        const float len = p("branch_length") * (1.0f - 0.55f * f);
        vec3 down = -kZ - dir * glm::dot(-kZ, dir);
        if (glm::length(down) < 1e-3f) down = perpendicular(dir);
        const std::vector<vec3> arm =
            arcPath(at.position, dir, glm::normalize(down), len, 0.5f * droop, 6);
        parts.add("branches", tube(arm, std::vector<float>(arm.size(), 0.005f), 3));
        for (int g = 0; g < grains; ++g) {
            const float gf = 0.2f + 0.8f * (float(g) + 0.5f) / float(grains);
            const PathPoint on = pathAt(arm, glm::normalize(down), gf);
            const float side = g % 2 ? 1.0f : -1.0f;
            const float tilt = (25.0f + 10.0f * rng.uniform(-1.0f, 1.0f)) * kDeg;
            const vec3 gdir =
                glm::normalize(std::cos(tilt) * on.tangent + std::sin(tilt) * side * on.side);
            const vec3 gbase = on.position + gdir * 0.01f;
            parts.add("branches", tube(on.position, gbase + gdir * 0.004f, 0.003f, 0.003f, 3));
            parts.add("grains",
                      grain(gbase, gdir, on.normal, gl, 0.36f * gl, 0.27f * gl, 0.6f, rows, sides));
        }
    }
    return parts.finish();
}

// ---- compact_panicle ----------------------------------------------------------------------------

FloralFamilyInfo compactPanicleInfo() {
    FloralFamilyInfo f;
    f.name = "compact_panicle";
    f.fruit = true;
    f.description =
        "Compact panicle (head): an upright oval panicle, broadest below the middle, covered in "
        "round grains that point outward and up from a dark core.";
    f.defaultColor = {0.58f, 0.33f, 0.20f};
    f.parts = {"grains", "core"};
    auto& t = f.parameters;
    t.push_back(real("head_width", 0.36f, 0.1f, 1.0f, "Head width / head length"));
    t.push_back(whole("grain_rows", 22, 4, 60, "Whorls of grains along the head"));
    t.push_back(whole("grains_per_row", 12, 3, 40, "Grains in the widest whorl"));
    t.push_back(real("grain_size", 0.07f, 0.02f, 0.2f, "Grain diameter / head length"));
    t.push_back(real("stalk_length", 0.12f, 0.0f, 0.5f, "Bare stalk below the head / length"));
    addColor(t, "core", {0.36f, 0.28f, 0.16f}, "Core (branches and glumes)");
    return f;
}

OrganPrototype buildCompactPanicle(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("grains", req.color);
    parts.declare("core", p.color("core"));
    const float stalk = p("stalk_length"), gs = p("grain_size");
    const float x0 = stalk, length = 1.0f - stalk - 0.5f * gs;
    const float rmax = 0.5f * p("head_width") * length;
    auto envelope = [&](float t) {
        return rmax * ppow(std::sin(kPi * t), 0.65f) * (1.1f - 0.3f * t);
    };
    parts.add("core", tube({0, 0, 0}, {x0 + 0.05f, 0, 0}, 0.02f, 0.025f, resolution(s, 0.5f, 3)));
    parts.add("core",
              closedBody(resolution(s, 1.0f, 4), resolution(s, 1.0f, 6), [&](float u, float th) {
                  return vec3(x0 + length * u, 0, 0) + 0.8f * envelope(u) * radialDir(th);
              }));
    const int rows = p.count("grain_rows"), perRow = p.count("grains_per_row");
    const unsigned grows = resolution(s, 0.25f, 2), gsides = resolution(s, 0.5f, 4);
    for (int i = 0; i < rows; ++i) {
        const float t = (float(i) + 0.5f) / float(rows);
        const float r = envelope(t);
        const int count = std::max(3, int(std::lround(float(perRow) * r / rmax)));
        for (int k = 0; k < count; ++k) {
            const float az = 2.0f * kPi * (float(k) + 0.5f * float(i % 2)) / float(count) +
                             0.1f * rng.uniform(-1.0f, 1.0f);
            const vec3 radial = radialDir(az);
            const vec3 dir = glm::normalize(radial + (0.6f + 0.6f * t) * kX);
            const vec3 base = vec3(x0 + length * t, 0, 0) + radial * (0.75f * r);
            const float size = gs * rng.uniform(0.9f, 1.1f);
            parts.add("grains", grain(base, dir, perpendicular(dir), 1.15f * size, size,
                                      0.9f * size, 0.2f, grows, gsides));
        }
    }
    return parts.finish();
}

// ---- tassel -------------------------------------------------------------------------------------

FloralFamilyInfo tasselInfo() {
    FloralFamilyInfo f;
    f.name = "tassel";
    f.fruit = true;
    f.description =
        "Tassel (male panicle): an upright central spike with slender branches from its lower "
        "part that spread and arch down, all set with paired spikelets; open (shedding pollen) "
        "it hangs out yellow anthers, closed its branches stay close to the spike.";
    f.defaultColor = {0.72f, 0.64f, 0.38f};
    f.parts = {"spikelets", "axes", "anthers"};
    auto& t = f.parameters;
    t.push_back(whole("branch_count", 10, 0, 30, "Side branches"));
    t.push_back(real("branch_length", 0.5f, 0.1f, 0.9f, "Longest branch / tassel length"));
    t.push_back(real("branch_angle", 35.0f, 5.0f, 90.0f,
                     "Branches' angle from the spike at their base, degrees"));
    t.push_back(real("droop", 50.0f, 0.0f, 120.0f, "Downward arch along a branch, degrees"));
    t.push_back(real("spikelet_density", 1.0f, 0.2f, 3.0f, "Spikelets per unit length, relative"));
    t.push_back(whole("anthers", 1, 0, 1, "1 = hanging anthers on an open tassel"));
    return f;
}

void tasselSpikelets(PartSet& parts, std::span<const vec3> line, float density, bool anthers,
                     unsigned rows, unsigned sides, float from) {
    float length = 0.0f;
    for (std::size_t i = 1; i < line.size(); ++i) length += glm::length(line[i] - line[i - 1]);
    const int n = std::max(2, int(std::lround(45.0f * density * length * (1.0f - from))));
    for (int k = 0; k < n; ++k) {
        const float f = from + (1.0f - from) * (float(k) + 0.5f) / float(n);
        const PathPoint at = pathAt(line, kZ, f);
        const float az = float(k) * 2.0f;
        const vec3 out = std::cos(az) * at.side + std::sin(az) * at.normal;
        const vec3 dir = glm::normalize(at.tangent + 0.35f * out);
        const vec3 base = at.position + out * 0.006f;
        parts.add("spikelets", grain(base, dir, out, 0.032f, 0.012f, 0.010f, 0.5f, rows, sides));
        if (anthers && k % 3 == 0) {
            const vec3 hang = glm::normalize(-kX + 0.3f * out);
            const vec3 c = base + dir * 0.02f + out * 0.01f;
            parts.add("anthers", grain(c, hang, out, 0.02f, 0.007f, 0.006f, 0.0f, rows, sides));
        }
    }
}

OrganPrototype buildTassel(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("spikelets", req.color);
    parts.declare("axes", kCerealStalkGreen);
    parts.declare("anthers", {0.92f, 0.82f, 0.36f});
    const bool open = req.open, anthers = open && p.flag("anthers");
    const float density = p("spikelet_density");
    const unsigned rows = resolution(s, 0.25f, 2), sides = resolution(s, 0.25f, 3);
    const std::vector<vec3> spike = arcPath({0, 0, 0}, kX, kZ, 1.0f, 3.0f, 8);
    parts.add("axes", tube(spike,
                           std::vector<float>{0.014f, 0.013f, 0.012f, 0.011f, 0.01f, 0.009f, 0.008f,
                                              0.007f, 0.005f},
                           resolution(s, 0.5f, 3)));
    tasselSpikelets(parts, spike, density, anthers, rows, sides, 0.38f);
    const int branches = p.count("branch_count");
    for (int b = 0; b < branches; ++b) {
        const float t = float(b) / float(std::max(branches - 1, 1));
        const vec3 base{0.12f + 0.24f * t, 0, 0};
        const vec3 out = radialDir(float(b) * 2.39996f + 0.2f * rng.uniform(-1.0f, 1.0f));
        const float angle = p("branch_angle") * (open ? 1.0f : 0.25f) * kDeg;
        const vec3 dir = std::cos(angle) * kX + std::sin(angle) * out;
        const float len = p("branch_length") * (1.0f - 0.45f * t);
        // Arching down (toward -x); the turn is limited so branch tips stay above the base.
        const float droop = open ? std::min(p("droop"), 100.0f - angle / kDeg) : 0.0f;
        vec3 down = -kX - dir * glm::dot(-kX, dir);
        down = glm::length(down) > 1e-3f ? glm::normalize(down) : out;
        const std::vector<vec3> arm = arcPath(base, dir, down, len, std::max(droop, 0.0f), 6);
        parts.add("axes", tube(arm, std::vector<float>(arm.size(), 0.005f), 3));
        tasselSpikelets(parts, arm, density, anthers, rows, sides, 0.15f);
    }
    return parts.finish();
}

// ---- husked_ear ---------------------------------------------------------------------------------

FloralFamilyInfo huskedEarInfo() {
    FloralFamilyInfo f;
    f.name = "husked_ear";
    f.fruit = true;
    f.description =
        "Husked ear (female spike): a tapering cylindrical cob set with rows of kernels, "
        "wrapped in green husk leaves that close to a point over its tip, with a tuft of silk; "
        "the husks can be peeled back to show the kernels.";
    f.defaultColor = {0.45f, 0.60f, 0.28f};
    f.parts = {"husk", "cob", "silk", "shank"};
    auto& t = f.parameters;
    t.push_back(real("ear_diameter", 0.26f, 0.1f, 0.6f, "Cob diameter / ear length"));
    t.push_back(whole("kernel_rows", 16, 8, 26, "Kernel rows around the cob"));
    t.push_back(whole("kernels_per_row", 40, 10, 70, "Kernels along a row"));
    t.push_back(real("husk_cover", 1.0f, 0.0f, 1.0f,
                     "1 = husks wrapped around the ear .. 0 = husks peeled back"));
    t.push_back(whole("husk_leaves", 8, 0, 16, "Husk leaves"));
    t.push_back(real("silk_length", 0.12f, 0.0f, 0.5f, "Silk tuft length / ear length"));
    t.push_back(real("shank_length", 0.1f, 0.02f, 0.4f, "Shank (stalk) length / ear length"));
    addColor(t, "kernel", {0.96f, 0.80f, 0.28f}, "Kernel");
    return f;
}

struct EarShape {
    float x0, length, radius;
    // Cob radius at fraction t of its length (rounded base and tip).
    float radiusAt(float t) const {
        return radius * (1.0f - 0.3f * t * t) *
               ppow(std::sin(0.5f * kPi * std::min(t / 0.1f, 1.0f)), 0.6f) *
               ppow(std::sin(0.5f * kPi * std::min((1.0f - t) / 0.1f, 1.0f)), 0.6f);
    }
    // Radius the husk keeps around the cob: it closes faster at the base than the cob does.
    float huskAt(float t) const {
        return radius * (1.0f - 0.3f * t * t) *
               ppow(std::sin(0.5f * kPi * std::min(t / 0.06f, 1.0f)), 0.4f);
    }
};

Mesh earCob(const EarShape& ear, const Params& p, unsigned s) {
    const unsigned rows = resolution(s, 6.0f, 8), sides = resolution(s, 4.0f, 8);
    const int kr = p.count("kernel_rows"), kn = p.count("kernels_per_row");
    // Kernel bumps only where the mesh can resolve them (three vertices per kernel).
    const float rowBump = sides >= unsigned(3 * kr) ? 0.06f : 0.0f;
    const float kernelBump = rows >= unsigned(3 * kn) ? 0.04f : 0.0f;
    return closedBody(rows, sides, [&](float u, float th) {
        const float rows01 = 0.5f + 0.5f * std::cos(float(kr) * th);
        const float along = 0.5f + 0.5f * std::cos(2.0f * kPi * float(kn) * u);
        const float r =
            ear.radiusAt(u) * (1.0f - rowBump * (1.0f - std::sqrt(rows01)) -
                               kernelBump * (1.0f - std::sqrt(along)) * smooth(0.0f, 0.1f, u));
        return vec3(ear.x0 + ear.length * u, 0, 0) + r * radialDir(th);
    });
}

Mesh huskLeaf(const EarShape& ear, float az, float span, float layer, float open, unsigned rows,
              unsigned cols) {
    const float reach = 1.0f - ear.x0;  // husks close to a point beyond the cob's tip
    const float coneStart = 0.85f * ear.length / reach;
    const vec3 base = vec3(ear.x0, 0, 0) + radialDir(az) * (ear.radius * layer);
    const vec3 hinge = glm::normalize(glm::cross(kX, radialDir(az)));
    return gridMesh({rows, cols, false, false, true}, [&](unsigned i, unsigned j) {
        const float u = float(i) / float(rows);
        const float v = i == rows ? 0.0f : -1.0f + 2.0f * float(j) / float(cols);
        // Hug the cob, then close over its tip in a rounded cone.
        const float hug = ear.huskAt(std::min(u, coneStart) * reach / ear.length) * layer + 0.012f;
        const float radius =
            u <= coneStart ? hug : hug * std::sqrt(std::max(1.0f - u, 0.0f) / (1.0f - coneStart));
        const float a = az + v * 0.5f * span * (1.0f - 0.3f * u);
        vec3 q = vec3(ear.x0 + reach * u, 0, 0) + radius * radialDir(a);
        if (open > 0.0f)
            q = base + rotateAbout(q - base, hinge, -open * 100.0f * kDeg * smooth(0.0f, 0.6f, u));
        return q;
    });
}

OrganPrototype buildHuskedEar(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("husk", req.color);
    parts.declare("cob", p.color("kernel"));
    parts.declare("silk", {0.78f, 0.62f, 0.34f});
    parts.declare("shank", {0.40f, 0.52f, 0.24f});
    const float shank = p("shank_length");
    const float x0 = shank + 0.01f;
    const EarShape ear{x0, (1.0f - x0) / 1.25f, 0.5f * p("ear_diameter")};
    parts.add("shank", tube({0, 0, 0}, {ear.x0 + 0.02f, 0, 0}, 0.22f * ear.radius,
                            0.3f * ear.radius, resolution(s, 0.5f, 4)));
    parts.add("cob", earCob(ear, p, s));
    const int leaves = p.count("husk_leaves");
    const float open = 1.0f - p("husk_cover");
    for (int k = 0; k < leaves; ++k) {
        const float az = 2.0f * kPi * float(k) / float(leaves) + 0.1f * rng.uniform(-1.0f, 1.0f);
        const float span = std::min(2.0f * kPi / float(leaves) * 1.8f, 2.5f);
        parts.add("husk", huskLeaf(ear, az, span, 1.05f + 0.025f * float(k % 3), open,
                                   resolution(s, 2.0f, 4), resolution(s, 0.5f, 2)));
    }
    const float silk = p("silk_length");
    if (silk > 0.0f) {
        const vec3 tip =
            open > 0.3f || leaves == 0 ? vec3(ear.x0 + ear.length, 0, 0) : vec3(0.99f, 0, 0);
        for (int k = 0; k < 18; ++k) {
            const vec3 out = radialDir(float(k) * 2.39996f);
            const vec3 dir = glm::normalize(kX + (0.3f + 0.5f * rng.uniform01()) * out);
            const std::vector<vec3> strand =
                arcPath(tip, dir, out, silk * rng.uniform(0.7f, 1.0f), 50.0f, 4);
            const vec3 w = perpendicular(dir) * 0.004f;
            parts.add("silk", gridMesh({4, 1, false, false, false}, [&](unsigned i, unsigned j) {
                          return strand[i] + (j ? w : -w) * (1.0f - 0.5f * float(i) / 4.0f);
                      }));
        }
    }
    return parts.finish();
}

}  // namespace

std::vector<Family> cerealFamilies() {
    return {{spikeInfo(), buildSpike},
            {noddingPanicleInfo(), buildNoddingPanicle},
            {compactPanicleInfo(), buildCompactPanicle},
            {tasselInfo(), buildTassel},
            {huskedEarInfo(), buildHuskedEar}};
}

}  // namespace plantarch::organs
