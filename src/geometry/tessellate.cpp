// Tessellation: a plant's state becomes Context objects (one or more per organ), each
// labelled for segmentation. A pure function of state: running it twice changes nothing,
// and organs keep their object IDs while their shapes change.

#include "geometry/tessellate.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "core/math.h"
#include "core/mesh_simplify.h"
#include "geometry/organ_sink.h"
#include "geometry/tube.h"
#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/OrganPrototypes.h"

namespace plantarch {

// The fewest triangles a part of a thinned prototype keeps (mesh detail below 0.5): a leaf
// blade as two triangles either side of its midrib, a flower or fruit as a small solid.
constexpr std::size_t kCoarseLeafTriangles = 2, kCoarseFloralTriangles = 8;

namespace {

const vec3 kUp{0.0f, 0.0f, 1.0f};

// `segments` + 1 points of a path of more segments: its ends and the points nearest to equal
// steps between them (a coarse mesh's tube along a finer path).
template <class T>
std::vector<T> everyNth(const std::vector<T>& path, unsigned segments) {
    const std::size_t n = path.size() - 1;
    std::vector<T> out;
    out.reserve(segments + 1);
    for (unsigned k = 0; k <= segments; ++k) out.push_back(path[(n * k + segments / 2) / segments]);
    return out;
}

// Every angle goes through sinCosDeg (core/math.h), so a sine kept by a caller
// (OrganPlacer::leaves) is the one tessellation computes.

// The segment lengths of a polyline and their sum, measured once for all the organs placed
// along it.
struct PathMeasure {
    std::vector<float> lengths;
    float total = 0.0f;

    [[gnu::always_inline]] void measure(const std::vector<vec3>& pts) {
        lengths.resize(pts.empty() ? 0 : pts.size() - 1);
        total = 0.0f;
        for (std::size_t i = 1; i < pts.size(); ++i) {
            lengths[i - 1] = glm::length(pts[i] - pts[i - 1]);
            total += lengths[i - 1];
        }
    }
};

// Point and tangent at fraction `f` of the arc length of a polyline measured by `m`. (The
// small functions of leaf placement are inlined: leaves are placed by the hundred thousand.)
[[gnu::always_inline]] inline std::pair<vec3, vec3> alongPath(const std::vector<vec3>& pts,
                                                              const PathMeasure& m, float f) {
    float want = std::clamp(f, 0.0f, 1.0f) * m.total;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        const float len = m.lengths[i - 1];
        if (want <= len || i + 1 == pts.size()) {
            const vec3 d = pts[i] - pts[i - 1];
            const vec3 t = len > 0.0f ? d / len : vec3(0, 0, 1);
            return {pts[i - 1] + t * std::min(want, len), t};
        }
        want -= len;
    }
    return {pts.front(), kUp};
}

// An organ frame: x along the organ, z its "up" (lamina normal for leaves).
using geometry::OrganFrame;
using geometry::uprightFrame;

// Pitch lifts x toward z, yaw turns x toward y about z, roll turns about x.
[[gnu::always_inline]] inline OrganFrame rotated(const OrganFrame& f, const TurnTrig& t) {
    const SinCos p = t.pitch, w = t.yaw, r = t.roll;
    const vec3 x1 = p.c * f.x + p.s * f.z;
    const vec3 z1 = -p.s * f.x + p.c * f.z;
    const vec3 x2 = w.c * x1 + w.s * f.y;
    const vec3 y2 = -w.s * x1 + w.c * f.y;
    const vec3 y3 = r.c * y2 + r.s * z1;
    const vec3 z3 = -r.s * y2 + r.c * z1;
    return {x2, y3, z3};
}

OrganFrame rotated(OrganFrame f, float pitch, float yaw, float roll) {
    return rotated(f, TurnTrig{sinCosDeg(pitch), sinCosDeg(yaw), sinCosDeg(roll)});
}

[[gnu::always_inline]] inline mat4 placement(const OrganFrame& f, vec3 origin, float scale) {
    mat4 m(1.0f);
    m[0] = glm::vec4(f.x * scale, 0.0f);
    m[1] = glm::vec4(f.y * scale, 0.0f);
    m[2] = glm::vec4(f.z * scale, 0.0f);
    m[3] = glm::vec4(origin, 1.0f);
    return m;
}

// The sines a leaf's orientation takes of its angles.
LeafTrig trigOf(const LeafOrgan& leaf) {
    LeafTrig t;
    t.pitch = leaf.pitch;
    t.yaw = leaf.yaw;
    t.roll = leaf.roll;
    t.leaflet = leaf.leafletIndex;
    t.set = true;
    t.target = leaf.angleTarget;
    if (leaf.angleTarget) t.normal = geometry::targetNormal(*leaf.angleTarget);
    if (leaf.leafletIndex != 0) {
        // Lateral leaflets are swung by yaw before they turn. Roll turns a leaflet about its
        // midrib so that a positive angle lifts its edge toward the petiole tip: the right-hand
        // turn about a right leaflet's midrib, mirrored on the left, so pairs stay symmetric.
        const float rollSign = leaf.leafletIndex < 0 ? -1.0f : 1.0f;
        t.swing = sinCosDeg(leaf.yaw);
        t.turn = {sinCosDeg(leaf.pitch), sinCosDeg(0.0f), sinCosDeg(leaf.roll * rollSign)};
    } else {
        t.turn = {sinCosDeg(leaf.pitch), sinCosDeg(leaf.yaw), sinCosDeg(leaf.roll)};
    }
    return t;
}

// glm's vec3 arithmetic on (x, y, z, 0) in a glm::vec4, whose four lanes the compiler keeps in
// one vector register: each lane the same operations in the same order as glm's vec3, so the
// results are the same to the bit (leaves are placed by the hundred thousand: a canopy's
// collision proxies place them again at every refresh).
namespace lanes {

using V = glm::vec4;
inline V load(vec3 v) {
    return V(v, 0.0f);
}
// glm::dot: (a.x b.x + a.y b.y) + a.z b.z.
inline float dot(V a, V b) {
    const V p = a * b;
    return (p.x + p.y) + p.z;
}
inline float length(V v) {
    return std::sqrt(dot(v, v));
}
// glm::normalize: v * (1 / sqrt(dot(v, v))).
inline V normalize(V v) {
    return v * (1.0f / std::sqrt(dot(v, v)));
}
// glm::cross: (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
inline V cross(V a, V b) {
    return V(a.y, a.z, a.x, 0.0f) * V(b.z, b.x, b.y, 0.0f) -
           V(b.y, b.z, b.x, 0.0f) * V(a.z, a.x, a.y, 0.0f);
}
// s a + t b.
inline V mix(float s, V a, float t, V b) {
    return s * a + t * b;
}

}  // namespace lanes

}  // namespace

vec3 geometry::targetNormal(const LeafAngleTarget& t) {
    const SinCos i = sinCosDeg(t.inclination), a = sinCosDeg(t.azimuth);
    return glm::normalize(vec3(i.s * a.s, i.s * a.c, i.c));
}

vec3 geometry::meanNormal(const OrganPrototype& prototype) {
    glm::dvec3 sum(0.0);
    double area = 0.0;
    for (const PrototypePart& part : prototype) {
        const Mesh& m = part.mesh;
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::dvec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                             c = m.positions[m.indices[i + 2]];
            const glm::dvec3 n = glm::cross(b - a, c - a);
            sum += n;
            area += glm::length(n);
        }
    }
    if (sum.z < 0.0) sum = -sum;  // the upper side is +z, whatever the triangles' winding
    if (!(glm::length(sum) > 1e-3 * area)) return kUp;
    return vec3(glm::normalize(sum));
}

namespace {

// A leaf with a target pose (geometry::leafTransform): the frame whose z is the target normal
// and whose x is the leaf's own x (`x`, else `y`) made square to it, applied after the turn
// that takes the prototype's mean normal to its +z.
mat4 targetTransform(vec3 origin, vec3 x, vec3 y, const LeafTrig& t, float scale, vec3 offset) {
    const vec3 n = t.normal;
    vec3 fx = x - glm::dot(x, n) * n;
    if (glm::length(fx) < 1e-4f) fx = y - glm::dot(y, n) * n;
    fx = unitOr(fx, anyPerpendicular(n));
    const vec3 fy = glm::cross(n, fx);
    // The prototype turned so that its mean normal is +z (the shortest turn).
    const vec3 p = t.prototypeNormal;
    vec3 axis = glm::cross(p, kUp);
    const float turn = std::atan2(glm::length(axis), glm::dot(p, kUp));
    axis = unitOr(axis, vec3(1.0f, 0.0f, 0.0f));
    mat4 m(1.0f);
    for (int i = 0; i < 3; ++i) {
        vec3 e(0.0f);
        e[i] = 1.0f;
        const vec3 q = turn > 1e-7f ? rotateAbout(e, axis, turn) : e;
        m[i] = glm::vec4((q.x * fx + q.y * fy + q.z * n) * scale, 0.0f);
    }
    const vec3 shift = vec3(m * glm::vec4(offset, 0.0f));
    m[3] = glm::vec4(origin + shift, 1.0f);
    return m;
}

}  // namespace

mat4 geometry::leafTransform(vec3 origin, vec3 tangent, vec3 side, const LeafTrig& t, float scale,
                             vec3 offset) {
    // uprightFrame, the lateral leaflet's swing, rotated and placement, lane by lane.
    using namespace lanes;
    const V x = normalize(load(tangent)), up = load(kUp);
    V z = up - dot(up, x) * x;
    if (length(z) < 1e-4f) {
        const V fallback = load(side);
        z = fallback - dot(fallback, x) * x;
    }
    if (length(z) < 1e-6f) z = load(anyPerpendicular(vec3(x)));
    V fz = normalize(z), fx = x, fy = cross(fz, x);
    if (t.leaflet != 0) {
        // Lateral leaflet: perpendicular to the rachis on its side (left +y, right -y),
        // swung toward the tip by yaw; roll mirrored so pairs are symmetric.
        const float sideSign = t.leaflet < 0 ? 1.0f : -1.0f;
        fx = normalize(mix(t.swing.s, x, t.swing.c * sideSign, fy));
        fy = cross(fz, fx);
    }
    const SinCos p = t.turn.pitch, w = t.turn.yaw, r = t.turn.roll;
    const V x1 = mix(p.c, fx, p.s, fz), z1 = mix(-p.s, fx, p.c, fz);
    const V x2 = mix(w.c, x1, w.s, fy), y2 = mix(-w.s, x1, w.c, fy);
    const V y3 = mix(r.c, y2, r.s, z1), z3 = mix(-r.s, y2, r.c, z1);
    if (t.target) return targetTransform(origin, vec3(x2), vec3(y3), t, scale, offset);
    offset *= scale;
    const V base = ((load(origin) + x2 * offset.x) + y3 * offset.y) + z3 * offset.z;
    mat4 m;
    m[0] = V(vec3(x2 * scale), 0.0f);
    m[1] = V(vec3(y3 * scale), 0.0f);
    m[2] = V(vec3(z3 * scale), 0.0f);
    m[3] = V(vec3(base), 1.0f);
    return m;
}

namespace {

// Which prototype a leaf uses: its parameters' prototype, the leaflet whose outline it takes,
// its variant.
struct PrototypeSlot {
    const LeafPrototype* proto;
    int leaflet;
    unsigned variant;
    bool operator==(const PrototypeSlot&) const = default;
};

PrototypeSlot prototypeSlot(const LeafParameters& lp, const LeafOrgan& leaf) {
    const LeafPrototype& proto = lp.prototype;
    const unsigned variants = proto.unique_prototypes;
    // Leaflets use the texture (outline) of their own index when one is given, else the tip's
    // for the tip leaflet and the side's first for lateral ones.
    const int leaflet = proto.leaf_texture_file.count(leaf.leafletIndex) ? leaf.leafletIndex
                        : leaf.leafletIndex == 0                         ? 0
                                                 : (leaf.leafletIndex < 0 ? -1 : 1);
    const unsigned variant = variants == 0 ? unsigned(leaf.leafID) : leaf.variant % variants;
    return {&proto, leaflet, variant};
}

// Whether two floats are the same to the bit (-0 and 0 differ: their sines do).
bool sameBits(float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}
bool sameBits(vec3 a, vec3 b) {
    return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

// Writes organs into the Context, reusing their objects.
class ContextSink final : public OrganSink {
public:
    ContextSink(Context& ctx, const PlantInstance& plant,
                const std::array<bool, kOrganKinds>& built)
        : ctx_(ctx),
          built_(built),
          plantID_(int(plant.id)),
          plantName_(plant.name),
          stage_(std::string(phenologyStageName(plant.stage))) {
        for (std::size_t k = 0; k < organNames_.size(); ++k)
            organNames_[k] = std::string(organName(OrganKind(k)));
    }

    bool wants(OrganKind) const override { return true; }

    // Kinds the PlantArchitecture builds no geometry for (setOrganGeometry) are placed as
    // usual and then dropped, so every other organ lands where it always does.
    void write(ObjectID& object, const Mesh& mesh, const Material& material,
               const OrganLabels& l) override {
        if (!built_[std::size_t(l.kind)]) return remove(object);
        place(object, mesh, nullptr, material, l);
    }

    // Places every part of a prototype; extra old objects are deleted.
    void writeParts(std::vector<ObjectID>& objects, const OrganPrototype& proto, const mat4& xf,
                    const OrganLabels& l) override {
        if (!built_[std::size_t(l.kind)]) return removeAll(objects);
        for (std::size_t i = proto.size(); i < objects.size(); ++i)
            if (ctx_.doesObjectExist(objects[i])) ctx_.deleteObject(objects[i]);
        objects.resize(proto.size(), kNoObject);
        for (std::size_t i = 0; i < proto.size(); ++i)
            place(objects[i], proto[i].mesh, &xf, proto[i].material, l);
    }

    void remove(ObjectID& id) override {
        if (id != kNoObject && ctx_.doesObjectExist(id)) ctx_.deleteObject(id);
        id = kNoObject;
    }

    void removeAll(std::vector<ObjectID>& ids) override {
        for (ObjectID& id : ids) remove(id);
        ids.clear();
    }

private:
    // The labels every organ object carries, each column found on first use (a label is
    // listed by the Context only once an object carries it).
    enum Label { kPlantID, kPlantName, kShootID, kRank, kNode, kLeafID, kOrgan, kAge, kStage };
    static constexpr const char* kLabelNames[] = {"plantID", "plant_name", "shootID",
                                                  "rank",    "node",       "leafID",
                                                  "organ",   "age",        "phenology_stage"};

    void set(ObjectID object, Label label, const DataValue& value) {
        std::optional<DataColumn>& column = columns_[label];
        if (!column) column = ctx_.dataColumn(kLabelNames[label], DataType(value.index()));
        ctx_.setObjectData(object, *column, value);
    }

    // Writes an organ's mesh (placed by *xf when given) into its object, or a new one.
    void place(ObjectID& object, const Mesh& mesh, const mat4* xf, const Material& material,
               const OrganLabels& l) {
        const MaterialID m = ctx_.addMaterial(material);
        if (object != kNoObject && ctx_.doesObjectExist(object)) {
            if (xf)
                ctx_.setObjectMesh(object, mesh, *xf);
            else
                ctx_.setObjectMesh(object, mesh);
            ctx_.setObjectMaterial(object, m);
        } else {
            object = xf ? ctx_.addObject(mesh, *xf, m) : ctx_.addObject(mesh, m);
            set(object, kPlantID, plantID_);
            set(object, kPlantName, plantName_);
            set(object, kShootID, int(l.shoot->id));
            set(object, kRank, int(l.shoot->rank));
            set(object, kNode, l.node);
            if (l.leafID >= 0) set(object, kLeafID, l.leafID);
        }
        set(object, kOrgan, organNames_[std::size_t(l.kind)]);
        set(object, kAge, l.age);
        set(object, kStage, stage_);
    }

    Context& ctx_;
    const std::array<bool, kOrganKinds>& built_;
    std::array<std::optional<DataColumn>, 9> columns_;
    // Values every object of the plant shares, made once.
    const DataValue plantID_, plantName_, stage_;
    std::array<DataValue, kOrganKinds> organNames_;
};

void deleteIf(Context& ctx, ObjectID& id) {
    if (id != kNoObject && ctx.doesObjectExist(id)) ctx.deleteObject(id);
    id = kNoObject;
}

void deleteAll(Context& ctx, std::vector<ObjectID>& ids) {
    for (ObjectID& id : ids) deleteIf(ctx, id);
    ids.clear();
}

// Turns a direction by an organ's clearance turn (none when its angle is 0).
vec3 turned(vec3 v, const OrganTurn& t) {
    return t.angle == 0.0f ? v : glm::normalize(rotateAbout(v, t.axis, t.angle * kDeg));
}

std::string variantKey(const std::string& fn, const std::string& params, int leaflet,
                       unsigned variant) {
    return fn + "|" + params + "|" + std::to_string(leaflet) + "|" + std::to_string(variant);
}

// A compact description of a leaf prototype for the cache key (which also seeds the shape
// variants: the text must stay as it is for the same plants).
std::string describePrototype(const LeafPrototype& p) {
    std::string s = p.prototype_function + ";" + std::string(leafShapeName(p.shape)) + ";" +
                    p.OBJ_model_file + (p.normalize_OBJ_model ? "|normalized;" : ";");
    for (const auto& [i, f] : p.leaf_texture_file) s += std::to_string(i) + "=" + f + ",";
    for (const RandomFloat* r :
         {&p.leaf_aspect_ratio, &p.widest_point, &p.tip_angle, &p.base_angle, &p.lobe_depth,
          &p.serration_depth, &p.midrib_fold_fraction, &p.longitudinal_curvature,
          &p.lateral_curvature, &p.petiole_roll, &p.wave_period, &p.wave_amplitude,
          &p.leaf_buckle_length, &p.leaf_buckle_angle, &p.base_width, &p.sinus_depth})
        s += r->describe() + ";";
    s += p.lobes.describe() + ";" + p.serrations.describe() + ";" + std::to_string(p.subdivisions) +
         ";" + std::to_string(p.build_petiolule) + ";";
    for (int i = 0; i < 3; ++i)
        s += std::to_string(p.color[i]) + "," + std::to_string(p.leaf_offset[i]) + ";";
    // Pleats only where set, so the keys (and the variants they seed) of leaves without
    // stay as they were.
    if (p.pleats != RandomInt(0) || p.pleat_depth != RandomFloat(0.0f))
        s += "pleats " + p.pleats.describe() + "," + p.pleat_depth.describe() + ";";
    return s;
}

std::string describeFloral(const FloralPrototypeRequest& r) {
    std::string s = std::string(r.fruit ? "fruit;" : "flower;") + (r.open ? "open;" : "closed;");
    for (const auto& [k, v] : r.parameters) s += k + "=" + std::to_string(v) + ";";
    for (int i = 0; i < 3; ++i) s += std::to_string(r.color[i]) + ",";
    return s + std::to_string(r.subdivisions);
}

std::uint64_t hashKey(const std::string& s) {
    std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
    return h;
}

}  // namespace

namespace {

// Node positions of a shoot whose base is `base`.
void nodesFrom(const Shoot& s, vec3 base, std::vector<vec3>& nodes) {
    nodes.clear();
    nodes.reserve(s.phytomers.size() + 1);
    nodes.push_back(base);
    for (const Phytomer& ph : s.phytomers)
        nodes.push_back(nodes.back() +
                        ph.internode.direction * ph.internode.length * ph.internodeFraction);
}

// Where a shoot starts on its parent's nodes.
vec3 baseOn(const Shoot& s, const std::vector<vec3>& parentNodes) {
    return parentNodes[std::min<std::size_t>(std::size_t(s.parentNode) + 1,
                                             parentNodes.size() - 1)];
}

}  // namespace

std::vector<vec3> shootNodePositions(const PlantInstance& plant, unsigned shootID) {
    // Walk down from the base stem (no recursion: a chain of appended shoots can be long).
    std::vector<unsigned> chain{shootID};
    while (plant.shoots[chain.back()].parent >= 0)
        chain.push_back(unsigned(plant.shoots[chain.back()].parent));
    std::vector<vec3> nodes;
    vec3 base = plant.base;
    for (std::size_t i = chain.size(); i-- > 0;) {
        const Shoot& s = plant.shoots[chain[i]];
        if (i + 1 < chain.size()) base = baseOn(s, nodes);
        // As the geometry stands: each internode turned by its bend under load, exactly as
        // the tessellation's BentView turns it.
        nodes.clear();
        nodes.push_back(base);
        for (const Phytomer& ph : s.phytomers) {
            vec3 d = ph.internode.direction;
            if (ph.internode.bend && ph.internode.bend->angle != 0.0f)
                d = unitOr(rotateAbout(d, ph.internode.bend->axis, ph.internode.bend->angle * kDeg),
                           d);
            nodes.push_back(nodes.back() + d * ph.internode.length * ph.internodeFraction);
        }
    }
    return nodes;
}

namespace {

struct Tessellator {
    const PlantStore& store;
    PrototypeCache& prototypes;
    PlantInstance& plant;
    OrganSink* sink = nullptr;
    std::vector<std::vector<vec3>> nodes;  // per shoot
    // Scratch kept from one organ to the next: the petiole being placed, the peduncle.
    std::vector<vec3> petiolePath;
    PathMeasure petioleMeasure, peduncleMeasure;
    std::array<std::pair<PrototypeSlot, const OrganPrototype*>, 32> recentPrototypes{};
    std::string lastLabel;
    const PhytomerParameters* lastParameters = nullptr;
    float detail = store.meshDetail;  // factor on the organs' mesh resolution

    void computeNodes() {
        // Parents come before their children (a shoot grows from one made earlier), so each
        // shoot starts from its parent's nodes computed just before: linear in the plant's size.
        // (The vectors are reused: an OrganPlacer keeps those of the last one on its thread.)
        nodes.resize(plant.shoots.size());
        for (std::vector<vec3>& n : nodes) n.clear();
        for (const Shoot& s : plant.shoots) {
            if (s.removed) continue;
            const bool parentDone =
                s.parent >= 0 && unsigned(s.parent) < s.id && !nodes[unsigned(s.parent)].empty();
            if (parentDone)
                nodesFrom(s, baseOn(s, nodes[unsigned(s.parent)]), nodes[s.id]);
            else
                nodes[s.id] = shootNodePositions(plant, s.id);
        }
    }

    // Flower and fruit prototypes, one per (function, request, variant), cached.
    const OrganPrototype& floralPrototype(const std::string& fn, unsigned variant,
                                          const FloralPrototypeRequest& request,
                                          bool normalizeOBJ) {
        const std::string key = variantKey(fn, describeFloral(request), 0, variant) +
                                (normalizeOBJ ? "|normalized" : "");
        const PrototypeCache::Scope scope =
            isOBJPrototypeName(fn) ? PrototypeCache::Scope::Own : prototypes.floralScope(fn);
        if (auto hit = prototypes.find(key, scope))
            return prototypes.coarse(*hit, key, detail, kCoarseFloralTriangles, scope);
        Rng rng(hashKey(key), 7);
        auto built = std::make_shared<OrganPrototype>(
            isOBJPrototypeName(fn) ? loadOBJPrototype(fn, normalizeOBJ)
                                   : prototypes.functions().floralPrototypes.at(fn)(request, rng));
        prototypes.insert(key, built, scope);
        return prototypes.coarse(*built, key, detail, kCoarseFloralTriangles, scope);
    }

    // The sides of a tube of `radial` sides at the mesh detail.
    unsigned sides(unsigned radial) const { return detailed(radial, detail, 3); }

    void internodes(Shoot& s) {
        if (!sink->wants(OrganKind::Internode)) return;
        const std::vector<vec3>& pts = nodes[s.id];
        const ShootParameters& type = store.shootTypeFor(plant, s.type);
        // An internode's segments are straight steps: a coarse mesh draws fewer of them.
        const unsigned segs = coarseSegments(
            std::max(1u, type.phytomer_parameters.internode.length_segments), detail);
        std::vector<vec3> line;
        std::vector<float> radii;
        for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
            const float rNext = i + 1 < s.phytomers.size() ? s.phytomers[i + 1].internode.radius
                                                           : s.phytomers[i].internode.radius;
            for (unsigned k = 0; k < segs; ++k) {
                const float f = float(k) / float(segs);
                line.push_back(glm::mix(pts[i], pts[i + 1], f));
                radii.push_back(s.phytomers[i].internode.radius);
            }
            if (i + 1 == s.phytomers.size()) {
                line.push_back(pts[i + 1]);
                radii.push_back(rNext);
            }
        }
        if (s.phytomers.empty()) return;
        const std::vector<geometry::Ring> rings =
            geometry::tubeRings(line, radii, s.phytomers.front().internode.rollReference);
        const InternodeParameters& ip = type.phytomer_parameters.internode;
        const Material mat{ip.color, ip.image_texture, ""};
        for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
            Phytomer& ph = s.phytomers[i];
            // An internode of zero length or radius is a line or a point: no geometry.
            if (!hasSize(ph.internode.length * ph.internodeFraction) ||
                !hasSize(ph.internode.radius)) {
                sink->remove(ph.internode.object);
                continue;
            }
            const Mesh m =
                geometry::tubeMesh(rings, i * segs, (i + 1) * segs, sides(ip.radial_subdivisions));
            sink->write(ph.internode.object, m, mat, {OrganKind::Internode, &s, int(i), ph.age});
        }
    }

    // Where a petiole starts, the side it leans to and its initial direction.
    struct PetioleFrame {
        vec3 side, dir, start;
    };
    PetioleFrame petioleFrame(const Shoot& s, const Phytomer& ph, int node,
                              const Petiole& pt) const {
        return petioleFrame(s, ph, node, pt, sinCosDeg(pt.azimuth), sinCosDeg(std::abs(pt.pitch)));
    }
    // The same with the sines of the petiole's azimuth and pitch given. The pitch is the angle
    // between the internode axis and the petiole's base, on the side of its azimuth (where its
    // axillary buds are) whatever its sign.
    PetioleFrame petioleFrame(const Shoot& s, const Phytomer& ph, int node, const Petiole& pt,
                              SinCos azimuth, SinCos pitch) const {
        const Internode& in = ph.internode;
        const vec3 side = petioleSide(in, azimuth);
        const vec3 dir =
            turned(glm::normalize(pitch.c * in.direction + pitch.s * side), pt.clearance);
        return {side, dir, startOn(s, node, side)};
    }
    static vec3 petioleSide(const Internode& in, SinCos azimuth) {
        const vec3 side = azimuthDirection(in.guide, in.rollReference, azimuth);
        return glm::normalize(side - glm::dot(side, in.direction) * in.direction);
    }
    vec3 startOn(const Shoot& s, int node, vec3 side) const {
        const Internode& in = s.phytomers[std::size_t(node)].internode;
        return nodes[s.id][std::size_t(node) + 1] + side * in.radius * 0.5f;
    }

    void petiole(Shoot& s, Phytomer& ph, int node, Petiole& pt, const PhytomerParameters& pp) {
        const Internode& in = ph.internode;
        const auto [side, dir, start] = petioleFrame(s, ph, node, pt);
        const float length = pt.length * ph.leafFraction;
        const unsigned segs = std::max(1u, pp.petiole.length_segments);
        std::vector<vec3>& path = petiolePath;
        geometry::curvedPath(start, dir, std::max(length, 1e-6f),
                             petioleBendRate(pt, ph.leafFraction), kUp, segs, path);
        // A petiole falls with its leaves (leaf fall, senescence, pruning).
        const bool bare =
            !pt.leaves.empty() && std::all_of(pt.leaves.begin(), pt.leaves.end(),
                                              [](const LeafOrgan& l) { return l.removed; });
        if (!sink->wants(OrganKind::Petiole)) {
        } else if (!bare && length > 1e-5f && pt.radius > 0.0f) {
            std::vector<float> radii;
            const float r0 = pt.radius * ph.leafFraction;
            // Tip radius = taper x base, kept above 2% of the base so no triangle degenerates.
            const float tip = std::max(pt.taper, 0.02f);
            for (unsigned k = 0; k <= segs; ++k)
                radii.push_back(r0 * (1.0f - (1.0f - tip) * float(k) / float(segs)));
            // A coarse mesh draws the tube through fewer of the path's points (the leaves
            // stay on the path).
            const unsigned drawn = coarseSegments(segs, detail);
            const auto rings = drawn == segs
                                   ? geometry::tubeRings(path, radii, in.direction)
                                   : geometry::tubeRings(everyNth(path, drawn),
                                                         everyNth(radii, drawn), in.direction);
            const Mesh m = geometry::tubeMesh(rings, 0, rings.size() - 1,
                                              sides(pp.petiole.radial_subdivisions));
            sink->write(pt.object, m, Material{pp.petiole.color, "", ""},
                        {OrganKind::Petiole, &s, node, ph.age});
        } else {
            sink->remove(pt.object);
        }
        if (sink->wants(OrganKind::Leaf)) {
            petioleMeasure.measure(path);
            for (LeafOrgan& leaf : pt.leaves) placeLeaf(s, ph, node, side, leaf, pp.leaf);
        }
    }

    // A leaf along petiolePath (measured).
    void placeLeaf(Shoot& s, Phytomer& ph, int node, vec3 side, LeafOrgan& leaf,
                   const LeafParameters& lp) {
        const float scale = currentLeafSize(ph, leaf);
        if (leaf.removed || !hasSize(scale)) {  // fallen, or not grown (see PlantState.h)
            sink->removeAll(leaf.objects);
            return;
        }
        const auto [origin, tangent] = alongPath(petiolePath, petioleMeasure, leaf.position);
        LeafTrig trig = trigOf(leaf);
        if (trig.target) trig.prototypeNormal = prototypeNormal(leafPrototype(lp, leaf));
        const mat4 xf =
            geometry::leafTransform(origin, tangent, side, trig, scale, lp.prototype.leaf_offset);
        sink->writeParts(leaf.objects, prototypes.leafPrototype(lp, leaf, detail), xf,
                         {OrganKind::Leaf, &s, node, leaf.age, leaf.leafID});
    }

    // The leaves of a petiole as placeLeaf places them, with the sines kept in `trig`.
    vec3 leaves(Shoot& s, int node, Petiole& pt, PetioleTrig& trig, std::span<LeafTrig> leafTrig,
                std::vector<LeafPlacement>& out, vec3& side) {
        Phytomer& ph = s.phytomers[std::size_t(node)];
        const PhytomerParameters& pp = phytomerParameters(ph);
        if (!trig.set || !sameBits(trig.azimuth, pt.azimuth) || !sameBits(trig.pitch, pt.pitch)) {
            trig.azimuth = pt.azimuth;
            trig.pitch = pt.pitch;
            trig.azimuthTrig = sinCosDeg(pt.azimuth);
            trig.pitchTrig = sinCosDeg(std::abs(pt.pitch));
            trig.set = true;
            trig.frameSet = false;
        }
        const Internode& in = ph.internode;
        if (!trig.frameSet || !sameBits(trig.axis, in.direction) ||
            !sameBits(trig.guide, in.guide) || !sameBits(trig.rollReference, in.rollReference) ||
            !sameBits(trig.clearance.axis, pt.clearance.axis) ||
            !sameBits(trig.clearance.angle, pt.clearance.angle)) {
            const PetioleFrame f = petioleFrame(s, ph, node, pt, trig.azimuthTrig, trig.pitchTrig);
            trig.axis = in.direction;
            trig.guide = in.guide;
            trig.rollReference = in.rollReference;
            trig.clearance = pt.clearance;
            trig.side = f.side;
            trig.dir = f.dir;
            trig.frameSet = true;
        }
        side = trig.side;
        const vec3 dir = trig.dir, start = startOn(s, node, side);
        const float length = pt.length * ph.leafFraction;
        const unsigned segs = std::max(1u, pp.petiole.length_segments);
        const bool bendsUp = pt.curvature >= 0.0f;
        if (!trig.curveSet || trig.bendsUp != bendsUp || !sameBits(trig.direction, dir)) {
            trig.curve = geometry::curveBasis(dir, bendsUp ? kUp : -kUp);
            trig.direction = dir;
            trig.bendsUp = bendsUp;
            trig.curveSet = true;
        }
        geometry::curvedPath(start, trig.curve, std::max(length, 1e-6f),
                             petioleBendRate(pt, ph.leafFraction), segs, petiolePath);
        petioleMeasure.measure(petiolePath);
        const LeafParameters& lp = pp.leaf;
        if (leafTrig.size() != pt.leaves.size())
            throw Error("one kept leaf angle per leaf is needed",
                        {.parameter = "leafTrig",
                         .value = std::to_string(leafTrig.size()),
                         .validRange = std::to_string(pt.leaves.size())});
        out.resize(pt.leaves.size());
        // Where the last leaf sits on the petiole (a compound leaf's leaflets mostly share a
        // place): alongPath of that position.
        float position = 0.0f;
        std::pair<vec3, vec3> place;
        bool placed = false;
        for (std::size_t i = 0; i < pt.leaves.size(); ++i) {
            const LeafOrgan& leaf = pt.leaves[i];
            const float scale = currentLeafSize(ph, leaf);
            if (leaf.removed || !hasSize(scale)) {  // as placeLeaf: no geometry
                out[i].prototype = nullptr;
                continue;
            }
            LeafTrig& t = leafTrig[i];
            if (!t.set || t.leaflet != leaf.leafletIndex || !sameBits(t.pitch, leaf.pitch) ||
                !sameBits(t.yaw, leaf.yaw) || !sameBits(t.roll, leaf.roll) ||
                t.target != leaf.angleTarget)
                t = trigOf(leaf);
            if (!placed || !sameBits(position, leaf.position)) {
                place = alongPath(petiolePath, petioleMeasure, leaf.position);
                position = leaf.position;
                placed = true;
            }
            const auto& [origin, tangent] = place;
            if (!t.prototype || trig.epoch == 0 || t.epoch != trig.epoch || t.parameters != &lp ||
                t.variant != leaf.variant || t.leafID != leaf.leafID) {
                t.prototype = &leafPrototype(lp, leaf);
                t.parameters = &lp;
                t.variant = leaf.variant;
                t.leafID = leaf.leafID;
                t.epoch = trig.epoch;
            }
            if (t.target && t.normalPrototype != t.prototype) {
                t.prototypeNormal = prototypeNormal(*t.prototype);
                t.normalPrototype = t.prototype;
            }
            out[i].transform =
                geometry::leafTransform(origin, tangent, side, t, scale, lp.prototype.leaf_offset);
            out[i].prototype = t.prototype;
        }
        return start;
    }

    // The phytomer parameters of a phytomer's shoot type (the last one at hand: a plant's
    // phytomers mostly share one).
    const PhytomerParameters& phytomerParameters(const Phytomer& ph) {
        if (!lastParameters || ph.parametersLabel != lastLabel) {
            lastParameters = &store.shootTypeFor(plant, ph.parametersLabel).phytomer_parameters;
            lastLabel = ph.parametersLabel;
        }
        return *lastParameters;
    }

    // geometry::meanNormal of a leaf prototype, the last answer at hand.
    const OrganPrototype* lastNormalPrototype = nullptr;
    vec3 lastNormal{0.0f, 0.0f, 1.0f};
    vec3 prototypeNormal(const OrganPrototype& prototype) {
        if (lastNormalPrototype != &prototype) {
            lastNormal = geometry::meanNormal(prototype);
            lastNormalPrototype = &prototype;
        }
        return lastNormal;
    }

    // prototypes.leafPrototype with the last few answers at hand (a plant's leaves share a few).
    const OrganPrototype& leafPrototype(const LeafParameters& lp, const LeafOrgan& leaf) {
        const PrototypeSlot slot = prototypeSlot(lp, leaf);
        // A multiplicative hash: the parameters are aligned, their low bits all alike.
        const std::uint64_t mixed =
            (std::uint64_t(reinterpret_cast<std::uintptr_t>(slot.proto)) ^
             std::uint64_t(std::uint32_t(slot.leaflet)) << 40 ^ std::uint64_t(slot.variant) << 20) *
            0x9e3779b97f4a7c15ULL;
        const std::size_t h = std::size_t(mixed >> 59);  // 32 slots
        auto& [key, shape] = recentPrototypes[h];
        if (!shape || !(key == slot)) {
            key = slot;
            shape = &prototypes.leafPrototype(lp, leaf);
        }
        return *shape;
    }

    // The template a floral bud is drawn from: its own when a rule function gave it one.
    const PhytomerParameters& budParameters(const FloralBud& fb, const PhytomerParameters& pp) {
        return fb.parametersLabel.empty()
                   ? pp
                   : store.shootTypeFor(plant, fb.parametersLabel).phytomer_parameters;
    }

    void floral(Shoot& s, Phytomer& ph, int node, Petiole& pt, FloralBud& fb,
                const PhytomerParameters& pp) {
        const Internode& in = ph.internode;
        // The peduncle leaves the stem on its petiole's side (in the axil); its roll turns the
        // flowers about its own axis.
        vec3 side = azimuthDirection(in.guide, in.rollReference, pt.azimuth + fb.peduncleAzimuth);
        side = glm::normalize(side - glm::dot(side, in.direction) * in.direction);
        inflorescence(s, ph, node, fb, budParameters(fb, pp), nodes[s.id][std::size_t(node) + 1],
                      in.direction, side);
    }

    // Terminal floral buds sit at the shoot tip, spread evenly around its axis.
    void terminal(Shoot& s, const PhytomerParameters& pp) {
        for (std::size_t i = 0; i < s.terminalFloralBuds.size(); ++i) terminalBud(s, pp, i);
    }

    void terminalBud(Shoot& s, const PhytomerParameters& pp, std::size_t i) {
        if (s.phytomers.empty()) return;
        Phytomer& ph = s.phytomers.back();
        const Internode& in = ph.internode;
        FloralBud& fb = s.terminalFloralBuds[i];
        const float az = in.azimuth + fb.terminalAzimuth + fb.peduncleAzimuth;
        vec3 side = azimuthDirection(in.guide, in.rollReference, az);
        side = glm::normalize(side - glm::dot(side, in.direction) * in.direction);
        inflorescence(s, ph, int(s.phytomers.size()) - 1, fb, budParameters(fb, pp),
                      nodes[s.id].back(), in.direction, side);
    }

    void inflorescence(Shoot& s, Phytomer& ph, int node, FloralBud& fb,
                       const PhytomerParameters& pp, vec3 top, vec3 axis, vec3 side) {
        const bool visible = fb.stage == FloralStage::FlowerClosed ||
                             fb.stage == FloralStage::FlowerOpen || fb.stage == FloralStage::Fruit;
        if (!visible) {
            sink->remove(fb.peduncleObject);
            for (FlowerOrgan& fl : fb.flowers) sink->removeAll(fl.objects);
            return;
        }
        const float p = fb.pedunclePitch * kDeg;
        const vec3 dir =
            turned(glm::normalize(std::cos(p) * axis + std::sin(p) * side), fb.peduncleClearance);
        const unsigned segs = std::max(1u, pp.peduncle.length_segments);
        const std::vector<vec3> path = geometry::curvedPath(
            top, dir, std::max(fb.peduncleLength, 1e-6f), fb.peduncleCurvature, kUp, segs);
        if (fb.peduncleLength > 1e-5f && fb.peduncleRadius > 0.0f &&
            sink->wants(OrganKind::Peduncle)) {
            const unsigned drawn = coarseSegments(segs, detail);
            const std::vector<vec3> line = drawn == segs ? path : everyNth(path, drawn);
            const std::vector<float> radii(line.size(), fb.peduncleRadius);
            const auto rings = geometry::tubeRings(line, radii, axis);
            sink->write(fb.peduncleObject,
                        geometry::tubeMesh(rings, 0, rings.size() - 1,
                                           sides(pp.peduncle.radial_subdivisions)),
                        Material{pp.peduncle.color, "", ""},
                        {OrganKind::Peduncle, &s, node, ph.age});
        } else if (sink->wants(OrganKind::Peduncle)) {
            sink->remove(fb.peduncleObject);
        }
        const InflorescenceParameters& inf = pp.inflorescence;
        const bool fruit = fb.stage == FloralStage::Fruit;
        const bool open = fb.stage == FloralStage::FlowerOpen;
        const OrganKind kind =
            fruit ? OrganKind::Fruit : (open ? OrganKind::FlowerOpen : OrganKind::FlowerClosed);
        if (!sink->wants(kind)) return;
        const std::string& fn =
            fruit ? inf.fruit_prototype_function : inf.flower_prototype_function;
        const std::string name = fn.empty() ? (fruit ? "builtin_fruit" : "builtin_flower") : fn;
        const float maturity = fruit ? std::clamp(fb.fruitGrowth, 0.0f, 1.0f) : 1.0f;
        FloralPrototypeRequest request;
        request.fruit = fruit;
        request.open = open;
        request.parameters =
            fruit ? inf.fruit_prototype_parameters : inf.flower_prototype_parameters;
        request.color = fruit ? inf.fruit_color : inf.flower_color;
        request.subdivisions =
            detailed(fruit ? inf.fruit_subdivisions : inf.flower_subdivisions, detail, 2);
        peduncleMeasure.measure(path);
        for (FlowerOrgan& fl : fb.flowers) {
            const float scale = currentFloralSize(fb, fl);
            if (!hasSize(scale)) {  // a fruit at the moment it sets (see PlantState.h)
                sink->removeAll(fl.objects);
                continue;
            }
            auto [origin, tangent] = alongPath(path, peduncleMeasure, fl.position);
            OrganFrame f = uprightFrame(tangent, side);
            // Flowers stand on alternating sides of the peduncle (azimuth about its axis), all
            // turned by the peduncle's roll.
            const float az = (fl.azimuth + fb.peduncleRoll) * kDeg;
            const vec3 flSide = std::cos(az) * f.z + std::sin(az) * f.y;
            const float pitch = fl.pitch * kDeg;
            vec3 axis = glm::normalize(std::cos(pitch) * f.x + std::sin(pitch) * flSide);
            if (fruit && fl.gravityFactor > 0.0f) {
                axis = glm::normalize(
                    glm::mix(axis, -kUp, std::clamp(fl.gravityFactor * maturity, 0.0f, 0.999f)));
            }
            axis = turned(axis, fl.clearance);
            OrganFrame of = uprightFrame(axis, f.z);
            of = rotated(of, 0.0f, 0.0f, fl.roll);
            const OrganPrototype& shape =
                floralPrototype(name, fl.variant, request, inf.normalize_OBJ_model);
            sink->writeParts(fl.objects, shape, placement(of, origin, scale),
                             {kind, &s, node, ph.age});
        }
    }

    void run() {
        computeNodes();
        for (Shoot& s : plant.shoots) {
            if (s.removed) continue;
            internodes(s);
            for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
                Phytomer& ph = s.phytomers[i];
                const ShootParameters& type = store.shootTypeFor(plant, ph.parametersLabel);
                const PhytomerParameters& pp = type.phytomer_parameters;
                for (Petiole& pt : ph.petioles) {
                    petiole(s, ph, int(i), pt, pp);
                    for (FloralBud& fb : pt.floralBuds) floral(s, ph, int(i), pt, fb, pp);
                }
            }
            terminal(s, store.shootTypeFor(plant, s.type).phytomer_parameters);
        }
    }
};

}  // namespace

const OrganPrototype& PrototypeCache::leafPrototype(const LeafParameters& lp, const LeafOrgan& leaf,
                                                    float detail) {
    const PrototypeSlot slot = prototypeSlot(lp, leaf);
    if (detail != 1.0f) {
        // A coarser or finer copy of the parameters, cached by its own key (the memos below
        // are for the species' own resolution).
        LeafPrototype scaled = lp.prototype;
        scaled.subdivisions = detailed(lp.prototype.subdivisions, detail, 1);
        if (scaled.subdivisions != lp.prototype.subdivisions || detail < kCoarseDetail)
            return buildLeafPrototype(scaled, slot.leaflet, slot.variant, describePrototype(scaled),
                                      detail);
    }
    const LeafPrototype& proto = lp.prototype;
    const auto memoKey = std::make_tuple(&proto, slot.leaflet, slot.variant);
    const auto fast = prototypeMemo_.find(memoKey);
    if (fast != prototypeMemo_.end()) return *fast->second;
    auto memo = prototypeKeys_.find(&proto);
    if (memo == prototypeKeys_.end())
        memo = prototypeKeys_.emplace(&proto, describePrototype(proto)).first;
    const OrganPrototype& built =
        buildLeafPrototype(proto, slot.leaflet, slot.variant, memo->second);
    prototypeMemo_.emplace(memoKey, &built);
    return built;
}

const OrganPrototype& PrototypeCache::coarse(const OrganPrototype& proto, const std::string& key,
                                             float detail, std::size_t floor, Scope scope) {
    const float share = coarseShare(detail);
    if (share >= 1.0f) return proto;
    const std::string coarseKey =
        key + "|coarse=" + std::to_string(std::bit_cast<std::uint32_t>(share));
    if (auto hit = find(coarseKey, scope)) return *hit;
    auto thinned = std::make_shared<OrganPrototype>(proto);
    for (PrototypePart& part : *thinned) {
        const std::size_t n = part.mesh.triangleCount();
        const std::size_t target =
            std::max(std::min(floor, n), std::size_t(double(n) * double(share) + 0.5));
        part.mesh = meshes::simplified(part.mesh, {.targetTriangles = target});
    }
    insert(coarseKey, thinned, scope);
    return *thinned;
}

const OrganPrototype& PrototypeCache::buildLeafPrototype(const LeafPrototype& proto, int leaflet,
                                                         unsigned variant,
                                                         const std::string& description,
                                                         float detail) {
    const std::string key = variantKey(proto.prototype_function, description, leaflet, variant) +
                            (proto.unique_prototypes == 0 ? "|unique" : "");
    // A traced leaf image or an OBJ model is read from a file that may change: their shapes
    // stay with this cache.
    const bool fromFile = !proto.OBJ_model_file.empty() || !proto.leaf_texture_file.empty();
    const Scope scope = fromFile ? Scope::Own : leafScope(proto.prototype_function);
    if (auto hit = find(key, scope)) return coarse(*hit, key, detail, kCoarseLeafTriangles, scope);
    // Variants are seeded from their key, not the plant's stream, so plants sharing a
    // prototype see the same shapes and building one never shifts a plant's random numbers.
    Rng rng(hashKey(key), 7);
    auto built = std::make_shared<OrganPrototype>(
        proto.OBJ_model_file.empty()
            ? functions_->leafPrototypes.at(proto.prototype_function)(proto, rng, leaflet)
            : loadOBJPrototype(proto.OBJ_model_file, proto.normalize_OBJ_model));
    insert(key, built, scope);
    return coarse(*built, key, detail, kCoarseLeafTriangles, scope);
}

double PrototypeCache::leafPrototypeArea(const LeafParameters& lp, const LeafOrgan& leaf) {
    const unsigned variants = lp.prototype.unique_prototypes;
    const unsigned variant = variants == 0 ? unsigned(leaf.leafID) : leaf.variant % variants;
    const auto key = std::make_tuple(&lp.prototype, leaf.leafletIndex, variant);
    auto it = prototypeAreas_.find(key);
    if (it != prototypeAreas_.end()) return it->second;
    double area = 0.0;
    for (const PrototypePart& part : leafPrototype(lp, leaf)) area += part.mesh.area();
    prototypeAreas_.emplace(key, area);
    return area;
}

namespace {

// A plant bent under load, for the length of a tessellation: each internode with a bend has
// its directions, and the clearance axes of the organs on its node, turned by it; put back
// as they were, to the bit, when it ends (docs/measured-plants.md).
class BentView {
public:
    explicit BentView(PlantInstance& plant) {
        for (Shoot& s : plant.shoots)
            for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
                Phytomer& ph = s.phytomers[i];
                if (!ph.internode.bend || ph.internode.bend->angle == 0.0f) continue;
                const InternodeBend b = *ph.internode.bend;
                Internode& in = ph.internode;
                turn(in.direction, b);
                turn(in.guide, b);
                turn(in.rollReference, b);
                for (Petiole& pt : ph.petioles) {
                    turn(pt.clearance.axis, b);
                    for (FloralBud& fb : pt.floralBuds) floral(fb, b);
                }
                if (i + 1 == s.phytomers.size())
                    for (FloralBud& fb : s.terminalFloralBuds) floral(fb, b);
            }
    }
    ~BentView() {
        for (auto& [where, was] : saved_) *where = was;
    }
    BentView(const BentView&) = delete;
    BentView& operator=(const BentView&) = delete;

private:
    void turn(vec3& v, const InternodeBend& b) {
        saved_.emplace_back(&v, v);
        v = unitOr(rotateAbout(v, b.axis, b.angle * kDeg), v);
    }
    void floral(FloralBud& fb, const InternodeBend& b) {
        turn(fb.peduncleClearance.axis, b);
        for (FlowerOrgan& fl : fb.flowers) turn(fl.clearance.axis, b);
    }
    std::vector<std::pair<vec3*, vec3>> saved_;
};

}  // namespace

void tessellatePlant(const PlantStore& store, PrototypeCache& prototypes, OrganSink& sink,
                     PlantInstance& plant) {
    prototypes.clearCallMemos();
    const BentView bent(plant);
    Tessellator t{store, prototypes, plant, &sink, {}};
    t.run();
}

void tessellatePlant(const PlantStore& store, PrototypeCache& prototypes, Context& ctx,
                     PlantInstance& plant) {
    ContextSink sink(ctx, plant, store.organGeometry);
    tessellatePlant(store, prototypes, sink, plant);
}

// ---- single organs -----------------------------------------------------------------------

struct OrganPlacer::State {
    Tessellator tessellator;
};

namespace {

// The storage of the last OrganPlacer on this thread, for the next (collision refreshes make
// one per plant and refresh).
struct PlacerStorage {
    std::vector<std::vector<vec3>> nodes;
    std::vector<vec3> path;
    PathMeasure measure;
    void swap(Tessellator& t) {
        t.nodes.swap(nodes);
        t.petiolePath.swap(path);
        std::swap(t.petioleMeasure, measure);
    }
};

PlacerStorage& placerStorage() {
    thread_local PlacerStorage storage;
    return storage;
}

}  // namespace

OrganPlacer::OrganPlacer(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant)
    : OrganPlacer(store, prototypes, plant, store.meshDetail) {}

OrganPlacer::OrganPlacer(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                         float detail)
    : state_(std::make_unique<State>(State{Tessellator{store, prototypes, plant, nullptr, {}}})) {
    state_->tessellator.detail = detail;
    prototypes.clearCallMemos();
    placerStorage().swap(state_->tessellator);
    state_->tessellator.computeNodes();
}

const std::vector<vec3>& OrganPlacer::nodes(unsigned shoot) const {
    return state_->tessellator.nodes[shoot];
}

OrganPlacer::~OrganPlacer() {
    placerStorage().swap(state_->tessellator);
}

void OrganPlacer::petiole(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole) {
    Tessellator& t = state_->tessellator;
    t.sink = &sink;
    Shoot& s = t.plant.shoots[shoot];
    Phytomer& ph = s.phytomers[node];
    const PhytomerParameters& pp =
        t.store.shootTypeFor(t.plant, ph.parametersLabel).phytomer_parameters;
    t.petiole(s, ph, int(node), ph.petioles[petiole], pp);
}

vec3 OrganPlacer::petioleStart(unsigned shoot, unsigned node, unsigned petiole) const {
    const Tessellator& t = state_->tessellator;
    const Shoot& s = t.plant.shoots[shoot];
    const Phytomer& ph = s.phytomers[node];
    return t.petioleFrame(s, ph, int(node), ph.petioles[petiole]).start;
}

vec3 OrganPlacer::leaves(unsigned shoot, unsigned node, unsigned petiole, PetioleTrig& trig,
                         std::span<LeafTrig> leafTrig, std::vector<LeafPlacement>& out,
                         vec3& side) {
    Tessellator& t = state_->tessellator;
    Shoot& s = t.plant.shoots[shoot];
    return t.leaves(s, int(node), s.phytomers[node].petioles[petiole], trig, leafTrig, out, side);
}

vec3 OrganPlacer::petioleStartOn(unsigned shoot, unsigned node, vec3 side) const {
    const Tessellator& t = state_->tessellator;
    return t.startOn(t.plant.shoots[shoot], int(node), side);
}

void OrganPlacer::floralBud(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole,
                            unsigned bud, bool terminal) {
    Tessellator& t = state_->tessellator;
    t.sink = &sink;
    Shoot& s = t.plant.shoots[shoot];
    if (terminal) {
        t.terminalBud(s, t.store.shootTypeFor(t.plant, s.type).phytomer_parameters, bud);
        return;
    }
    Phytomer& ph = s.phytomers[node];
    const PhytomerParameters& pp =
        t.store.shootTypeFor(t.plant, ph.parametersLabel).phytomer_parameters;
    Petiole& pt = ph.petioles[petiole];
    t.floral(s, ph, int(node), pt, pt.floralBuds[bud], pp);
}

void deletePhytomerObjects(Context& ctx, Phytomer& ph) {
    deleteIf(ctx, ph.internode.object);
    for (Petiole& pt : ph.petioles) {
        deleteIf(ctx, pt.object);
        for (LeafOrgan& l : pt.leaves) deleteAll(ctx, l.objects);
        for (FloralBud& fb : pt.floralBuds) {
            deleteIf(ctx, fb.peduncleObject);
            for (FlowerOrgan& fl : fb.flowers) deleteAll(ctx, fl.objects);
        }
    }
}

void deleteShootObjects(Context& ctx, Shoot& s) {
    for (Phytomer& ph : s.phytomers) deletePhytomerObjects(ctx, ph);
    for (FloralBud& fb : s.terminalFloralBuds) {
        deleteIf(ctx, fb.peduncleObject);
        for (FlowerOrgan& fl : fb.flowers) deleteAll(ctx, fl.objects);
    }
}

}  // namespace plantarch
