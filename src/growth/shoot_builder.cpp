// Making shoots and phytomers as state, with the orientation conventions of the model (pitch
// away from the parent axis, yaw about the parent axis, roll about the element's own axis;
// phyllotaxis as a roll between successive phytomers). Growth makes them as buds break and
// shoots lengthen; the facade makes them for hand-built plants.

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "core/value_text.h"
#include "growth/growth.h"
#include "model/leaf_angle_distribution.h"
#include "model/node_rules.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

void invalid(const char* name, float v, const char* range) {
    throw Error("invalid shoot argument",
                {.parameter = name, .value = text::formatFloat(v), .validRange = range});
}

// Where the tip of `shoot` will be once every internode below it is full grown.
vec3 matureTip(const PlantInstance& plant, const Shoot& shoot) {
    vec3 p(0.0f);
    std::size_t nodes = shoot.phytomers.size();  // internodes of this shoot below the tip
    for (const Shoot* s = &shoot;;) {
        for (std::size_t i = 0; i < nodes; ++i)
            p += s->phytomers[i].internode.direction * s->phytomers[i].internode.length;
        if (s->parent < 0) break;
        const Shoot& parent = plant.shoots[unsigned(s->parent)];
        nodes = std::min(std::size_t(s->parentNode) + 1, parent.phytomers.size());
        s = &parent;
    }
    return plant.base + p;
}

// Ground clearance of stems: a stem that meets its plant's ground lies on it. A new internode
// heading down whose full-grown tip would come nearer the plant's ground (the z of its base)
// than its radius is turned about its start, keeping its heading, until its tip rests on the
// ground (its axis one radius above it). Decided once, from full-grown lengths and the radius
// it is made with, so that the step size changes nothing.
void keepAboveGround(const PlantInstance& plant, const Shoot& shoot, Internode& in) {
    if (!plant.groundClearance || !(in.direction.z < 0.0f) || !(in.length > 0.0f)) return;
    const float start = matureTip(plant, shoot).z;
    const float rest = plant.base.z + in.radius;  // the axis of a stem lying on the ground
    if (start + in.direction.z * in.length >= rest) return;
    const float dz = std::clamp((rest - start) / in.length, -1.0f, 1.0f);
    vec3 heading(in.direction.x, in.direction.y, 0.0f);
    if (glm::length(heading) < 1e-6f) heading = vec3(in.guide.x, in.guide.y, 0.0f);
    if (glm::length(heading) < 1e-6f) heading = vec3(in.rollReference.x, in.rollReference.y, 0.0f);
    heading = unitOr(heading, vec3(1.0f, 0.0f, 0.0f));
    in.direction = glm::normalize(heading * std::sqrt(1.0f - dz * dz) + vec3(0.0f, 0.0f, dz));
}

}  // namespace

void checkPhytomerSize(const PhytomerSize& s) {
    if (!(s.internodeRadius > 0.0f && s.internodeRadius <= 10.0f))
        invalid("internode_radius", s.internodeRadius, "> 0 and <= 10 m");
    if (!(s.internodeLengthMax >= 0.0f && s.internodeLengthMax <= 100.0f))
        invalid("internode_length_max", s.internodeLengthMax, "0 to 100 m");
    if (!(s.internodeLengthScale > 0.0f && s.internodeLengthScale <= 1.0f))
        invalid("internode_length_scale_factor_fraction", s.internodeLengthScale, "> 0 and <= 1");
    if (!(s.leafScale > 0.0f && s.leafScale <= 1.0f))
        invalid("leaf_scale_factor_fraction", s.leafScale, "> 0 and <= 1");
}

void checkShootSpec(const ShootSpec& s) {
    if (s.phytomers < 1)
        throw Error("a shoot needs at least one phytomer",
                    {.parameter = "current_node_number", .value = "0", .validRange = ">= 1"});
    if (s.phytomers > 100000) invalid("current_node_number", float(s.phytomers), "1 to 100000");
    checkPhytomerSize(s.size);
    if (!(s.radiusTaper >= 0.0f && s.radiusTaper <= 1.0f))
        invalid("radius_taper", s.radiusTaper, "0 to 1");
    for (float a : {s.baseRotation.pitch, s.baseRotation.yaw, s.baseRotation.roll})
        if (!std::isfinite(a)) invalid("base_rotation", a, "finite angles in degrees");
}

// ---- phytomer creation -----------------------------------------------------------------

namespace {

void addLeaves(PlantInstance& plant, Petiole& pt, const LeafParameters& lp) {
    const int n = lp.leaves_per_petiole.sample(plant.rng);
    const float offset = lp.leaflet_offset.sample(plant.rng);
    const float shrink = lp.leaflet_scale.sample(plant.rng);
    // One size for the whole leaf: its leaflets are that size times their leaflet_scale steps.
    float size = lp.prototype_scale.sample(plant.rng);
    // A plant short of nitrogen makes smaller leaves (docs/physiology.md).
    if (plant.nitrogen)
        size *= 1.0f - plant.phenology.nitrogen.expansion_sensitivity *
                           (1.0f - std::clamp(plant.nitrogen->stress, 0.0f, 1.0f));
    // A plant with a leaf angle distribution draws each leaf's pose last (none: no draw, so
    // the plant's random stream is as without it).
    const LeafAngleParameters& angles = plant.phenology.leaf_angles;
    const leaf_angles::Sampler* poses = angles.inclination != LeafInclinationDistribution::None
                                            ? &leaf_angles::sampler(angles)
                                            : nullptr;
    auto leaf = [&](int index, float position, float scaleFactor, bool rotated) {
        LeafOrgan l;
        l.leafletIndex = index;
        l.position = std::max(0.0f, position);
        l.scale = size * scaleFactor;
        l.pitch = rotated ? lp.pitch.sample(plant.rng) : 0.0f;
        l.yaw = rotated ? lp.yaw.sample(plant.rng) : 0.0f;
        l.roll = rotated ? lp.roll.sample(plant.rng) : 0.0f;
        l.leafID = plant.nextLeafID++;
        // Which of the prototype's shape variants this leaf wears (0 = every leaf unique).
        const unsigned variants = lp.prototype.unique_prototypes;
        l.variant = variants > 1 ? plant.rng.nextU32() % variants : 0;
        if (poses) l.angleTarget = poses->draw(plant.rng);
        pt.leaves.push_back(l);
    };
    if (n <= 1) {
        leaf(0, 1.0f, 1.0f, true);
        return;
    }
    // Compound leaf: an odd count has one tip leaflet (unscaled, unrotated); an even count
    // has a pair at the tip. Pairs below sit leaflet_offset apart, each leaflet_scale times
    // the size of the pair above.
    int pair = 0;
    if (n % 2 == 1) leaf(0, 1.0f, 1.0f, false);
    const int pairs = n / 2;
    for (int i = 0; i < pairs; ++i) {
        const int step = (n % 2 == 1) ? i + 1 : i;  // distance from the tip in pair steps
        const float scale = std::pow(shrink, float(step));
        const float position = 1.0f - float(step) * offset;
        ++pair;
        leaf(-pair, position, scale, true);
        leaf(pair, position, scale, true);
    }
}

// Degrees off the stem: the least a petiole stands at, and the angle of a shoot's last node's.
constexpr float kMinPetiolePitch = 5.0f;

}  // namespace

void createPhytomer(const GrowthContext& growth, PlantInstance& plant, Shoot& shoot,
                    const PhytomerParameters& pp, float radius, float lengthMax,
                    float internodeFraction, float leafFraction, const Internode* start) {
    Phytomer ph;
    ph.parametersLabel = shoot.type;
    ph.internodeFraction = ph.internodeFraction0 = internodeFraction;
    ph.leafFraction = ph.leafFraction0 = leafFraction;
    ph.birth = plant.age;
    ph.radiusInitial = radius;
    Internode& in = ph.internode;
    if (shoot.phytomers.empty()) {
        in.guide = start->guide;
        in.rollReference = start->rollReference;
        in.azimuth = 0.0f;
    } else {
        const Internode& prev = shoot.phytomers.back().internode;
        in.phyllotacticAngle = pp.internode.phyllotactic_angle.sample(plant.rng);
        in.azimuth = std::fmod(prev.azimuth + in.phyllotacticAngle, 360.0f);
        vec3 g = prev.guide;
        // Gravitropism: turn toward vertical by s (1 - cos theta_z) L curvature, with
        // s = 1 when the tip points down and 0.5 otherwise (theta_z from vertical).
        const float L = lengthMax;
        const float cosZ = std::clamp(g.z, -1.0f, 1.0f);
        // Pointing down means clearly below horizontal (float noise at exactly 90 is not).
        const float s = cosZ < -1e-5f ? 1.0f : 0.5f;
        in.gravitropicTurn = s * (1.0f - cosZ) * L * shoot.gravitropicCurvature;
        // Random walk on zenith and yaw: the damping term pulls the previous perturbation back
        // and the tortuosity term adds N(0, L) noise. Each internode turns from its parent by
        // the walk's value, so a perturbation bends the shoot for as long as it lasts.
        const float sd = std::sqrt(std::max(L, 0.0f));
        in.walkZenith = prev.walkZenith - 0.5f * prev.walkZenith * L +
                        shoot.tortuosity * float(plant.rng.normal01()) * sd;
        in.walkYaw = prev.walkYaw - 0.5f * prev.walkYaw * L +
                     shoot.tortuosity * float(plant.rng.normal01()) * sd;
        const float zenithChange = -in.gravitropicTurn + in.walkZenith;
        const vec3 horizontal = vec3(g.x, g.y, 0.0f);
        // Rotating about this horizontal axis by a positive angle increases the zenith angle.
        const vec3 tiltAxis = glm::length(horizontal) > 1e-6f
                                  ? glm::normalize(glm::cross(vec3(0, 0, 1), horizontal))
                                  : glm::normalize(glm::cross(g, prev.rollReference));
        const float zenith = std::acos(cosZ);
        const float newZenith = std::clamp(zenith + zenithChange * kDeg, 0.0f, kPi);
        g = rotateAbout(g, tiltAxis, newZenith - zenith);
        g = rotateAbout(g, vec3(0, 0, 1), in.walkYaw * kDeg);
        in.guide = glm::normalize(g);
        // Carry the roll reference along with the smallest rotation (no twist).
        vec3 ref = prev.rollReference - glm::dot(prev.rollReference, in.guide) * in.guide;
        in.rollReference =
            glm::length(ref) > 1e-6f ? glm::normalize(ref) : anyPerpendicular(in.guide);
    }
    // Steering (collision avoidance, attraction points) turns internodes made by growth.
    if (growth.steering) growth.steering->steerShootAxis(plant, shoot, in, lengthMax);
    // Zig-zag: the pitch is the angle from the previous internode. Each internode leans half
    // of it off the shoot axis, toward the side of its own petiole (away from the previous
    // phytomer's, for alternate leaves), so two successive internodes of an alternate shoot
    // meet at the pitch and each petiole stands on the outer side of its node's bend.
    in.pitch = pp.internode.pitch.sample(plant.rng);
    in.direction = internodeLean(in.guide, in.rollReference, in.azimuth, in.pitch);
    in.length = lengthMax;
    in.radius = radius;
    if (growth.steering) growth.steering->keepInternodeClear(plant, shoot, in);
    keepAboveGround(plant, shoot, in);

    const unsigned petioles = pp.petiole.petioles_per_internode;
    // A shoot's last node (its max_nodes-th) holds its petioles 5 degrees off the stem, nearly
    // along it (a grass's flag leaf, a rosette's youngest leaf standing up); elsewhere a
    // petiole stands at least 5 degrees off the stem.
    const bool lastNode = int(shoot.phytomers.size()) + 1 == shoot.maxNodes;
    for (unsigned j = 0; j < petioles; ++j) {
        Petiole pt;
        pt.azimuth = in.azimuth + 360.0f * float(j) / float(petioles);
        pt.pitch = pp.petiole.pitch.sample(plant.rng);
        if (lastNode || std::abs(pt.pitch) < kMinPetiolePitch) pt.pitch = kMinPetiolePitch;
        pt.radius = pp.petiole.radius.sample(plant.rng);
        pt.length = pp.petiole.length.sample(plant.rng);
        pt.curvature = pp.petiole.curvature.sample(plant.rng);
        pt.taper = pp.petiole.taper.sample(plant.rng);
        if (growth.steering)
            growth.steering->steerPetiole(plant, shoot, in, internodeFraction, j, pt);
        addLeaves(plant, pt, pp.leaf);
        for (LeafOrgan& l : pt.leaves) l.birth = plant.age;
        pt.vegetativeBuds.resize(
            std::max(0, pp.internode.max_vegetative_buds_per_petiole.sample(plant.rng)));
        pt.floralBuds.resize(
            std::max(0, pp.internode.max_floral_buds_per_petiole.sample(plant.rng)));
        ph.petioles.push_back(std::move(pt));
    }
    shoot.phytomers.push_back(std::move(ph));
    rules::applyAtCreation(plant, shoot, pp);
    if (!pp.phytomer_creation_function.empty()) {
        const PhytomerCreationFunction& fn =
            growth.functions.creation(pp.phytomer_creation_function, shoot.type);
        PhytomerCreationContext c{plant,
                                  shoot,
                                  shoot.phytomers.back(),
                                  unsigned(shoot.phytomers.size() - 1),
                                  shoot.parentNode,
                                  shoot.maxNodes,
                                  plant.age};
        fn(c);
    }
}

// ---- shoots ----------------------------------------------------------------------------

namespace {

void realizeShoot(Shoot& s, const ShootParameters& t, Rng& rng) {
    s.maxNodes = t.max_nodes.sample(rng);
    s.maxNodesPerSeason = t.max_nodes_per_season.sample(rng);
    s.internodeLengthMax = t.internode_length_max.sample(rng);
    s.phyllochron = t.phyllochron_min.sample(rng);
    s.elongationRate = t.elongation_rate_max.sample(rng);
    s.gravitropicCurvature = t.gravitropic_curvature.sample(rng);
    s.tortuosity = t.tortuosity.sample(rng);
    s.girthAreaFactor = t.girth_area_factor.sample(rng);
    s.apicalBud.state = BudState::Active;
}

}  // namespace

unsigned createShoot(const GrowthContext& growth, PlantInstance& plant, const ShootSpec& spec,
                     StartMode mode, int parentID, unsigned parentNode, unsigned parentPetiole) {
    checkShootSpec(spec);
    const ShootParameters& type = growth.store.shootTypeFor(plant, spec.shootType);
    Shoot s;
    s.id = static_cast<unsigned>(plant.shoots.size());
    s.type = spec.shootType;
    s.parent = parentID;
    s.baseRotation = spec.baseRotation;
    s.radiusTaper = spec.radiusTaper;
    realizeShoot(s, type, plant.rng);

    Internode start;  // frame of the first phytomer
    const AxisRotation& r = spec.baseRotation;
    if (mode == StartMode::Base) {
        const AxisFrame f = turnedFrame({vec3(0, 0, 1), vec3(1, 0, 0)}, r.pitch, r.yaw, r.roll);
        start.guide = f.axis;
        start.rollReference = f.reference;
    } else {
        Shoot& parent = PlantStore::shoot(plant, unsigned(parentID));
        s.rank = parent.rank + (mode == StartMode::Append ? 0 : 1);
        if (mode == StartMode::Epicormic) {
            if (parentNode >= parent.phytomers.size())
                throw Error("parent node out of range",
                            {.parameter = "parent_node_index",
                             .value = std::to_string(parentNode),
                             .validRange = "0 to " + std::to_string(parent.phytomers.size() - 1)});
            // Upright: its roll reference faces the way the parent's axis leans.
            const vec3 axis = parent.phytomers[parentNode].internode.direction;
            const vec3 lean = vec3(axis.x, axis.y, 0.0f);
            const vec3 reference = glm::length(lean) > 1e-6f ? glm::normalize(lean) : vec3(1, 0, 0);
            const AxisFrame f = turnedFrame({vec3(0, 0, 1), reference}, r.pitch, r.yaw, r.roll);
            start.guide = f.axis;
            start.rollReference = f.reference;
            s.insertionAngle = std::acos(std::clamp(glm::dot(f.axis, axis), -1.0f, 1.0f)) / kDeg;
            s.parentNode = int(parentNode);
            s.parentPetiole = 0;
        } else if (mode == StartMode::Append) {
            const Internode& tip = parent.phytomers.back().internode;
            const AxisFrame f = turnedFrame({tip.guide, tip.rollReference}, r.pitch, r.yaw, r.roll);
            start.guide = f.axis;
            start.rollReference = f.reference;
            s.parentNode = int(parent.phytomers.size()) - 1;
            parent.apicalBud.state = BudState::Dead;
        } else {
            if (parentNode >= parent.phytomers.size())
                throw Error("parent node out of range",
                            {.parameter = "parent_node_index",
                             .value = std::to_string(parentNode),
                             .validRange = "0 to " + std::to_string(parent.phytomers.size() - 1)});
            Phytomer& node = parent.phytomers[parentNode];
            if (parentPetiole >= node.petioles.size())
                throw Error(
                    "petiole index out of range",
                    {.parameter = "petiole_index",
                     .value = std::to_string(parentPetiole),
                     .validRange = node.petioles.empty()
                                       ? "the node has no petioles"
                                       : "0 to " + std::to_string(node.petioles.size() - 1)});
            // A shoot growing from a bud takes its own type's insertion angle, which grows by
            // the decay rate per node down from the parent's tip (its most distal node as the
            // bud breaks), up to 90 degrees. A shoot placed by hand starts at the pitch given.
            float insertion = 0.0f;
            if (mode == StartMode::Bud) {
                const int fromTip = int(parent.phytomers.size()) - 1 - int(parentNode);
                const float tipAngle = type.insertion_angle_tip.sample(plant.rng);
                const float decay = type.insertion_angle_decay_rate.sample(plant.rng);
                insertion = std::min(90.0f, tipAngle + decay * float(fromTip));
            }
            s.insertionAngle = insertion + r.pitch;
            const float yaw = type.base_yaw.sample(plant.rng) + r.yaw;
            const float roll = type.base_roll.sample(plant.rng) + r.roll;
            const Internode& pin = node.internode;
            const vec3 axis = pin.direction;
            const vec3 budSide = azimuthDirection(pin.guide, pin.rollReference,
                                                  node.petioles[parentPetiole].azimuth);
            // By default the first petiole points along the parent's axis.
            const AxisFrame f = lateralFrame(axis, budSide, s.insertionAngle, yaw, roll);
            start.guide = f.axis;
            start.rollReference = f.reference;
            s.parentNode = int(parentNode);
            s.parentPetiole = int(parentPetiole);
            // The axillary bud the shoot grows from has broken.
            auto& buds = node.petioles[parentPetiole].vegetativeBuds;
            if (buds.empty()) buds.emplace_back();
            for (VegetativeBud& b : buds)
                if (b.childShoot < 0) {
                    b.state = BudState::Broken;
                    b.childShoot = int(s.id);
                    b.shootType = s.type;
                    break;
                }
        }
    }
    plant.shoots.push_back(std::move(s));
    Shoot& shoot = plant.shoots.back();
    if (parentID >= 0) plant.shoots[unsigned(parentID)].children.push_back(shoot.id);
    for (unsigned k = 0; k < spec.phytomers; ++k) {
        const float radius = spec.size.internodeRadius *
                             (1.0f - spec.radiusTaper * float(k) / float(spec.phytomers));
        createPhytomer(growth, plant, shoot, type.phytomer_parameters, std::max(radius, 1e-6f),
                       spec.size.internodeLengthMax, spec.size.internodeLengthScale,
                       spec.size.leafScale, &start);
    }
    Shoot& created = plant.shoots.back();  // the creation function cannot add shoots
    created.internodeLengthMax = spec.size.internodeLengthMax;
    scheduleNewShoot(growth, plant, created);
    return created.id;
}

}  // namespace plantarch
