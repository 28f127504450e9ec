// Leaf outline families.
//
// Each outline is built as its upper half (y >= 0), from the base point on the midrib to the
// tip (1, 0), then mirrored. Three forms cover the families:
//  - simple: two cubic Bezier quarters meeting with a horizontal tangent at the widest
//    point (p, w/2): the base quarter leaves the base at half the base angle, the tip
//    quarter reaches the tip at half the tip angle. Handle lengths ("fullness") differ per
//    family: 0.55 gives an ellipse when both angles are 180, larger values square the
//    shoulders (oblong, linear), small ones straighten the sides (deltoid).
//  - notched (cordate, reniform, palmate): the base quarter starts in the sinus at
//    (sinus_depth, 0), leaves it backwards and sweeps round a basal lobe that reaches x = 0.
//  - arrow (sagittate, hastate): a straight inner edge from the sinus to a pointed basal lobe
//    at (0, w/2), a concave shoulder to the body, and a tip quarter.
// Lobes then scale the margin (radially from the sinus for notched forms, toward the midrib
// for the others), teeth are cut inward along the normal, and Douglas-Peucker keeps the
// polygon within the tolerance of the curve.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <tuple>

#include "core/math.h"
#include "geometry/polygon_mesh.h"
#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/ParameterTable.h"

namespace plantarch {

namespace {

using glm::dvec2;
constexpr double kInf = std::numeric_limits<double>::infinity();

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

struct Cubic {
    dvec2 p0, p1, p2, p3;
    dvec2 at(double t) const {
        const double s = 1.0 - t;
        return s * s * s * p0 + 3.0 * s * s * t * p1 + 3.0 * s * t * t * p2 + t * t * t * p3;
    }
};

// Appends samples of c for t in (0, 1] (the start point is already in `out`).
void appendCubic(std::vector<dvec2>& out, const Cubic& c, int samples = 400) {
    for (int i = 1; i <= samples; ++i) out.push_back(c.at(double(i) / samples));
}
enum class Form { Simple, Notched, Arrow };

// How a family draws its margin.
struct FamilyForm {
    Form form = Form::Simple;
    double baseFullness = 0.55;  // handle at the widest point, fraction of its x span
    double baseHandle = 0.55;    // handle at the base, fraction of its largest monotone length
    double tipFullness = 0.55;
    double tipHandle = 0.55;
    double lobePoint = 0.0;  // pointedness of palmate lobe tips (0 rounded)
};

FamilyForm familyForm(LeafShape shape) {
    switch (shape) {
        case LeafShape::Elliptic:
        case LeafShape::Ovate:
        case LeafShape::Obovate:
        case LeafShape::Lanceolate:
        case LeafShape::Oblanceolate:
            return {Form::Simple, 0.7, 0.6, 0.7, 0.6};
        case LeafShape::Oblong:
            return {Form::Simple, 0.85, 0.6, 0.85, 0.6};
        case LeafShape::Linear:
            return {Form::Simple, 0.9, 0.6, 0.6, 0.5};
        case LeafShape::Needle:
            return {Form::Simple, 0.8, 0.5, 0.6, 0.5};
        case LeafShape::Spatulate:
            return {Form::Simple, 0.25, 0.6, 0.6, 0.55};
        case LeafShape::Deltoid:
            return {Form::Simple, 0.3, 0.9, 0.05, 0.05};
        case LeafShape::Cordate:
        case LeafShape::Reniform:
            return {Form::Notched, 0.55, 0.55, 0.55, 0.55, 0.3};
        case LeafShape::Palmate:
            return {Form::Notched, 0.55, 0.55, 0.55, 0.55, 0.55};
        case LeafShape::Sagittate:
        case LeafShape::Hastate:
            return {Form::Arrow, 0.55, 0.55, 0.5, 0.5};
        default:
            return {};
    }
}

LeafOutlineParams clamped(LeafOutlineParams p, Form form) {
    p.aspect_ratio = std::clamp(p.aspect_ratio, 0.01f, 4.0f);
    p.widest_point = std::clamp(p.widest_point, 0.05f, 0.95f);
    p.tip_angle = std::clamp(p.tip_angle, 1.0f, 180.0f);
    p.base_angle = form == Form::Notched ? std::clamp(p.base_angle, 184.0f, 356.0f)
                                         : std::clamp(p.base_angle, 1.0f, 180.0f);
    p.base_width = std::clamp(p.base_width, 0.0f, 0.95f);
    p.sinus_depth = std::clamp(p.sinus_depth, 0.01f, std::min(0.6f, 0.8f * p.widest_point));
    p.lobes = std::clamp(p.lobes, 0, 31);
    p.lobe_depth = std::clamp(p.lobe_depth, 0.0f, 0.9f);
    p.serrations = std::clamp(p.serrations, 0, 200);
    p.serration_depth = std::clamp(p.serration_depth, 0.0f, 0.1f);
    p.tolerance = std::clamp(p.tolerance, 1e-6f, 0.05f);
    return p;
}

// Tip quarter from the widest point w to the tip (1, 0). The control points lie on the
// tangents at both ends, a fraction of the way to where those tangents meet, so the margin is
// convex (an ellipse quadrant for a 180 degree tip with fullness 0.55). When the tip angle is
// narrower than the taper allows, the meeting point falls behind w: it is held at 40 % of the
// way to the tip and the margin turns concave near the tip (a drawn-out, acuminate tip).
Cubic tipQuarter(dvec2 w, double tipAngle, const FamilyForm& f) {
    const double beta = 0.5 * radians(tipAngle);
    const dvec2 tip(1.0, 0.0);
    const dvec2 dir(-std::cos(beta), std::sin(beta));  // from the tip back along the margin
    double meetX = dir.y > 1e-9 ? tip.x + w.y * dir.x / dir.y : w.x;
    meetX = std::max(meetX, w.x + 0.4 * (tip.x - w.x));
    const dvec2 meet(meetX, w.y);
    const dvec2 p1 = w + f.tipFullness * (meet - w);
    const dvec2 p2 = tip + f.tipHandle * glm::length(meet - tip) * dir;
    return {w, p1, p2, tip};
}

// Base quarter from `start` (leaving at `baseAngle` / 2 from +x) to the widest point w, built
// like the tip quarter; `backX` is the rearmost x the blade may reach. A non-negative
// `handle` overrides the length of the start handle (notched forms choose it).
Cubic baseQuarter(dvec2 start, dvec2 w, double baseAngle, const FamilyForm& f, double backX,
                  double handle = -1.0) {
    const double beta = 0.5 * radians(baseAngle);
    const dvec2 dir(std::cos(beta), std::sin(beta));
    double meetX = dir.y > 1e-9 ? start.x + (w.y - start.y) * dir.x / dir.y : w.x;
    meetX = std::clamp(meetX, backX, w.x - 0.4 * (w.x - start.x));
    const dvec2 meet(meetX, w.y);
    const dvec2 p2 = w + f.baseFullness * (meet - w);
    if (handle < 0) handle = f.baseHandle * glm::length(meet - start);
    return {start, start + handle * dir, p2, w};
}

// ---- the three forms ---------------------------------------------------------------------

std::vector<dvec2> simpleHalf(const LeafOutlineParams& p, const FamilyForm& f) {
    const double halfWidth = 0.5 * p.aspect_ratio;
    const dvec2 w(p.widest_point, halfWidth);
    std::vector<dvec2> half{{0.0, 0.0}};
    if (p.base_width > 0) half.push_back({0.0, p.base_width * halfWidth});
    appendCubic(half, baseQuarter(half.back(), w, p.base_angle, f, 0.0));
    appendCubic(half, tipQuarter(w, p.tip_angle, f));
    return half;
}

// Notched forms: from the sinus S = (sinus, 0) the margin leaves backwards at half the base
// angle and sweeps round to the back of the basal lobe B = (0, yB), where it runs straight up
// (so the lobe reaches exactly x = 0), then on to the widest point. The back of the lobe sits
// lower for a narrow sinus, whose margin first runs back along the midrib.
std::vector<dvec2> notchedHalf(double sinus, double widest, const LeafOutlineParams& p,
                               const FamilyForm& f) {
    const double halfWidth = 0.5 * p.aspect_ratio;
    const double beta = 0.5 * radians(double(p.base_angle));  // 92 to 178 degrees
    const dvec2 s(sinus, 0.0), w(widest, halfWidth);
    const double yB =
        halfWidth * (0.15 + 0.45 * (std::numbers::pi - beta) / (0.5 * std::numbers::pi));
    const dvec2 back(0.0, yB);
    const dvec2 dir(std::cos(beta), std::sin(beta));
    // Handles keep both coordinates monotone on the way to the back of the lobe.
    const double h2 = 0.55 * yB;
    const double h1 =
        std::min({0.55 * glm::length(back - s), 0.95 * sinus / -dir.x, (yB - h2) / dir.y});
    std::vector<dvec2> half{s};
    appendCubic(half, {s, s + h1 * dir, back - dvec2(0.0, h2), back}, 300);
    const double h3 = f.baseHandle * (halfWidth - yB);
    appendCubic(half, {back, back + dvec2(0.0, h3), w - dvec2(f.baseFullness * widest, 0.0), w},
                300);
    appendCubic(half, tipQuarter(w, p.tip_angle, f));
    return half;
}

std::vector<dvec2> arrowHalf(double sinus, double widest, const LeafOutlineParams& p,
                             const FamilyForm& f, std::vector<std::size_t>& corners) {
    const double halfWidth = 0.5 * p.aspect_ratio;
    const double body = halfWidth * std::clamp(1.0 - double(p.lobe_depth), 0.2, 0.95);
    const dvec2 s(sinus, 0.0), lobe(0.0, halfWidth), w(widest, body);
    std::vector<dvec2> half{s};
    // Inner edge, bowed slightly toward the blade.
    const dvec2 mid = 0.5 * (s + lobe) - 0.08 * dvec2(lobe.y - s.y, s.x - lobe.x);
    appendCubic(half, {s, glm::mix(s, mid, 0.7), glm::mix(lobe, mid, 0.7), lobe}, 200);
    corners.push_back(half.size() - 1);
    // Shoulder from the lobe tip (heading forward) in to the body.
    const double span = w.x - lobe.x;
    appendCubic(half, {lobe, lobe + dvec2(0.3 * span, 0.0), w - dvec2(0.5 * span, 0.0), w}, 300);
    appendCubic(half, tipQuarter(w, p.tip_angle, f));
    return half;
}

// ---- lobes -----------------------------------------------------------------------------

// Pinnate lobes: sinuses at x_j = 0.95 j / (k + 1), the margin scaled toward the midrib.
void pinnateLobes(std::vector<dvec2>& half, int lateral, double depth) {
    const double spacing = 0.95 / (lateral + 1);
    for (dvec2& q : half) {
        double scale = 1.0;
        for (int j = 1; j <= lateral; ++j) {
            const double d = std::abs(q.x - spacing * j) / (0.5 * spacing);
            scale = std::min(scale, 1.0 - depth * (1.0 - smoothstep(0.0, 0.7, d)));
        }
        q.y *= scale;
    }
}

// Palmate lobes radiating from the sinus point S. Each lobe is a small pointed leaf (an
// elliptic outline with the family's tip angle) with its base at S, its axis at angle
// theta_j (the central lobe on the midrib, `lateral` lobes per side spread evenly up to the
// petiolar sinus) and its length the unlobed margin's distance from S along that axis. All
// lobes are star-shaped around S, so their union is the polar curve r = max_j r_j(theta),
// floored by (1 - depth) times the unlobed radius: the sinuses fall where neighbouring lobes
// meet, no deeper than `depth`.
std::vector<dvec2> palmateLobes(const std::vector<dvec2>& half, int lateral, double depth,
                                double tipAngle, std::vector<std::size_t>& corners) {
    const dvec2 origin = half.front();
    // The unlobed margin as radius against angle (the angle falls from S to the tip). Close
    // to S a ray may cross the margin twice: bins keep the outer crossing.
    double thetaMax = 0.0;
    for (std::size_t i = 1; i < half.size(); ++i) {
        const dvec2 d = half[i] - origin;
        if (glm::length(d) > 1e-9) thetaMax = std::max(thetaMax, std::atan2(d.y, d.x));
    }
    constexpr int kBins = 2048;
    std::vector<double> binRadius(kBins + 1, -1.0);
    for (std::size_t i = 1; i < half.size(); ++i) {
        const dvec2 d = half[i] - origin;
        const double theta = std::clamp(std::atan2(d.y, d.x), 0.0, thetaMax);
        const int bin = int(std::round(theta / thetaMax * kBins));
        binRadius[bin] = std::max(binRadius[bin], glm::length(d));
    }
    std::vector<std::pair<double, double>> polar;
    for (int b = 0; b <= kBins; ++b)
        if (binRadius[b] >= 0) polar.push_back({thetaMax * b / kBins, binRadius[b]});
    auto unlobed = [&](double theta) {
        const auto it = std::lower_bound(polar.begin(), polar.end(), std::pair{theta, -1.0});
        if (it == polar.begin()) return it->second;
        if (it == polar.end()) return polar.back().second;
        const auto& [t0, r0] = *(it - 1);
        const auto& [t1, r1] = *it;
        return t1 > t0 ? r0 + (r1 - r0) * (theta - t0) / (t1 - t0) : r1;
    };
    const double sector = thetaMax / (lateral + 0.5);

    // One lobe outline (unit length), as half-width against x.
    LeafOutlineParams lobeParams;
    lobeParams.widest_point = 0.6f;
    lobeParams.tip_angle = float(tipAngle);
    lobeParams.base_angle = 150.0f;
    std::vector<dvec2> lobe;
    auto lobeWidth = [&](double x) {  // x in [0, 1]
        const auto it = std::lower_bound(lobe.begin(), lobe.end(), x,
                                         [](const dvec2& q, double v) { return q.x < v; });
        if (it == lobe.begin()) return it->y;
        if (it == lobe.end()) return 0.0;
        const dvec2 q0 = *(it - 1), q1 = *it;
        return q1.x > q0.x ? q0.y + (q1.y - q0.y) * (x - q0.x) / (q1.x - q0.x) : q1.y;
    };
    // Distance from the base of a unit lobe to its margin along a ray `phi` off its axis.
    auto castRay = [&](double phi) {
        const double c = std::cos(phi), s = std::sin(phi);
        auto inside = [&](double rho) { return rho * s <= lobeWidth(rho * c); };
        const double far = 1.0 / c;
        constexpr int steps = 120;
        // The lobe is star-shaped around its base, so the outermost of `steps` points inside
        // the margin is found by halving; then its margin crossing by bisection.
        int j = 0, outside = steps + 1;
        while (outside - j > 1) {
            const int mid = (j + outside) / 2;
            (inside(far * mid / steps) ? j : outside) = mid;
        }
        if (j == 0) return 0.0;
        double in = far * j / steps, out = std::min(far, far * (j + 1) / steps);
        for (int b = 0; b < 30; ++b) (inside(0.5 * (in + out)) ? in : out) = 0.5 * (in + out);
        return in;
    };
    // Lobe width such that neighbouring lobes meet, half a sector off their axes, at
    // 1 - depth of their length.
    // (At most 1.6 wide: wider lobes would not be star-shaped around their base.)
    double narrow = 0.02, wide = 1.6;
    for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (narrow + wide);
        lobeParams.aspect_ratio = float(mid);
        lobe = simpleHalf(lobeParams, FamilyForm{});
        (castRay(0.5 * sector) < 1.0 - depth ? narrow : wide) = mid;
    }
    lobeParams.aspect_ratio = float(0.5 * (narrow + wide));
    lobe = simpleHalf(lobeParams, FamilyForm{});

    // The rays tabulated once: lobes differ only in length, so they scale this table.
    constexpr int kRays = 512;
    std::vector<double> unitRadius(kRays + 1, 0.0);
    for (int k = 0; k < kRays; ++k) unitRadius[k] = castRay(0.5 * std::numbers::pi * k / kRays);
    auto lobeRadius = [&](double length, double phi) {
        const double f = std::abs(phi) / (0.5 * std::numbers::pi) * kRays;
        if (f >= kRays) return 0.0;
        const int k = int(f);
        return length * (unitRadius[k] + (unitRadius[k + 1] - unitRadius[k]) * (f - k));
    };
    std::vector<double> axisLength(lateral + 1);
    for (int j = 0; j <= lateral; ++j) axisLength[j] = unlobed(j * sector);

    // Sample the polar curve, with every lobe tip exactly.
    std::vector<double> angles;
    constexpr int samples = 1500;
    for (int k = 0; k <= samples; ++k) angles.push_back(thetaMax * k / samples);
    for (int j = 0; j <= lateral; ++j) angles.push_back(j * sector);
    std::sort(angles.begin(), angles.end(), std::greater<double>());
    std::vector<dvec2> out{origin};
    corners.clear();
    for (double theta : angles) {
        double r = (1.0 - depth) * unlobed(theta);
        for (int j = 0; j <= lateral; ++j)
            r = std::max(r, lobeRadius(axisLength[j], theta - j * sector));
        if (theta > lateral * sector) r = std::min(r, unlobed(theta));  // petiolar sinus
        if (r <= 1e-9) continue;
        for (int j = 1; j <= lateral; ++j)
            if (theta == j * sector) corners.push_back(out.size());
        out.push_back(origin + r * dvec2(std::cos(theta), std::sin(theta)));
    }
    out.back() = origin + dvec2(axisLength[0], 0.0);
    return out;
}

// Maps x so the half spans [0, 1] and scales y to the requested half-width.
void normalizeHalf(std::vector<dvec2>& half, double halfWidth) {
    double lo = kInf, hi = -kInf, top = 0.0;
    for (const dvec2& q : half) {
        lo = std::min(lo, q.x);
        hi = std::max(hi, q.x);
        top = std::max(top, q.y);
    }
    for (dvec2& q : half) q = {(q.x - lo) / (hi - lo), q.y * halfWidth / top};
}

// Indices of the widest point and of the rearmost point of a half margin.
std::vector<std::size_t> extremes(const std::vector<dvec2>& half) {
    std::size_t widest = 0, back = 0;
    for (std::size_t i = 1; i < half.size(); ++i) {
        if (half[i].y > half[widest].y) widest = i;
        if (half[i].x < half[back].x) back = i;
    }
    return {widest, back};
}

// ---- teeth -----------------------------------------------------------------------------

std::vector<double> arcLengths(const std::vector<dvec2>& line) {
    std::vector<double> s(line.size(), 0.0);
    for (std::size_t i = 1; i < line.size(); ++i)
        s[i] = s[i - 1] + glm::length(line[i] - line[i - 1]);
    return s;
}

dvec2 pointAt(const std::vector<dvec2>& line, const std::vector<double>& s, double at) {
    const auto it = std::upper_bound(s.begin(), s.end(), at);
    if (it == s.begin()) return line.front();
    if (it == s.end()) return line.back();
    const std::size_t i = std::size_t(it - s.begin());
    const double span = s[i] - s[i - 1];
    return span > 0 ? glm::mix(line[i - 1], line[i], (at - s[i - 1]) / span) : line[i];
}

// How deep a notch may be cut at arc length `a` (baseline `h` for the tangent and the
// bend): clear of the midrib and of tight convex bends (radius from three points).
double allowedNotch(const std::vector<dvec2>& half, const std::vector<double>& s, double a,
                    double h, double depth, dvec2& inward) {
    const double total = s.back();
    const dvec2 q = pointAt(half, s, a);
    const dvec2 before = pointAt(half, s, std::max(0.0, a - h));
    const dvec2 after = pointAt(half, s, std::min(total, a + h));
    const dvec2 t = after - before;
    const double len = glm::length(t);
    if (len < 1e-12) return 0.0;
    inward = dvec2(t.y / len, -t.x / len);
    double offset = depth;
    const double turn = (after.x - q.x) * (q.y - before.y) - (after.y - q.y) * (q.x - before.x);
    const double chords =
        glm::length(after - q) * glm::length(q - before) * glm::length(after - before);
    if (turn > 0 && chords > 0) offset = std::min(offset, 0.4 * chords / (2.0 * turn));
    if (inward.y < -1e-9) offset = std::min(offset, 0.6 * q.y / -inward.y);
    return std::max(offset, 0.0);
}

// Serrate teeth pointing to the tip, `count` per margin. They run over the part of the margin
// where a full-depth notch fits (not into the narrow apex or the base), which is split at
// its corners (lobe tips) so that every corner is a tooth tip; each piece gets a share of
// the teeth by length. Within a tooth the margin drops from the previous tip to a notch at
// 40 % of its length, cut inward along the normal, and rises to its own tip.
std::vector<dvec2> cutTeeth(const std::vector<dvec2>& half, const std::vector<std::size_t>& sharp,
                            const std::vector<std::size_t>& smooth, int count, double depth) {
    constexpr double notchAt = 0.4;
    const std::vector<double> s = arcLengths(half);
    const double total = s.back();
    // The stretch where notches fit.
    dvec2 inward;
    auto fits = [&](double a) {
        return allowedNotch(half, s, a, 0.01 * total, depth, inward) >= 0.75 * depth;
    };
    double start = 0.03 * total, end = total;
    while (start < total && !fits(start)) start += 0.002 * total;
    while (end > start && !fits(end)) end -= 0.002 * total;
    if (end - start < 0.05 * total) return half;

    std::vector<double> ends, sharpAt;
    for (const auto* list : {&sharp, &smooth})
        for (std::size_t c : *list)
            if (c < s.size() && s[c] > start + 0.02 * total && s[c] < end - 0.02 * total)
                ends.push_back(s[c]);
    for (std::size_t c : sharp)
        if (c < s.size()) sharpAt.push_back(s[c]);
    std::sort(ends.begin(), ends.end());
    ends.push_back(end);
    // Teeth per piece by length, largest remainders first.
    std::vector<double> from(ends.size()), share(ends.size());
    std::vector<int> teeth(ends.size());
    int given = 0;
    for (std::size_t i = 0; i < ends.size(); ++i) {
        from[i] = i == 0 ? start : ends[i - 1];
        share[i] = count * (ends[i] - from[i]) / (end - start);
        teeth[i] = int(std::floor(share[i]));
        given += teeth[i];
    }
    while (given < count) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < ends.size(); ++i)
            if (share[i] - teeth[i] > share[best] - teeth[best]) best = i;
        ++teeth[best];
        share[best] = teeth[best];
        ++given;
    }
    // Sample positions: uniform steps plus every notch and tip exactly.
    double shortest = total;
    for (std::size_t i = 0; i < ends.size(); ++i)
        if (teeth[i] > 0) shortest = std::min(shortest, (ends[i] - from[i]) / teeth[i]);
    const double step = std::min(total / 3000.0, shortest / 24.0);
    std::vector<double> at;
    for (double a = 0.0; a < total; a += step) at.push_back(a);
    for (std::size_t i = 0; i < ends.size(); ++i) {
        const double period = teeth[i] > 0 ? (ends[i] - from[i]) / teeth[i] : 0.0;
        for (int k = 0; k < teeth[i]; ++k) {
            at.push_back(from[i] + k * period);
            at.push_back(from[i] + (k + notchAt) * period);
        }
    }
    at.push_back(end);
    at.push_back(total);
    std::sort(at.begin(), at.end());
    at.erase(std::unique(at.begin(), at.end(), [](double a, double b) { return b - a < 1e-9; }),
             at.end());

    std::vector<dvec2> out;
    out.reserve(at.size());
    for (double a : at) {
        const dvec2 q = pointAt(half, s, a);
        if (a <= start || a >= end) {
            out.push_back(q);
            continue;
        }
        const std::size_t i =
            std::size_t(std::lower_bound(ends.begin(), ends.end(), a) - ends.begin());
        if (teeth[i] == 0) {
            out.push_back(q);
            continue;
        }
        const double period = (ends[i] - from[i]) / teeth[i];
        const double u = (a - from[i]) / period;
        const double f = std::clamp(u - std::floor(u), 0.0, 1.0);
        // Straight-sided teeth with V notches; shallower beside a sharp corner (lobe tip) so the
        // corner does not turn into a thin spike.
        double profile = f < notchAt ? f / notchAt : (1.0 - f) / (1.0 - notchAt);
        for (double c : sharpAt) profile *= smoothstep(0.0, 0.4 * period, std::abs(a - c));
        const double offset = profile * allowedNotch(half, s, a, 0.25 * period, depth, inward);
        out.push_back(q + offset * inward);
    }
    out.front() = half.front();
    out.back() = half.back();
    return out;
}

// ---- assembly --------------------------------------------------------------------------

// The smooth (untoothed) upper half of the family's form with its lobes, normalized;
// `corners` receives the sharp points (lobe tips) where tooth tips go.
std::vector<dvec2> smoothHalf(const LeafOutlineParams& p, const FamilyForm& f,
                              std::vector<std::size_t>& corners) {
    // Sinuses shallower than 2 % of the radius would not show: no lobes then.
    const int lateral = p.lobes >= 3 && p.lobe_depth >= 0.02f ? (p.lobes - 1) / 2 : 0;
    std::vector<dvec2> half;
    corners.clear();
    if (f.form == Form::Simple) {
        half = simpleHalf(p, f);
        if (lateral > 0) {
            pinnateLobes(half, lateral, p.lobe_depth);
            normalizeHalf(half, 0.5 * p.aspect_ratio);
        }
        return half;
    }
    // Lobes and the arrow's bowed edges move the extremes a little: correct the sinus (and,
    // unlobed, the widest point) so the normalized outline puts them where asked.
    double sinus = p.sinus_depth, widest = p.widest_point;
    for (int iteration = 0; iteration < 6; ++iteration) {
        corners.clear();
        if (f.form == Form::Notched) {
            half = notchedHalf(sinus, widest, p, f);
            if (lateral > 0) half = palmateLobes(half, lateral, p.lobe_depth, p.tip_angle, corners);
        } else {
            half = arrowHalf(sinus, widest, p, f, corners);
        }
        normalizeHalf(half, 0.5 * p.aspect_ratio);
        const double sinusError = p.sinus_depth - half.front().x;
        const double widestError = f.form == Form::Notched && lateral == 0
                                       ? p.widest_point - half[extremes(half)[0]].x
                                       : 0.0;
        if (std::abs(sinusError) < 1e-3 && std::abs(widestError) < 1e-3) break;
        widest = std::clamp(widest + widestError, 0.06, 0.95);
        sinus = std::clamp(sinus + sinusError, 0.005, 0.8 * widest);
    }
    return half;
}

// Teeth, simplification, and interior points kept off the midrib.
std::vector<dvec2> finishHalf(std::vector<dvec2> half, const std::vector<std::size_t>& corners,
                              const LeafOutlineParams& p) {
    // The extremes (widest point, back of the basal lobes) are tooth tips, so teeth do not
    // change the blade's extent, and simplification keeps them.
    if (p.serrations > 0 && p.serration_depth > 0)
        half = cutTeeth(half, corners, extremes(half), p.serrations, p.serration_depth);
    const double tolerance = p.tolerance * std::min(1.0, double(p.aspect_ratio));
    half = polygon::simplifyPolyline(half, tolerance, extremes(half));
    for (std::size_t i = 1; i + 1 < half.size(); ++i)
        half[i].y = std::max(half[i].y, 1e-4 * double(p.aspect_ratio));
    return half;
}

std::vector<vec2> toFloat(const std::vector<dvec2>& poly) {
    std::vector<vec2> out;
    out.reserve(poly.size());
    for (const dvec2& q : poly) out.emplace_back(float(q.x), float(q.y));
    return out;
}

std::vector<dvec2> mirrorHalf(const std::vector<dvec2>& half) {
    std::vector<dvec2> full{half.front()};
    for (std::size_t i = 1; i + 1 < half.size(); ++i) full.push_back({half[i].x, -half[i].y});
    full.push_back(half.back());
    for (std::size_t i = half.size() - 2; i >= 1; --i) full.push_back(half[i]);
    return full;
}

std::string validShapeNames() {
    std::string valid;
    for (const std::string& name : params::choiceNames<LeafShape>())
        valid += (valid.empty() ? "" : ", ") + name;
    return valid;
}

}  // namespace

// ---- names and presets -------------------------------------------------------------------

const std::vector<LeafShape>& allLeafShapes() {
    static const std::vector<LeafShape> shapes = [] {
        std::vector<LeafShape> all;
        for (const auto& c : params::kChoices<LeafShape>) all.push_back(c.value);
        return all;
    }();
    return shapes;
}

std::string_view leafShapeName(LeafShape shape) {
    const char* name = params::choiceName(shape);
    if (!name)
        throw Error("not a leaf shape", {.parameter = "shape",
                                         .value = std::to_string(int(shape)),
                                         .validRange = "one of: " + validShapeNames()});
    return name;
}

LeafShape leafShapeFromName(std::string_view name) {
    if (const auto shape = params::choiceNamed<LeafShape>(name)) return *shape;
    throw Error("unknown leaf shape", {.parameter = "shape",
                                       .value = std::string(name),
                                       .validRange = "one of: " + validShapeNames()});
}

LeafOutlineParams leafShapePreset(LeafShape shape) {
    LeafOutlineParams p;
    p.shape = shape;
    auto set = [&](float aspect, float widest, float tip, float base) {
        p.aspect_ratio = aspect;
        p.widest_point = widest;
        p.tip_angle = tip;
        p.base_angle = base;
    };
    switch (shape) {
        case LeafShape::Elliptic:
            set(0.5f, 0.5f, 90, 90);
            break;
        case LeafShape::Ovate:
            set(0.6f, 0.38f, 60, 150);
            break;
        case LeafShape::Obovate:
            set(0.6f, 0.65f, 160, 60);
            break;
        case LeafShape::Lanceolate:
            set(0.25f, 0.38f, 30, 60);
            break;
        case LeafShape::Oblanceolate:
            set(0.25f, 0.65f, 60, 25);
            break;
        case LeafShape::Linear:
            set(0.08f, 0.4f, 12, 20);
            p.base_width = 0.5f;
            break;
        case LeafShape::Needle:
            set(0.03f, 0.5f, 8, 10);
            break;
        case LeafShape::Spatulate:
            set(0.45f, 0.75f, 170, 20);
            break;
        case LeafShape::Oblong:
            set(0.4f, 0.5f, 150, 150);
            break;
        case LeafShape::Orbicular:
            set(0.95f, 0.5f, 180, 180);
            break;
        case LeafShape::Deltoid:
            set(0.85f, 0.12f, 60, 120);
            p.base_width = 0.75f;
            break;
        case LeafShape::Cordate:
            set(0.85f, 0.4f, 60, 320);
            p.sinus_depth = 0.12f;
            break;
        case LeafShape::Reniform:
            set(1.25f, 0.5f, 180, 320);
            p.sinus_depth = 0.22f;
            break;
        case LeafShape::Sagittate:
            set(0.55f, 0.45f, 60, 90);
            p.sinus_depth = 0.22f;
            p.lobe_depth = 0.3f;
            break;
        case LeafShape::Hastate:
            set(0.7f, 0.4f, 50, 90);
            p.sinus_depth = 0.06f;
            p.lobe_depth = 0.45f;
            break;
        case LeafShape::Palmate:
            set(1.05f, 0.5f, 90, 330);
            p.sinus_depth = 0.3f;
            p.lobes = 5;
            p.lobe_depth = 0.5f;
            p.serrations = 24;
            p.serration_depth = 0.025f;
            break;
    }
    return p;
}

// ---- outline -----------------------------------------------------------------------------

namespace {

std::vector<vec2> computeLeafOutline(const LeafOutlineParams& params) {
    const FamilyForm form = familyForm(params.shape);
    const LeafOutlineParams asked = clamped(params, form.form);
    // Teeth or lobes too deep for a tight bend could make the margin cross itself: make
    // them shallower until the polygon is simple, then drop them, and as a last resort draw
    // the plain elliptic form with the same proportions.
    std::vector<dvec2> full;
    auto accept = [&](const std::vector<dvec2>& half) {
        full = mirrorHalf(half);
        return polygon::isSimple(full) && polygon::signedArea(full) > 0;
    };
    std::vector<std::size_t> corners;
    for (float lobeScale : {1.0f, 0.5f, 0.25f, 0.0f}) {
        LeafOutlineParams p = asked;
        p.lobe_depth *= lobeScale;
        if (lobeScale == 0.0f) p.lobes = 0;
        if (asked.lobes < 3 && lobeScale < 1.0f) break;  // unlobed: nothing to reduce
        const std::vector<dvec2> smooth = smoothHalf(p, form, corners);
        for (float toothScale : {1.0f, 0.5f, 0.25f, 0.125f, 0.0f}) {
            if (toothScale < 1.0f && (asked.serrations == 0 || asked.serration_depth == 0)) break;
            LeafOutlineParams t = p;
            t.serration_depth *= toothScale;
            if (toothScale == 0.0f) t.serrations = 0;
            if (accept(finishHalf(smooth, corners, t))) return toFloat(full);
        }
    }
    LeafOutlineParams plain = asked;
    plain.base_angle = 180.0f;
    plain.lobes = plain.serrations = 0;
    if (accept(finishHalf(simpleHalf(plain, FamilyForm{}), {}, plain))) return toFloat(full);
    throw Error("leaf outline is not a simple polygon",
                {.parameter = "shape", .value = std::string(leafShapeName(asked.shape))});
}

// Outlines are a pure function of their parameters and palmate ones cost milliseconds, while
// a plant asks for the same outline once per leaf variant and a canopy once per worker: a
// small process-wide memo, shared by all threads, keeps one computation per parameter set.
using OutlineKey =
    std::tuple<int, float, float, float, float, float, float, int, float, int, float, float>;

static_assert(sizeof(LeafOutlineParams) == 12 * 4, "a new outline parameter must join OutlineKey");

OutlineKey outlineKey(const LeafOutlineParams& p) {
    return {int(p.shape), p.aspect_ratio, p.widest_point,    p.tip_angle,
            p.base_angle, p.base_width,   p.sinus_depth,     p.lobes,
            p.lobe_depth, p.serrations,   p.serration_depth, p.tolerance};
}

}  // namespace

std::vector<vec2> leafOutline(const LeafOutlineParams& params) {
    static std::mutex mutex;
    static std::map<OutlineKey, std::vector<vec2>> memo;
    constexpr std::size_t kMaxEntries = 512;
    const OutlineKey key = outlineKey(params);
    {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = memo.find(key);
        if (it != memo.end()) return it->second;
    }
    std::vector<vec2> outline = computeLeafOutline(params);
    std::lock_guard<std::mutex> lock(mutex);
    if (memo.size() >= kMaxEntries) memo.clear();
    memo.emplace(key, outline);
    return outline;
}

}  // namespace plantarch
