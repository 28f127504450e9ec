// `<helios>` angles as the reference system draws them (helios_pose.h). The conventions
// were found by reading files into the reference system and comparing what it drew with
// plantarch's drawing, one angle at a time; docs/plant-xml.md lists them.

#include "plant_io/helios_pose.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "geometry/organ_sink.h"

namespace plantarch::plant_io {

namespace {

constexpr vec3 kZ{0.0f, 0.0f, 1.0f};
// Directions within 0.05 degrees count as one (cosine).
constexpr float kSameDirection = 0.99999962f;

// A turn of `v` by `degrees` about `axis` (any length; none when it is zero), right-handed.
vec3 turn(vec3 v, vec3 axis, float degrees) {
    const float l = glm::length(axis);
    if (degrees == 0.0f || !(l > 1e-6f)) return v;
    return rotateAbout(v, axis / l, degrees * kDeg);
}

float degreesOf(float radians) {
    return radians / kDeg;
}

float angleBetween(vec3 a, vec3 b) {
    return degreesOf(std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)));
}

// The angle that turns `from` to `to` about `axis` (all unit; from and to taken across it).
float signedAngle(vec3 from, vec3 to, vec3 axis) {
    return degreesOf(std::atan2(glm::dot(glm::cross(from, to), axis), glm::dot(from, to)));
}

// The reference's frame where a phytomer starts: the axis of the internode before (at its
// tip) and the first direction of that internode's first petiole (or the petiole a branch
// grows from).
struct ParentAxes {
    vec3 internode{0.0f, 0.0f, 1.0f};
    vec3 petiole{0.0f, -1.0f, 0.0f};
};

// An internode as the reference builds it.
struct RefInternode {
    vec3 first;   // direction before its segments bend
    vec3 across;  // the axis its petioles pitch about
    vec3 tip;     // direction of its last segment
    vec3 chord;   // unit, base to tip
};

// The axis across a parent internode and petiole.
vec3 acrossOf(const ParentAxes& parent) {
    return unitOr(glm::cross(parent.internode, parent.petiole), vec3(1, 0, 0));
}

// The gravitropic lean factor of a segment along `axis`.
float leanOf(vec3 axis) {
    const float lean = 0.5f - axis.z / 2.0f;
    return axis.z < 0.0f ? 2.0f * lean : lean;
}

RefInternode internodeForward(const ParentAxes& parent, bool first, const AxisRotation& base,
                              const HeliosInternode& x, float gravity, float fullLength) {
    RefInternode r;
    vec3 across = acrossOf(parent);
    vec3 axis = parent.internode;
    if (first) {
        axis = turn(axis, across, 0.5f * x.pitch);
        across = turn(across, parent.internode, base.roll);
        axis = turn(axis, parent.internode, base.roll);
        const vec3 pitchAxis = -glm::cross(parent.internode, parent.petiole);
        across = turn(across, pitchAxis, -base.pitch);
        axis = turn(axis, pitchAxis, -base.pitch);
        across = turn(across, parent.internode, base.yaw);
        axis = turn(axis, parent.internode, base.yaw);
    } else {
        axis = turn(axis, across, -1.25f * x.pitch);
    }
    r.first = axis;
    r.across = across;
    const vec3 bendAxis = axis == kZ ? vec3(0, 1, 0) : glm::cross(axis, kZ);
    const unsigned n = std::max(1u, x.segments);
    const float step = fullLength / float(n);
    vec3 chord(0.0f);
    for (unsigned j = 0; j < n; ++j) {
        if (!first && !x.curvature.empty()) {
            const float perturbation = j < x.curvature.size() ? x.curvature[j] : 0.0f;
            axis = turn(axis, bendAxis, gravity * leanOf(axis) * step + perturbation);
            if (j < x.yaw.size()) axis = turn(axis, kZ, x.yaw[j]);
        }
        chord += axis;
    }
    r.tip = axis;
    r.chord = unitOr(chord, axis);
    return r;
}

// A petiole as the reference builds it: its first direction, the axis it bends about and the
// direction of each segment.
struct RefPetiole {
    vec3 dir, about;
    std::vector<vec3> segments;
};

// Degrees the reference turns a petiole before each of its segments.
float petioleBend(const Petiole& pt, const Phytomer& ph, unsigned segments) {
    return -pt.curvature * pt.length * ph.leafFraction / float(std::max(1u, segments));
}

RefPetiole petioleForward(const RefInternode& in, bool first, float phyllotaxis, std::size_t j,
                          std::size_t count, float pitch, float bend, unsigned segments) {
    RefPetiole r;
    r.dir = turn(in.first, in.across, std::abs(pitch));
    r.about = in.across;
    if (!first) {
        r.dir = turn(r.dir, in.first, phyllotaxis);
        r.about = turn(r.about, in.first, phyllotaxis);
    }
    if (j > 0) {
        const float around = 360.0f * float(j) / float(count);
        r.dir = turn(r.dir, in.first, around);
        r.about = turn(r.about, in.first, around);
    }
    r.segments.resize(std::max(1u, segments));
    vec3 d = r.dir;
    for (vec3& s : r.segments) {
        d = turn(d, r.about, bend);
        s = d;
    }
    return r;
}

// The frame plantarch places leaves in: x along the petiole, z toward the vertical, y across.
using Frame = geometry::OrganFrame;
using geometry::uprightFrame;

// A leaf's length and width directions in the world.
struct LeafAxes {
    vec3 x, y;
};

// Where leaf `i` of `n` (file order) sits on the reference's petiole and how it is turned.
struct RefLeafPlace {
    float fromTip = 0.0f;   // leaves from the middle one (halves for an even count)
    float compound = 0.0f;  // degrees: -90 left, 90 right, 0 single or tip
    int pair = 0;           // whole leaves from the middle, for the position
};
RefLeafPlace leafPlace(int i, int n) {
    RefLeafPlace p;
    p.fromTip = float(i) - float(n - 1) / 2.0f;
    if (n > 1 && p.fromTip != 0.0f) p.compound = p.fromTip < 0.0f ? -90.0f : 90.0f;
    p.pair = i - (n - 1) / 2;
    return p;
}

// The reference's turns of a leaf, about world x, then y, then z (twice).
struct RefLeafTurns {
    float roll, pitch, yaw, azimuth;
};
RefLeafTurns leafTurns(const HeliosLeaf& a, const RefLeafPlace& p, int n, vec3 tip,
                       vec3 internodeTip) {
    const float elevation = degreesOf(std::asin(std::clamp(tip.z, -1.0f, 1.0f)));
    RefLeafTurns t;
    t.roll = 0.0f;
    if (n == 1)
        t.roll = degreesOf(std::acos(std::clamp(internodeTip.z, -1.0f, 1.0f))) - a.roll;
    else if (p.fromTip != 0.0f)
        t.roll = (elevation + a.roll) * (p.compound < 0.0f ? -1.0f : 1.0f);
    t.pitch = a.pitch + (p.fromTip == 0.0f ? elevation : 0.0f);
    t.yaw = p.fromTip != 0.0f ? a.yaw : 0.0f;
    t.azimuth = -degreesOf(std::atan2(tip.y, tip.x)) + p.compound;
    return t;
}

LeafAxes refLeafAxes(const RefLeafTurns& t) {
    auto place = [&](vec3 v) {
        v = turn(v, vec3(1, 0, 0), t.roll);
        v = turn(v, vec3(0, 1, 0), -t.pitch);
        v = turn(v, kZ, t.yaw);
        return turn(v, kZ, t.azimuth);
    };
    return {place(vec3(1, 0, 0)), place(vec3(0, 1, 0))};
}

// The file's angles of a leaf whose axes are `want`: the inverse of refLeafTurns and
// refLeafAxes, as far as the reference's turns reach.
HeliosLeaf refLeafAngles(LeafAxes want, const RefLeafPlace& p, int n, vec3 tip, vec3 internodeTip) {
    const RefLeafTurns none = leafTurns({}, p, n, tip, internodeTip);
    // Undo the final turn about z; what is left is yaw(z) pitch(-y) roll(x).
    const vec3 ex = turn(want.x, kZ, -none.azimuth), ey = turn(want.y, kZ, -none.azimuth);
    const float pitch = degreesOf(std::asin(std::clamp(ex.z, -1.0f, 1.0f)));
    const float yaw = p.fromTip != 0.0f ? degreesOf(std::atan2(ex.y, ex.x)) : 0.0f;
    const vec3 local = turn(turn(ey, kZ, -yaw), vec3(0, 1, 0), pitch);
    const float roll = degreesOf(std::atan2(local.z, local.y));
    const float elevation = degreesOf(std::asin(std::clamp(tip.z, -1.0f, 1.0f)));
    HeliosLeaf a;
    a.pitch = pitch - (p.fromTip == 0.0f ? elevation : 0.0f);
    a.yaw = yaw;
    if (n == 1)
        a.roll = degreesOf(std::acos(std::clamp(internodeTip.z, -1.0f, 1.0f))) - roll;
    else if (p.fromTip != 0.0f)
        a.roll = roll * (p.compound < 0.0f ? -1.0f : 1.0f) - elevation;
    return a;
}

// plantarch's leaf axes from its angles on frame `f` (geometry::leafTransform).
LeafAxes ownLeafAxes(const Frame& f, const LeafOrgan& l) {
    const float p = l.pitch * kDeg, r = l.roll * kDeg;
    if (l.leafletIndex == 0) {
        const float w = l.yaw * kDeg;
        const vec3 x1 = std::cos(p) * f.x + std::sin(p) * f.z;
        const vec3 z1 = -std::sin(p) * f.x + std::cos(p) * f.z;
        const vec3 x2 = std::cos(w) * x1 + std::sin(w) * f.y;
        const vec3 y2 = -std::sin(w) * x1 + std::cos(w) * f.y;
        return {x2, std::cos(r) * y2 + std::sin(r) * z1};
    }
    const float sideSign = l.leafletIndex < 0 ? 1.0f : -1.0f;
    const float rr = l.leafletIndex < 0 ? -r : r;
    const float w = l.yaw * kDeg;
    const vec3 lx = glm::normalize(std::sin(w) * f.x + std::cos(w) * sideSign * f.y);
    const vec3 ly = glm::cross(f.z, lx);
    const vec3 x1 = std::cos(p) * lx + std::sin(p) * f.z;
    const vec3 z1 = -std::sin(p) * lx + std::cos(p) * f.z;
    return {x1, std::cos(rr) * ly + std::sin(rr) * z1};
}

// ... and its angles from its axes (the inverse of ownLeafAxes).
void setOwnLeafAngles(const Frame& f, LeafAxes a, LeafOrgan& l) {
    if (l.leafletIndex == 0) {
        l.yaw = degreesOf(std::asin(std::clamp(glm::dot(a.x, f.y), -1.0f, 1.0f)));
        l.pitch = degreesOf(std::atan2(glm::dot(a.x, f.z), glm::dot(a.x, f.x)));
        const float p = l.pitch * kDeg, w = l.yaw * kDeg;
        const vec3 x1 = std::cos(p) * f.x + std::sin(p) * f.z;
        const vec3 z1 = -std::sin(p) * f.x + std::cos(p) * f.z;
        const vec3 y2 = -std::sin(w) * x1 + std::cos(w) * f.y;
        l.roll = degreesOf(std::atan2(glm::dot(a.y, z1), glm::dot(a.y, y2)));
        return;
    }
    const float sideSign = l.leafletIndex < 0 ? 1.0f : -1.0f;
    const float sp = std::clamp(glm::dot(a.x, f.z), -1.0f, 1.0f);
    const vec3 flat = unitOr(a.x - sp * f.z, f.x);
    l.yaw = degreesOf(std::atan2(glm::dot(flat, f.x), glm::dot(flat, f.y) * sideSign));
    l.pitch = degreesOf(std::asin(sp));
    const vec3 ly = glm::cross(f.z, flat);
    const vec3 z1 = -sp * flat + std::sqrt(std::max(0.0f, 1.0f - sp * sp)) * f.z;
    const float r = degreesOf(std::atan2(glm::dot(a.y, z1), glm::dot(a.y, ly)));
    l.roll = l.leafletIndex < 0 ? -r : r;
}

}  // namespace

int leafletIndexOf(int i, int n) {
    const int twice = 2 * i - (n - 1);  // twice the signed distance from the middle
    if (n % 2 == 1) return twice / 2;
    return twice > 0 ? (twice + 1) / 2 : (twice - 1) / 2;
}

namespace {

// Leaf `i` of `n` in the file's order from its leaflet index (leafletIndexOf undone).
int fileOrder(int index, int n) {
    const int twice = n % 2 == 1 ? 2 * index : (index > 0 ? 2 * index - 1 : 2 * index + 1);
    return (twice + n - 1) / 2;
}

// A leaf's place along the reference's petiole: the segment it sits on.
vec3 segmentAt(const std::vector<vec3>& segments, float position) {
    const std::size_t at = std::size_t(std::clamp(position, 0.0f, 1.0f) * float(segments.size()));
    return segments[std::min(at, segments.size() - 1)];
}

float referencePosition(const RefLeafPlace& p, int n, float offset) {
    if (n <= 1 || !(offset > 0.0f) || p.pair == 0) return 1.0f;
    return std::max(0.0f, 1.0f - (float(std::abs(p.pair)) - 0.5f) * offset);
}

// plantarch's first direction of a petiole (geometry/tessellate.cpp, petioleFrame).
vec3 ownPetioleDirection(const Internode& in, const Petiole& pt) {
    vec3 side = azimuthDirection(in.guide, in.rollReference, pt.azimuth);
    side =
        unitOr(side - glm::dot(side, in.direction) * in.direction, anyPerpendicular(in.direction));
    const float p = std::abs(pt.pitch) * kDeg;
    vec3 d = glm::normalize(std::cos(p) * in.direction + std::sin(p) * side);
    if (pt.clearance.angle != 0.0f) d = turn(d, pt.clearance.axis, pt.clearance.angle);
    return d;
}

// The walk over a plant's shoots in order, each phytomer's reference frame passed on to the
// phytomers and branches after it.
class Walk {
public:
    explicit Walk(const PlantInstance& p) : p_(p), posed_(p.shoots.size()) {}

protected:
    struct Posed {
        vec3 tip{0.0f, 0.0f, 1.0f};
        std::vector<vec3> petioleBases;  // first segment of each petiole
        float phyllotaxis = 0.0f;        // degrees, of the file
        std::size_t index = 0;           // of the phytomer along its shoot
    };

    ParentAxes parentOf(std::size_t i, std::size_t k) const {
        ParentAxes a;
        const Shoot& s = p_.shoots[i];
        const Posed* node = nullptr;
        std::size_t petiole = 0;
        if (k > 0) {
            node = &posed_[i][k - 1];
        } else if (s.parent >= 0 && std::size_t(s.parent) < i && s.parentNode >= 0 &&
                   std::size_t(s.parentNode) < posed_[std::size_t(s.parent)].size()) {
            node = &posed_[std::size_t(s.parent)][std::size_t(s.parentNode)];
            petiole = std::size_t(s.parentPetiole);
        }
        if (!node) return a;
        a.internode = node->tip;
        if (petiole < node->petioleBases.size()) {
            a.petiole = node->petioleBases[petiole];
        } else if (!node->petioleBases.empty()) {
            a.petiole = node->petioleBases[0];
        } else {
            // A node without petioles: the reference's stand-in, level and across the
            // internode (or along y on a vertical one), turned about it by the phytomer's
            // phyllotactic angle once per node below.
            vec3 ghost = glm::cross(node->tip, kZ);
            ghost = glm::length(ghost) < 0.01f ? vec3(0, 1, 0) : glm::normalize(ghost);
            a.petiole = turn(ghost, node->tip, float(node->index) * node->phyllotaxis);
        }
        return a;
    }

    float gravityOf(const std::string& label,
                    const std::map<std::string, ShootParameters>* types) const {
        if (!types) return 0.0f;
        const auto it = types->find(label);
        return it == types->end() ? 0.0f : it->second.gravitropic_curvature.mean();
    }

    const PlantInstance& p_;
    std::vector<std::vector<Posed>> posed_;
};

class Poser : Walk {
public:
    Poser(PlantInstance& p, const HeliosExtras& x,
          const std::map<std::string, ShootParameters>* types, Presence& given)
        : Walk(p), plant_(p), x_(x), types_(types), given_(given) {}

    void run() {
        for (std::size_t i = 0; i < plant_.shoots.size(); ++i) {
            Shoot& s = plant_.shoots[i];
            posed_[i].resize(s.phytomers.size());
            const float gravity = gravityOf(s.type, types_);
            const auto b = x_.baseRotations.find(&s);
            const AxisRotation base = b == x_.baseRotations.end() ? AxisRotation{} : b->second;
            for (std::size_t k = 0; k < s.phytomers.size(); ++k)
                phytomer(s.phytomers[k], i, k, base, gravity);
        }
    }

private:
    template <class K, class T>
    static T find(const std::unordered_map<const K*, T>& m, const K* key) {
        const auto it = m.find(key);
        return it == m.end() ? T{} : it->second;
    }

    void phytomer(Phytomer& ph, std::size_t i, std::size_t k, const AxisRotation& base,
                  float gravity) {
        Internode& in = ph.internode;
        const auto found = x_.internodes.find(&in);
        static const HeliosInternode none{};
        const HeliosInternode& x = found == x_.internodes.end() ? none : found->second;
        const RefInternode ref =
            internodeForward(parentOf(i, k), k == 0, base, x, gravity, in.length);
        in.direction = ref.chord;
        in.guide = ref.chord;
        Posed& out = posed_[i][k];
        out.tip = ref.tip;
        out.phyllotaxis = x.phyllotaxis;
        out.index = k;
        const std::size_t count = ph.petioles.size();
        out.petioleBases.assign(count, ref.tip);
        std::vector<vec3> sides(count);
        for (std::size_t j = 0; j < count; ++j) {
            Petiole& pt = ph.petioles[j];
            const HeliosPetiole px = find(x_.petioles, &pt);
            const float bend = petioleBend(pt, ph, px.segments);
            const RefPetiole r =
                petioleForward(ref, k == 0, x.phyllotaxis, j, count, px.pitch, bend, px.segments);
            out.petioleBases[j] = r.segments.front();
            // The reference turns before each segment, plantarch half a turn before the first
            // and whole turns after: plantarch's petiole starts half a turn on.
            const vec3 start = turn(r.dir, r.about, 0.5f * bend);
            pt.pitch = angleBetween(start, ref.chord);
            const float c = glm::dot(start, ref.chord);
            sides[j] = unitOr(start - c * ref.chord, anyPerpendicular(ref.chord));
            const int n = int(pt.leaves.size());
            for (LeafOrgan& l : pt.leaves) {
                const RefLeafPlace place = leafPlace(fileOrder(l.leafletIndex, n), n);
                l.position = referencePosition(place, n, px.leafletOffset);
                const HeliosLeaf a = find(x_.leaves, &l);
                if (a.own) {
                    l.pitch = a.own->x;
                    l.yaw = a.own->y;
                    l.roll = a.own->z;
                } else {
                    const RefLeafTurns t = leafTurns(a, place, n, r.segments.back(), ref.tip);
                    const Frame f = uprightFrame(segmentAt(r.segments, l.position), sides[j]);
                    setOwnLeafAngles(f, refLeafAxes(t), l);
                }
                for (const void* m : {(const void*)&l.pitch, (const void*)&l.yaw,
                                      (const void*)&l.roll, (const void*)&l.position})
                    given_.note(m);
            }
        }
        // Petiole azimuths about the internode, from the first petiole's side.
        in.rollReference = count ? sides[0] : anyPerpendicular(ref.chord);
        in.azimuth = 0.0f;
        for (std::size_t j = 0; j < count; ++j) {
            ph.petioles[j].azimuth = signedAngle(in.rollReference, sides[j], ref.chord);
            given_.note(&ph.petioles[j].azimuth);
            given_.note(&ph.petioles[j].pitch);
        }
        for (const void* m : {(const void*)&in.direction, (const void*)&in.guide,
                              (const void*)&in.rollReference, (const void*)&in.azimuth})
            given_.note(m);
    }

    PlantInstance& plant_;
    const HeliosExtras& x_;
    const std::map<std::string, ShootParameters>* types_;
    Presence& given_;
};

// The rotation taking (a, b, a x b) to (c, d, c x d), applied to `v`.
vec3 mapFrame(vec3 v, vec3 a, vec3 b, vec3 c, vec3 d) {
    const vec3 ab = glm::cross(a, b), cd = glm::cross(c, d);
    return glm::dot(v, a) * c + glm::dot(v, b) * d + glm::dot(v, ab) * cd;
}

class Solver : Walk {
public:
    explicit Solver(const PlantInstance& p) : Walk(p) {}

    HeliosExtras run() {
        for (std::size_t i = 0; i < p_.shoots.size(); ++i) {
            const Shoot& s = p_.shoots[i];
            posed_[i].resize(s.phytomers.size());
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) phytomer(s, i, k);
        }
        return std::move(out_);
    }

private:
    const PhytomerParameters& parametersOf(const Phytomer& ph) const {
        static const PhytomerParameters fallback{};
        const auto it = p_.shootTypes.find(ph.parametersLabel);
        return it == p_.shootTypes.end() ? fallback : it->second.phytomer_parameters;
    }

    // The base rotation that turns the parent's frame so that the shoot's first internode
    // runs along `d` and its petioles pitch about `across`: the rotation taking the unturned
    // frame to the wanted one, as roll, pitch and yaw about the parent's axes.
    static AxisRotation baseRotationFor(const ParentAxes& parent, float pitch, vec3 d,
                                        vec3 across) {
        const vec3 a0 = acrossOf(parent);
        const vec3 i = parent.internode;
        const vec3 axis0 = turn(i, a0, 0.5f * pitch);
        // The rotation Q maps (axis0, a0) to (d, across); Q = yaw(i) pitch(a0) roll(i).
        const vec3 qi = mapFrame(i, axis0, a0, d, across);
        const vec3 qa = across;
        AxisRotation r;
        r.pitch = angleBetween(i, qi);
        const vec3 w = glm::cross(a0, i);  // where pitch(a0) takes i
        const vec3 flat = qi - glm::dot(qi, i) * i;
        r.yaw = glm::length(flat) > 1e-6f ? signedAngle(w, glm::normalize(flat), i) : 0.0f;
        // roll(i) a0 = pitch(a0)^-1 yaw(i)^-1 qa.
        const vec3 left = turn(turn(qa, i, -r.yaw), a0, -r.pitch);
        r.roll = signedAngle(a0, unitOr(left - glm::dot(left, i) * i, a0), i);
        return r;
    }

    void phytomer(const Shoot& s, std::size_t i, std::size_t k) {
        const Phytomer& ph = s.phytomers[k];
        const Internode& in = ph.internode;
        const PhytomerParameters& pp = parametersOf(ph);
        const ParentAxes parent = parentOf(i, k);
        const float gravity = gravityOf(s.type, &p_.shootTypes);
        const vec3 d = unitOr(in.direction, kZ);
        const std::size_t count = ph.petioles.size();
        std::vector<vec3> petioleDirs(count);
        for (std::size_t j = 0; j < count; ++j)
            petioleDirs[j] = ownPetioleDirection(in, ph.petioles[j]);

        HeliosInternode& x = out_.internodes[&in];
        x.pitch = in.pitch;
        x.phyllotaxis = in.phyllotacticAngle;
        x.segments = std::max(1u, pp.internode.length_segments);
        AxisRotation base{};
        if (k == 0) {
            vec3 across = count ? glm::cross(d, petioleDirs[0]) : vec3(0.0f);
            if (glm::length(across) < 1e-6f) {
                // No petiole to aim: keep the unturned frame's axis across, carried to d.
                across = glm::cross(d, anyPerpendicular(d));
            }
            base = baseRotationFor(parent, x.pitch, d, glm::normalize(across));
            out_.baseRotations[&s] = base;
        } else {
            // Straight internodes: the whole turn from the first direction to d on the first
            // segment (toward vertical, then about it), the gravitropic curvature the
            // reference adds to each segment taken back.
            const vec3 across = acrossOf(parent);
            const vec3 first = turn(parent.internode, across, -1.25f * x.pitch);
            const float step = in.length / float(x.segments);
            const float up = angleBetween(first, kZ) - angleBetween(d, kZ);
            const vec3 bendAxis = first == kZ ? vec3(0, 1, 0) : glm::cross(first, kZ);
            const vec3 lifted = turn(first, bendAxis, up);
            float yaw = 0.0f;
            if (std::hypot(lifted.x, lifted.y) > 1e-6f && std::hypot(d.x, d.y) > 1e-6f)
                yaw = signedAngle(glm::normalize(vec3(lifted.x, lifted.y, 0.0f)),
                                  glm::normalize(vec3(d.x, d.y, 0.0f)), kZ);
            x.curvature.assign(x.segments, 0.0f);
            x.yaw.assign(x.segments, 0.0f);
            x.curvature[0] = up - gravity * leanOf(first) * step;
            x.yaw[0] = yaw;
            for (unsigned j = 1; j < x.segments; ++j) x.curvature[j] = -gravity * leanOf(d) * step;
        }
        const RefInternode ref = internodeForward(parent, k == 0, base, x, gravity, in.length);
        Posed& posed = posed_[i][k];
        posed.tip = ref.tip;
        posed.phyllotaxis = x.phyllotaxis;
        posed.index = k;
        posed.petioleBases.assign(count, ref.tip);

        for (std::size_t j = 0; j < count; ++j) {
            const Petiole& pt = ph.petioles[j];
            HeliosPetiole& px = out_.petioles[&pt];
            px.segments = std::max(1u, pp.petiole.length_segments);
            const float bend = petioleBend(pt, ph, px.segments);
            // The reference's first direction: plantarch's, half a segment's turn back, in
            // the plane of the internode's first direction.
            const vec3 own = petioleDirs[j];
            const vec3 about = unitOr(glm::cross(ref.first, own), ref.across);
            const vec3 want = turn(own, about, -0.5f * bend);
            px.pitch = angleBetween(ref.first, want);
            if (k > 0 && j == 0) {
                // The phyllotactic angle turns the pitched direction about the first
                // direction; unpitched it lies across `across` from it.
                const vec3 w = glm::cross(ref.across, ref.first);
                const vec3 flat = want - glm::dot(want, ref.first) * ref.first;
                if (glm::length(flat) > 1e-6f)
                    x.phyllotaxis = signedAngle(w, glm::normalize(flat), ref.first);
            }
            const RefPetiole r =
                petioleForward(ref, k == 0, x.phyllotaxis, j, count, px.pitch, bend, px.segments);
            posed.petioleBases[j] = r.segments.front();
            const vec3 start = turn(r.dir, r.about, 0.5f * bend);
            const vec3 side = unitOr(start - glm::dot(start, d) * d, anyPerpendicular(d));
            leaves(pt, px, r, ref.tip, side);
        }
    }

    // The leaves the file lists (shed ones are left out), left to right as written; each gets
    // the leaflet index the reader gives its place.
    void leaves(const Petiole& pt, HeliosPetiole& px, const RefPetiole& r, vec3 internodeTip,
                vec3 side) {
        std::vector<const LeafOrgan*> kept;
        for (const LeafOrgan& l : pt.leaves)
            if (!l.removed) kept.push_back(&l);
        std::stable_sort(kept.begin(), kept.end(), [](const LeafOrgan* a, const LeafOrgan* b) {
            return a->leafletIndex < b->leafletIndex;
        });
        const int n = int(kept.size());
        px.leafletOffset = 0.0f;
        for (int i = 0; i < n; ++i) {
            const RefLeafPlace place = leafPlace(i, n);
            if (place.pair != 0 && px.leafletOffset == 0.0f)
                px.leafletOffset =
                    (1.0f - kept[std::size_t(i)]->position) / (float(std::abs(place.pair)) - 0.5f);
        }
        for (int i = 0; i < n; ++i) {
            const LeafOrgan& l = *kept[std::size_t(i)];
            const RefLeafPlace place = leafPlace(i, n);
            const float position = referencePosition(place, n, px.leafletOffset);
            const Frame f = uprightFrame(segmentAt(r.segments, position), side);
            const LeafAxes own = ownLeafAxes(f, l);
            HeliosLeaf a = refLeafAngles(own, place, n, r.segments.back(), internodeTip);
            // What the reference draws from those angles; where it is not plantarch's leaf
            // (beyond float noise), plantarch's own angles go along, for the leaflet index the
            // reader gives this place.
            const LeafAxes drawn =
                refLeafAxes(leafTurns(a, place, n, r.segments.back(), internodeTip));
            if (glm::dot(drawn.x, own.x) < kSameDirection ||
                glm::dot(drawn.y, own.y) < kSameDirection) {
                LeafOrgan read = l;
                read.leafletIndex = leafletIndexOf(i, n);
                setOwnLeafAngles(f, own, read);
                a.own = vec3(read.pitch, read.yaw, read.roll);
            }
            out_.leaves[&l] = a;
        }
    }

    HeliosExtras out_;
};

}  // namespace

void poseAsReference(PlantInstance& plant, const HeliosExtras& extras,
                     const std::map<std::string, ShootParameters>* shootTypes, Presence& given) {
    Poser(plant, extras, shootTypes, given).run();
}

HeliosExtras referenceAngles(const PlantInstance& plant) {
    return Solver(plant).run();
}

}  // namespace plantarch::plant_io
