// Flower families of the organ library: radial petal flowers, papilionaceous (pea) flowers,
// funnel (trumpet) flowers, bract flowers and catkins. Each builds an open flower or a closed
// bud.
//
// Frame: the flower's axis is +x from the top of its stalk at the origin; a short pedicel
// stub and the receptacle come first, so petals that bend back (reflexed) stay at x > 0.

#include <algorithm>
#include <cmath>

#include "geometry/organ_library_internal.h"

namespace plantarch::organs {

namespace {

const vec3 kSepalGreen{0.30f, 0.48f, 0.17f};

// Pedicel stub and receptacle: a tube from the origin widening to `radius` at x = `length`.
Mesh receptacle(float length, float radius, unsigned sides) {
    const vec3 path[3] = {{0, 0, 0}, {0.5f * length, 0, 0}, {length, 0, 0}};
    const float radii[3] = {0.22f * radius, 0.3f * radius, radius};
    return tube(path, radii, sides);
}

// ---- petal_flower ---------------------------------------------------------------------------

constexpr float kRecLength = 0.2f;  // pedicel stub + receptacle
constexpr float kRecRadius = 0.07f;

FloralFamilyInfo petalFlowerInfo() {
    FloralFamilyInfo f;
    f.name = "petal_flower";
    f.fruit = false;
    f.description =
        "Radial flower: a ring of petals around a centre of stamens or an anther cone, with "
        "optional sepals: rose-like (5 round white or pink petals, many stamens), star-shaped "
        "with reflexed petals around an anther cone, small and yellow, or a white star. "
        "Closed: a bud of folded petals clasped by the sepals.";
    f.defaultColor = {0.97f, 0.95f, 0.92f};
    f.parts = {"petals", "flower_centre", "sepals"};
    auto& t = f.parameters;
    t.push_back(whole("petal_count", 5, 3, 20, "Number of petals"));
    t.push_back(real("petal_length", 0.6f, 0.1f, 2.0f,
                     "Petal length, in flower units (pedicel stub + receptacle = 0.2)"));
    t.push_back(real("petal_width", 0.75f, 0.05f, 1.5f, "Petal width / petal length"));
    t.push_back(real("petal_tip", 0.0f, 0.0f, 1.0f, "Petal tip: 0 rounded .. 1 pointed"));
    t.push_back(real("petal_widest", 0.62f, 0.1f, 0.9f,
                     "Position of the petal's widest point, fraction of its length"));
    t.push_back(real("cup_angle", 70.0f, 5.0f, 150.0f,
                     "Open petals' angle from the flower axis at their base, degrees "
                     "(90 = flat, smaller = cup)"));
    t.push_back(real("reflex", 10.0f, -90.0f, 150.0f,
                     "Extra bend from petal base to tip, degrees (positive bends back "
                     "toward the stalk)"));
    t.push_back(real("petal_cupping", 0.12f, -0.5f, 0.8f,
                     "Cross curvature of a petal, fraction of its width (positive = concave "
                     "toward the flower's front)"));
    t.push_back(
        real("petal_wave", 0.0f, 0.0f, 0.3f, "Margin waviness, fraction of the petal width"));
    t.push_back(whole("sepal_count", 5, 0, 20, "Number of sepals (0 = none)"));
    t.push_back(real("sepal_length", 0.3f, 0.02f, 2.0f, "Sepal length, same units as petals"));
    t.push_back(real("sepal_width", 0.35f, 0.05f, 1.0f, "Sepal width / sepal length"));
    t.push_back(real("sepal_angle", 100.0f, 0.0f, 170.0f,
                     "Open sepals' angle from the flower axis, degrees"));
    t.push_back(real("centre_size", 0.1f, 0.0f, 0.5f,
                     "Radius of the central disc (receptacle top / pistil), same units"));
    t.push_back(whole("stamen_count", 20, 0, 80, "Free stamens around the centre"));
    t.push_back(real("stamen_length", 0.16f, 0.02f, 1.0f, "Stamen length, same units"));
    t.push_back(real("anther_cone", 0.0f, 0.0f, 1.5f,
                     "Length of a cone of fused anthers on the axis, 0 = none"));
    addColor(t, "centre", {0.96f, 0.80f, 0.18f}, "Centre (stamens, anther cone)");
    t.push_back(real("irregularity", 0.04f, 0.0f, 0.3f,
                     "Random variation of petal size and spacing (drawn from the stream)"));
    return f;
}

// Sepals between the petals (open) or clasping the bud (closed).
void petalFlowerSepals(PartSet& parts, const Params& p, bool open, unsigned rows, unsigned cols) {
    const int n = p.count("sepal_count");
    const int petals = p.count("petal_count");
    for (int k = 0; k < n; ++k) {
        const float az = 2.0f * kPi * (float(k) + 0.5f) / float(n) + (n == petals ? 0.0f : 0.3f);
        PetalSpec s;
        s.length = p("sepal_length");
        s.width = p("sepal_width") * s.length;
        s.widest = 0.3f;
        s.tip = 1.0f;
        s.claw = 0.6f;
        s.cupping = 0.1f;
        if (open) {
            s.baseAngle = p("sepal_angle");
            s.tipAngle = s.baseAngle + 15.0f;
        } else {
            s.baseAngle = 30.0f;
            s.tipAngle = 0.0f;
            s.cupping = 0.3f;
        }
        const vec3 origin = vec3(kRecLength * 0.85f, 0, 0) + radialDir(az) * kRecRadius * 0.8f;
        parts.add("sepals", petalMesh(s, origin, kX, radialDir(az), rows, cols));
    }
}

// Central disc, free stamens and the anther cone of an open flower.
void petalFlowerCentre(PartSet& parts, const Params& p, unsigned s) {
    const float cs = p("centre_size");
    const vec3 c{kRecLength, 0, 0};
    const unsigned rows = resolution(s, 0.5f, 2), sides = resolution(s, 1.0f, 4);
    if (cs > 0.0f)
        parts.add("flower_centre",
                  ellipsoid(c, {0.45f * cs, 0, 0}, {0, cs, 0}, {0, 0, cs}, rows, sides));
    const float cone = p("anther_cone");
    if (cone > 0.0f) {
        const float rb = std::max(cs, 0.05f) * 0.9f;
        parts.add(
            "flower_centre", closedBody(resolution(s, 1.0f, 2), sides, [&](float u, float th) {
                const float r = rb * ppow(std::sin(kPi * std::min(u, 0.5f)), 0.5f) * (1.1f - u);
                return c + vec3(cone * u, 0, 0) + r * radialDir(th + 0.3f * u);
            }));
    }
    const int n = p.count("stamen_count");
    const float len = p("stamen_length");
    const unsigned antherRows = resolution(s, 0.125f, 2);
    for (int k = 0; k < n; ++k) {
        const float az = 2.0f * kPi * (float(k) + 0.25f * float(k % 2)) / float(n);
        const vec3 r = radialDir(az);
        const float spread = (k % 2 ? 35.0f : 25.0f) * kDeg;
        const vec3 base = c + r * (0.75f * std::max(cs, 0.03f));
        const vec3 dir = std::cos(spread) * kX + std::sin(spread) * r;
        const vec3 tip = base + dir * len * (k % 2 ? 0.85f : 1.0f);
        parts.add("flower_centre", tube(base, tip, 0.006f, 0.005f, 3));
        parts.add("flower_centre",
                  ellipsoid(tip + dir * 0.012f, dir * 0.014f, glm::cross(dir, r) * 0.02f,
                            r * 0.012f, antherRows, 4));
    }
}

// Closed bud: the petals as overlapping segments of an ovoid (pointed for pointed petals),
// each a sheet spanning a little more than its share of the circumference.
Mesh budPetal(const Params& p, int k, int n, float az, unsigned rows, unsigned cols) {
    const float tip = p("petal_tip");
    const float length = p("petal_length") * glm::mix(0.55f, 0.75f, tip);
    const float radius = p("petal_length") * glm::mix(0.3f, 0.17f, tip) *
                         std::clamp(p("petal_width") * 1.4f, 0.6f, 1.2f);
    const float span = 1.3f * kPi / float(n);
    const float layer = 1.0f + 0.025f * float(k);
    return gridMesh({rows, cols, false, false, true}, [&](unsigned i, unsigned j) {
        const float u = float(i) / float(rows);
        const float v = i == rows ? 0.0f : -1.0f + 2.0f * float(j) / float(cols);
        // Ovoid profile from the receptacle rim to the apex; pointed buds taper linearly.
        const float round = ppow(std::sin(kPi * (0.18f + 0.82f * u)), 0.75f);
        const float r = radius * layer * glm::mix(round, (1.0f - u) * 0.9f + 0.1f * round, tip);
        const float x = kRecLength + length * u;
        return vec3(x, 0, 0) + r * radialDir(az + v * span * (1.0f - 0.3f * u));
    });
}

OrganPrototype buildPetalFlower(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("petals", req.color);
    parts.declare("flower_centre", p.color("centre"));
    parts.declare("sepals", kSepalGreen);
    parts.add("sepals", receptacle(kRecLength, kRecRadius, resolution(s, 1.0f, 4)));

    const int n = p.count("petal_count");
    const float jitter = p("irregularity");
    const unsigned rows = resolution(s, 1.0f, 1), cols = resolution(s, 0.5f, 1);
    for (int k = 0; k < n; ++k) {
        const float az = 2.0f * kPi * float(k) / float(n) + jitter * rng.uniform(-0.5f, 0.5f);
        const float grow = 1.0f + jitter * rng.uniform(-1.0f, 1.0f);
        if (!req.open) {
            parts.add("petals", budPetal(p, k, n, az, rows, cols));
            continue;
        }
        PetalSpec ps;
        ps.length = p("petal_length") * grow;
        ps.width = p("petal_width") * p("petal_length");
        ps.widest = p("petal_widest");
        ps.tip = p("petal_tip");
        ps.claw = 0.18f;
        ps.baseAngle = p("cup_angle") + (k % 2 ? 2.0f : -2.0f);
        ps.tipAngle = ps.baseAngle + p("reflex");
        ps.cupping = p("petal_cupping");
        ps.wave = p("petal_wave");
        ps.lift = 0.004f * float(k % 2);
        const vec3 origin = vec3(kRecLength, 0, 0) + radialDir(az) * kRecRadius * 0.9f;
        parts.add("petals", petalMesh(ps, origin, kX, radialDir(az), rows, cols));
    }
    petalFlowerSepals(parts, p, req.open, rows, cols);
    if (req.open) petalFlowerCentre(parts, p, s);
    return parts.finish();
}

// ---- papilionaceous_flower --------------------------------------------------------------------

FloralFamilyInfo papilionaceousInfo() {
    FloralFamilyInfo f;
    f.name = "papilionaceous_flower";
    f.fruit = false;
    f.description =
        "Pea flower: an upright banner petal, two wings at the sides and a boat-shaped keel "
        "that curves up (or coils), in a green bell-shaped calyx with five teeth. Closed: a "
        "flattened, upcurved pointed bud in the calyx.";
    f.defaultColor = {0.96f, 0.95f, 0.92f};
    f.parts = {"petals", "calyx"};
    auto& t = f.parameters;
    t.push_back(real("banner_length", 0.55f, 0.1f, 1.5f,
                     "Banner (standard) length, in units where the calyx tube is 0.2 long"));
    t.push_back(real("banner_width", 1.2f, 0.3f, 2.0f, "Banner width / banner length"));
    t.push_back(real("banner_angle", 100.0f, 30.0f, 170.0f,
                     "Banner tip angle from the flower axis, degrees (90 = upright)"));
    t.push_back(real("wing_length", 0.4f, 0.1f, 1.5f, "Wing petal length, same units"));
    t.push_back(real("wing_width", 0.55f, 0.1f, 1.5f, "Wing width / wing length"));
    t.push_back(real("wing_angle", 20.0f, 0.0f, 80.0f, "Wings' spread from the axis, degrees"));
    t.push_back(real("keel_length", 0.45f, 0.1f, 1.5f, "Keel length, same units"));
    t.push_back(
        real("keel_curl", 70.0f, 0.0f, 330.0f,
             "Upward turn of the keel from base to tip, degrees (above 180 the keel coils)"));
    t.push_back(real("calyx_length", 0.2f, 0.05f, 0.6f, "Calyx tube length, same units"));
    t.push_back(real("bud_length", 0.65f, 0.2f, 2.0f, "Closed bud length beyond the calyx"));
    return f;
}

Mesh calyxCup(float x0, float length, float radius, int teeth, float toothLength, unsigned rows,
              unsigned sides) {
    return gridMesh({rows, sides, true, true, false}, [&](unsigned i, unsigned j) {
        const float u = float(i) / float(rows);
        const float th = 2.0f * kPi * float(j) / float(sides);
        const float tooth = toothLength * std::pow(0.5f + 0.5f * std::cos(float(teeth) * th), 3.0f);
        const float x = x0 + length * u + tooth * u * u;
        const float r = radius * std::sqrt(u) * (1.0f + 0.15f * u);
        return vec3(x, 0, 0) + r * radialDir(th);
    });
}

void papilionaceousOpen(PartSet& parts, const Params& p, unsigned s) {
    const float xm = 0.06f + p("calyx_length");  // calyx mouth
    const unsigned rows = resolution(s, 1.0f, 1), cols = resolution(s, 0.5f, 1);
    PetalSpec banner;
    banner.length = p("banner_length");
    banner.width = p("banner_width") * banner.length;
    banner.widest = 0.58f;
    banner.claw = 0.12f;
    banner.baseAngle = 20.0f;
    banner.tipAngle = p("banner_angle");
    banner.cupping = -0.12f;
    parts.add("petals", petalMesh(banner, {xm - 0.02f, 0, 0.03f}, kX, {0, 0, 1}, rows, cols));
    for (int side : {-1, 1}) {
        PetalSpec wing;
        wing.length = p("wing_length");
        wing.width = p("wing_width") * wing.length;
        wing.widest = 0.6f;
        wing.claw = 0.2f;
        wing.baseAngle = 0.6f * p("wing_angle");
        wing.tipAngle = p("wing_angle");
        wing.cupping = 0.08f;
        const vec3 radial = glm::normalize(vec3(0, float(side), 0.15f));
        parts.add("petals", petalMesh(wing, {xm - 0.02f, 0.035f * float(side), 0.0f}, kX, radial,
                                      rows, cols));
    }
    // Keel: a laterally flattened beak curving up from below the wings.
    const float len = p("keel_length");
    const std::vector<vec3> path =
        arcPath({xm - 0.03f, 0, -0.02f}, kX, {0, 0, 1}, len, p("keel_curl"), rows);
    parts.add("petals", sweptBody(path, {0, 0, 1}, resolution(s, 1.5f, 2), resolution(s, 1.0f, 4),
                                  [&](float u, float th) {
                                      const float r = ppow(std::sin(kPi * u), 0.6f) *
                                                      (1.0f - 0.6f * u) * 0.16f * len;
                                      return vec2(0.45f * r * std::cos(th), r * std::sin(th));
                                  }));
}

OrganPrototype buildPapilionaceous(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("petals", req.color);
    parts.declare("calyx", kSepalGreen);
    const unsigned sides = resolution(s, 1.0f, 6);
    const float calyxLength = p("calyx_length");
    parts.add("calyx", tube({0, 0, 0}, {0.08f, 0, 0}, 0.025f, 0.03f, sides));
    parts.add("calyx", calyxCup(0.06f, calyxLength, 0.1f, 5, 0.07f, resolution(s, 0.5f, 2), sides));
    if (req.open) {
        papilionaceousOpen(parts, p, s);
    } else {
        const float len = p("bud_length");
        const std::vector<vec3> path =
            arcPath({0.06f + 0.3f * calyxLength, 0, 0}, kX, {0, 0, 1}, len, 35.0f, 8);
        parts.add("petals", sweptBody(path, {0, 0, 1}, resolution(s, 1.5f, 2),
                                      resolution(s, 1.0f, 4), [&](float u, float th) {
                                          const float r = ppow(std::sin(kPi * u), 0.7f) *
                                                          (1.0f - 0.45f * u) * 0.17f * len;
                                          return vec2(0.45f * r * std::cos(th), r * std::sin(th));
                                      }));
    }
    return parts.finish();
}

// ---- funnel_flower ----------------------------------------------------------------------------

FloralFamilyInfo funnelInfo() {
    FloralFamilyInfo f;
    f.name = "funnel_flower";
    f.fruit = false;
    f.description =
        "Funnel or trumpet flower: a fused corolla widening from a narrow tube to a broad "
        "shallow-lobed, pleated mouth, its throat in a second colour, on a small green calyx. "
        "Also a campanulate-rotate corolla with a short tube. Closed: a slender bud furled in "
        "a spiral.";
    f.defaultColor = {0.98f, 0.97f, 0.96f};
    f.parts = {"corolla", "throat", "calyx"};
    auto& t = f.parameters;
    t.push_back(real("mouth_width", 2.2f, 0.3f, 4.0f, "Mouth diameter / corolla length"));
    t.push_back(real("tube_width", 0.18f, 0.02f, 1.0f, "Tube diameter / corolla length"));
    t.push_back(real("flare", 2.2f, 1.0f, 6.0f,
                     "How late the corolla widens: 1 = straight cone, larger = long narrow "
                     "tube then an abrupt flare"));
    t.push_back(whole("lobes", 5, 0, 10, "Corolla lobes (angles of the rim)"));
    t.push_back(real("lobe_depth", 0.08f, 0.0f, 0.5f,
                     "Depth of the notches between lobes, fraction of the mouth radius"));
    t.push_back(real("pleat", 0.05f, 0.0f, 0.3f,
                     "Folds along the midribs of the lobes, fraction of the corolla length"));
    t.push_back(real("throat_fraction", 0.4f, 0.0f, 1.0f,
                     "Part of the corolla from its base drawn in the throat colour"));
    addColor(t, "throat", {0.97f, 0.93f, 0.62f}, "Throat");
    t.push_back(
        real("sepal_length", 0.14f, 0.02f, 0.6f, "Sepal length, fraction of the corolla length"));
    t.push_back(real("bud_twist", 200.0f, 0.0f, 720.0f, "Spiral twist of the closed bud, degrees"));
    return f;
}

void funnelCalyx(PartSet& parts, const Params& p, bool open, unsigned s) {
    const unsigned sides = resolution(s, 1.0f, 4);
    parts.add("calyx", tube({0, 0, 0}, {0.07f, 0, 0}, 0.02f, 0.035f, sides));
    const unsigned rows = resolution(s, 0.5f, 1), cols = resolution(s, 0.25f, 1);
    for (int k = 0; k < 5; ++k) {
        const float az = 2.0f * kPi * (float(k) + 0.5f) / 5.0f;
        PetalSpec sp;
        sp.length = p("sepal_length");
        sp.width = 0.5f * sp.length;
        sp.widest = 0.4f;
        sp.tip = 0.7f;
        sp.claw = 0.7f;
        sp.baseAngle = open ? 25.0f : 20.0f;
        sp.tipAngle = 5.0f;
        sp.cupping = 0.15f;
        parts.add("calyx", petalMesh(sp, vec3(0.06f, 0, 0) + radialDir(az) * 0.03f, kX,
                                     radialDir(az), rows, cols));
    }
}

OrganPrototype buildFunnel(const FloralPrototypeRequest& req, const Params& p, Rng&) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("corolla", req.color);
    parts.declare("throat", p.color("throat"));
    parts.declare("calyx", kSepalGreen);
    funnelCalyx(parts, p, req.open, s);
    const unsigned sides = resolution(s, 3.0f, 6);
    const int lobes = p.count("lobes");
    const float x0 = 0.05f;
    if (!req.open) {
        const float twist = p("bud_twist") * kDeg;
        parts.add(
            "corolla",
            closedBody(resolution(s, 1.5f, 4), resolution(s, 2.0f, 6), [&](float u, float th) {
                const float r =
                    0.11f * ppow(std::sin(kPi * std::pow(u, 0.75f)), 0.8f) * (1.0f - 0.35f * u) *
                    (1.0f + 0.12f * std::cos(float(std::max(lobes, 1)) * th + twist * u));
                return vec3(x0 + 0.8f * u, 0, 0) + r * radialDir(th);
            }));
        return parts.finish();
    }
    const float length = 1.0f - x0;
    const float rt = 0.5f * p("tube_width") * length, rm = 0.5f * p("mouth_width") * length;
    const float flare = p("flare"), depth = p("lobe_depth"), pleat = p("pleat");
    const unsigned rows = resolution(s, 2.0f, 4);
    const auto point = [&](float u, float th) {
        const float lobe = 0.5f - 0.5f * std::cos(float(lobes) * th);
        const float r = (rt + (rm - rt) * std::pow(u, flare)) *
                        (1.0f - depth * std::pow(u, 4.0f) * lobe * lobe);
        // The limb turns outward: x advances less per row as the corolla flares.
        const float x = x0 + length * (1.0f - std::pow(1.0f - u, 1.6f)) -
                        pleat * length * std::pow(u, 3.0f) * std::cos(float(lobes) * th);
        return vec3(x, 0, 0) + r * radialDir(th);
    };
    // Rows below the throat fraction go to the throat part (the boundary row is repeated).
    const unsigned split =
        std::min(rows - 1, unsigned(std::lround(p("throat_fraction") * float(rows))));
    const auto band = [&](unsigned first, unsigned last, bool apex) {
        return gridMesh({last - first, sides, true, apex, false}, [&](unsigned i, unsigned j) {
            const float u = float(first + i) / float(rows);
            return point(apex && i == 0 ? 0.0f : u, 2.0f * kPi * float(j) / float(sides));
        });
    };
    if (split > 0) parts.add("throat", band(0, split, true));
    parts.add("corolla", band(split, rows, split == 0));
    return parts.finish();
}

// ---- bract_flower ----------------------------------------------------------------------------

FloralFamilyInfo bractInfo() {
    FloralFamilyInfo f;
    f.name = "bract_flower";
    f.fruit = false;
    f.description =
        "Bract flower: three (or more) broad papery coloured bracts joined at the base, each "
        "carrying a slender tubular floret along its midrib that opens into a small white "
        "star. Closed: the bracts clasped into a pointed, three-sided bud.";
    f.defaultColor = {0.78f, 0.14f, 0.50f};
    f.parts = {"bracts", "florets", "stalk"};
    auto& t = f.parameters;
    t.push_back(whole("bract_count", 3, 2, 6, "Number of bracts (and florets)"));
    t.push_back(real("bract_length", 0.9f, 0.3f, 1.5f, "Bract length"));
    t.push_back(real("bract_width", 0.8f, 0.2f, 1.5f, "Bract width / bract length"));
    t.push_back(real("bract_angle", 38.0f, 5.0f, 100.0f,
                     "Open bracts' angle from the flower axis, degrees"));
    t.push_back(real("bract_cupping", 0.2f, -0.3f, 0.6f, "Cross curvature of the bracts"));
    t.push_back(real("bract_wave", 0.03f, 0.0f, 0.2f, "Margin waviness of the bracts"));
    t.push_back(real("floret_length", 0.6f, 0.0f, 1.0f,
                     "Floret tube length, fraction of the bract length (0 = no florets)"));
    addColor(t, "floret", {0.96f, 0.95f, 0.85f}, "Floret");
    return f;
}

void bractFloret(PartSet& parts, vec3 base, vec3 dir, vec3 radial, float length, unsigned s) {
    const vec3 tip = base + dir * length;
    parts.add("florets", tube(base, tip, 0.02f, 0.028f, resolution(s, 0.5f, 3), 2));
    const unsigned rows = resolution(s, 0.5f, 1), cols = resolution(s, 0.25f, 1);
    const vec3 side = glm::normalize(glm::cross(dir, radial));
    for (int k = 0; k < 5; ++k) {
        const float a = 2.0f * kPi * float(k) / 5.0f;
        const vec3 r = std::cos(a) * radial + std::sin(a) * side;
        PetalSpec lobe;
        lobe.length = 0.07f;
        lobe.width = 0.06f;
        lobe.widest = 0.5f;
        lobe.tip = 0.6f;
        lobe.claw = 0.5f;
        lobe.baseAngle = 80.0f;
        lobe.tipAngle = 95.0f;
        parts.add("florets", petalMesh(lobe, tip + r * 0.02f, dir, r, rows, cols));
    }
}

OrganPrototype buildBract(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("bracts", req.color);
    parts.declare("florets", p.color("floret"));
    parts.declare("stalk", kSepalGreen);
    const float x0 = 0.06f;
    parts.add("stalk", tube({0, 0, 0}, {x0 + 0.02f, 0, 0}, 0.018f, 0.03f, resolution(s, 1.0f, 4)));
    const int n = p.count("bract_count");
    const float len = p("bract_length");
    const unsigned rows = resolution(s, 1.5f, 2), cols = resolution(s, 1.0f, 2);
    for (int k = 0; k < n; ++k) {
        const float az = 2.0f * kPi * float(k) / float(n) + 0.05f * rng.uniform(-1.0f, 1.0f);
        const vec3 radial = radialDir(az);
        PetalSpec b;
        b.length = len * (1.0f + 0.04f * rng.uniform(-1.0f, 1.0f));
        b.width = p("bract_width") * len;
        b.widest = 0.38f;
        b.tip = 0.45f;
        b.claw = 0.25f;
        if (req.open) {
            b.baseAngle = p("bract_angle") * 0.6f;
            b.tipAngle = p("bract_angle") * 1.25f;
            b.cupping = p("bract_cupping");
            b.wave = p("bract_wave");
            b.waves = 2.5f;
        } else {
            b.length *= 0.75f;
            b.baseAngle = 22.0f;
            b.tipAngle = -12.0f;
            b.cupping = 0.45f;
        }
        b.lift = 0.003f * float(k);
        const vec3 origin = vec3(x0, 0, 0) + radial * 0.02f;
        parts.add("bracts", petalMesh(b, origin, kX, radial, rows, cols));
        if (req.open && p("floret_length") > 0.0f) {
            const float a = std::max(p("bract_angle") * 0.55f, 3.0f) * kDeg;
            const vec3 dir = std::cos(a) * kX + std::sin(a) * radial;
            bractFloret(parts, origin + radial * 0.02f, dir, radial, p("floret_length") * len, s);
        }
    }
    return parts.finish();
}

// ---- catkin ------------------------------------------------------------------------------------

FloralFamilyInfo catkinInfo() {
    FloralFamilyInfo f;
    f.name = "catkin";
    f.fruit = false;
    f.description =
        "Catkin (male flowers): a slender pendulous spike densely covered in small "
        "overlapping scale-like flowers. Closed: a straight, stouter cone of scales (the "
        "dormant catkin bud).";
    f.defaultColor = {0.62f, 0.64f, 0.30f};
    f.parts = {"flowers", "axis"};
    auto& t = f.parameters;
    t.push_back(whole("whorls", 16, 3, 60, "Rings of flowers along the catkin"));
    t.push_back(whole("flowers_per_whorl", 6, 3, 12, "Flowers in each ring"));
    t.push_back(real("width", 0.16f, 0.04f, 0.5f, "Catkin diameter / length"));
    t.push_back(real("droop", 50.0f, 0.0f, 150.0f,
                     "Bend of the open catkin toward -z from base to tip, degrees"));
    return f;
}

OrganPrototype buildCatkin(const FloralPrototypeRequest& req, const Params& p, Rng& rng) {
    const unsigned s = std::max(2u, req.subdivisions);
    PartSet parts;
    parts.declare("flowers", req.color);
    parts.declare("axis", {0.36f, 0.40f, 0.18f});
    const int whorls = p.count("whorls"), per = p.count("flowers_per_whorl");
    // The closed bud is a compact cone: shorter scales packed along a stouter axis (it is
    // scaled to unit length like the open catkin).
    const float length = 1.0f;
    const float radius = 0.5f * p("width") * (req.open ? 1.0f : 1.6f);
    const std::vector<vec3> axis =
        arcPath({0, 0, 0}, kX, {0, 0, -1}, length, req.open ? p("droop") : 0.0f, 10);
    parts.add("axis",
              tube(axis, std::vector<float>(axis.size(), 0.2f * radius), resolution(s, 0.5f, 3)));
    const unsigned rows = resolution(s, 0.25f, 2), sides = resolution(s, 0.5f, 4);
    const float step = 0.92f / float(whorls);
    for (int w = 0; w < whorls; ++w) {
        const float f = 0.06f + step * (float(w) + 0.5f);
        const PathPoint at = pathAt(axis, {0, 0, 1}, f);
        // Flowers get smaller toward the tip.
        const float size = radius * (1.0f - 0.4f * smooth(0.5f, 1.0f, f));
        for (int k = 0; k < per; ++k) {
            const float az = 2.0f * kPi * (float(k) + 0.5f * float(w % 2)) / float(per) +
                             0.1f * rng.uniform(-1.0f, 1.0f);
            const vec3 out = std::cos(az) * at.side + std::sin(az) * at.normal;
            const vec3 dir = glm::normalize(out + 0.8f * at.tangent);
            const vec3 across = glm::cross(dir, out);
            const vec3 base = at.position + out * (0.25f * size);
            const vec3 normal = glm::normalize(glm::cross(across, dir));
            parts.add("flowers", ellipsoid(base + dir * (0.45f * size), dir * (0.55f * size),
                                           across * (0.45f * size) * (3.0f / float(per)) * 1.6f,
                                           normal * (0.2f * size), rows, sides));
        }
    }
    return parts.finish();
}

}  // namespace

std::vector<Family> flowerFamilies() {
    return {{petalFlowerInfo(), buildPetalFlower},
            {papilionaceousInfo(), buildPapilionaceous},
            {funnelInfo(), buildFunnel},
            {bractInfo(), buildBract},
            {catkinInfo(), buildCatkin}};
}

}  // namespace plantarch::organs
