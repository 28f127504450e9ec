#pragma once
// The one declaration of every plant-state field that plant structure files hold: element
// name, valid range, meaning and whether a phytomer rule may change it, in file order.
// Public so that front ends (the Python module) bind the plant state from it.
//
// describeState(object, visitor) calls, for each piece of the object:
//   v.field(info, member)        a value (number, flag, vector, text, stage, generator)
//   v.group(name, fn)            a nested element; fn(subVisitor) visits its content
//   nested(v, name, member, more) a nested element holding the member struct's own table,
//                                then more(subVisitor) (see nested() below)
//   v.list(name, vector, ids)    one element per item (ids: items carry ID="index")
//   v.values(info, vector)       one element per value (a list of numbers or vectors)
//   v.optional(name, optional)   a nested element that may be absent (then: none, and no
//                                missing-value warning); its content is the type's table
//   v.parameters(name, member)   species parameters, read and written through the parameter
//                                table (plantarch/ParameterTable.h)
//   v.legacy(name)               an element plantarch accepts on reading and never writes
//   v.objects(name, member)      the organ's Context object ID (ObjectID) or IDs (a vector),
//                                written only on request (writePlantsXML's objectIDs); absent
//                                on reading: none, and nothing is missing
// The XML writer, the XML reader (with its range checks and missing-value report) are
// visitors, so a new state field is one line here: it is then written, read back, range
// checked, and reported as missing (default used) in older files.
//
// Object IDs belong to one Context: files carry them only when asked to, and reading gives
// them back only where the target Context has them free (PlantArchitecture's reading).
// Shoot::children is derived from the parents on reading.
//
// The ranges are also what every plant read must hold (plant_io::checkPlant, whatever the
// input: plant structure file, plant string or `<helios>` file) and what node rules' results
// are held to (model/node_rules.cpp): fieldInfo<S>("name") finds a field's declaration,
// inside() and rangeText(f.range()) (plantarch/NumberRange.h) apply and describe its range.

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "plantarch/NumberRange.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/PlantState.h"

namespace plantarch::state {

/// What a reader checks beyond the range.
enum class Check {
    None,
    UnitVector,    ///< a direction: length 1 (within 1e-3)
    Label,         ///< a shoot type label: letters, digits, '_' or '-'
    LabelOrEmpty,  ///< a label, or nothing
    ExclusiveMin,  ///< the range excludes its minimum: min < value <= max
    Exclusive,     ///< the range excludes both ends: min < value < max
};

/// Whether a field is a time on the plant's clock (a plant age, days), which moves with it
/// when a plant is copied to another age (model/plant_move.h).
enum class Clock {
    None,
    Age,        ///< a plant age
    Scheduled,  ///< a plant age, or negative: none (not scheduled, not yet)
};

/// What a state field is. The range bounds the value (each component of a vector).
struct FieldInfo {
    const char* name;  ///< XML element (and Python attribute)
    double min;
    double max;
    const char* doc;  ///< meaning and unit
    Check check = Check::None;
    Clock clock = Clock::None;
    /// A trait a phytomer function may set (in C++ or Python, held to the range); the others
    /// (identities, links, ages, derived directions) are bookkeeping that only growth changes.
    bool editable = false;

    /// The range, with the ends `check` excludes, for rangeText() (plantarch/NumberRange.h):
    /// "0 to 1000000", "> 0 and <= 100".
    NumberRange range() const {
        return {.min = min,
                .max = max,
                .openMin = check == Check::ExclusiveMin || check == Check::Exclusive,
                .openMax = check == Check::Exclusive};
    }
};

/// `f` marked editable: a trait phytomer functions may set.
constexpr FieldInfo editable(FieldInfo f) {
    f.editable = true;
    return f;
}

using params::SameAs;

// Generous bounds that keep geometry finite; realized values of unbounded distributions may
// fall outside a parameter's nominal range, so these are wider than the parameter table's.
inline constexpr double kBig = 1e6;    ///< lengths (m), angles (degrees), rates
inline constexpr double kTime = 1e9;   ///< plant ages, days (negative: not scheduled)
inline constexpr double kCount = 1e9;  ///< counters and indices
inline constexpr double kMaxLeafID = 1 << 30;
/// Any finite float: a petiole's curvature read from a plant string is its bend rate now (the
/// full-grown curvature over the fraction grown), which a young petiole has large.
inline constexpr double kAnyFloat = 3.4028234663852886e38;

template <class S, class V>
requires SameAs<S, VegetativeBud>
void describeState(S& b, V& v) {
    v.field(editable({"state", 0, 0, "dormant, active, broken or dead"}), b.state);
    v.field(
        editable({"break_time", -kTime, kTime, "plant age when it breaks, days (negative: waiting)",
                  Check::None, Clock::Scheduled}),
        b.breakTime);
    v.field({"child_shoot_ID", -1, kCount, "shoot grown from this bud (-1: none)"}, b.childShoot);
    v.field(editable({"shoot_type_label", 0, 0, "type it grows into (chosen when it breaks)",
                      Check::LabelOrEmpty}),
            b.shootType);
}

template <class S, class V>
requires SameAs<S, FlowerOrgan>
void describeState(S& f, V& v) {
    v.field(editable({"position", -kBig, kBig, "along the peduncle, fraction of its length"}),
            f.position);
    v.field(editable({"azimuth", -kBig, kBig, "side of the peduncle, degrees"}), f.azimuth);
    v.field(editable({"pitch", -kBig, kBig, "from the peduncle axis, degrees"}), f.pitch);
    v.field(editable({"roll", -kBig, kBig, "about its own axis, degrees"}), f.roll);
    v.field(editable({"flower_scale", 0, kBig, "flower length, m"}), f.flowerScale);
    v.field(editable({"fruit_scale", 0, kBig, "full-grown fruit length, m"}), f.fruitScale);
    v.field(editable({"gravity_factor", -kBig, kBig, "how far the fruit turns to the ground"}),
            f.gravityFactor);
    v.field({"variant", 0, kCount, "prototype shape variant"}, f.variant);
    v.field({"clearance_axis", -1, 1, "fruit adjustment: world axis", Check::UnitVector},
            f.clearance.axis);
    v.field({"clearance_angle", -kBig, kBig, "fruit adjustment, degrees (0: none)"},
            f.clearance.angle);
    v.objects("object_IDs", f.objects);
}

template <class S, class V>
requires SameAs<S, FloralBud>
void describeState(S& b, V& v) {
    v.field(editable({"stage", 0, 0, "bud, flower_closed, flower_open, fruit or removed"}),
            b.stage);
    v.field(editable({"state", 0, 0, "dormant, active, broken or dead"}), b.state);
    v.field({"terminal", 0, 1, "at the shoot tip (else axillary)"}, b.terminal);
    v.field(
        {"terminal_azimuth", -360, 360,
         "terminal buds: place around the shoot tip, degrees from its last internode's azimuth"},
        b.terminalAzimuth);
    v.field({"parameters_label", 0, 0,
             "shoot type whose template makes and draws it (empty: its phytomer's)",
             Check::LabelOrEmpty},
            b.parametersLabel);
    v.field({"fruit_age", -kTime, kTime, "days since fruit set"}, b.fruitAge);
    v.field(editable({"fruit_growth", 0, kBig, "current / full-grown fruit size"}), b.fruitGrowth);
    v.field({"stage_time", -kTime, kTime, "plant age when the stage began, days", Check::None,
             Clock::Age},
            b.stageTime);
    v.field({"next_time", -kTime, kTime, "plant age of the next stage (negative: none)",
             Check::None, Clock::Scheduled},
            b.nextTime);
    v.group("peduncle", [&](auto& p) {
        p.field(editable({"peduncle_length", 0, kBig, "m"}), b.peduncleLength);
        p.field(editable({"peduncle_radius", 0, kBig, "m"}), b.peduncleRadius);
        p.field(editable({"peduncle_pitch", -kBig, kBig, "degrees"}), b.pedunclePitch);
        p.field(editable({"peduncle_roll", -kBig, kBig, "degrees"}), b.peduncleRoll);
        p.field(editable({"peduncle_curvature", -kBig, kBig, "degrees per m"}),
                b.peduncleCurvature);
        p.field({"peduncle_azimuth", -kBig, kBig,
                 "its side turned about the stem from its petiole's, degrees (0: not steered)"},
                b.peduncleAzimuth);
        p.field({"peduncle_clearance_axis", -1, 1, "turn out of solid obstacles: world axis",
                 Check::UnitVector},
                b.peduncleClearance.axis);
        p.field({"peduncle_clearance_angle", -kBig, kBig,
                 "turn out of solid obstacles, degrees (0: none)"},
                b.peduncleClearance.angle);
        p.objects("peduncle_object_ID", b.peduncleObject);
        p.list("flower", b.flowers);
    });
}

template <class S, class V>
requires SameAs<S, LeafOrgan>
void describeState(S& l, V& v) {
    v.field(editable({"leaf_scale", 0, kBig, "full-grown length, m"}), l.scale);
    v.field(editable({"leaf_pitch", -kBig, kBig, "degrees"}), l.pitch);
    v.field(editable({"leaf_yaw", -kBig, kBig, "degrees"}), l.yaw);
    v.field(editable({"leaf_roll", -kBig, kBig, "degrees"}), l.roll);
    v.field({"leaflet_index", -1000, 1000, "0 tip, negative left, positive right"}, l.leafletIndex);
    v.field(editable({"position", -kBig, kBig, "along the petiole, fraction of its length"}),
            l.position);
    v.field({"variant", 0, kCount, "prototype shape variant"}, l.variant);
    v.field({"leaf_ID", -1, kMaxLeafID, "unique within the plant"}, l.leafID);
    v.field({"age", -kTime, kTime, "days"}, l.age);
    v.field({"birth", -kTime, kTime, "plant age when it appeared, days", Check::None, Clock::Age},
            l.birth);
    v.field({"removed", 0, 1, "shed or removed"}, l.removed);
    v.objects("object_IDs", l.objects);
    v.optional("nitrogen", l.nitrogen);
    v.optional("angle_target", l.angleTarget);
}

template <class S, class V>
requires SameAs<S, Petiole>
void describeState(S& p, V& v) {
    v.field(editable({"petiole_length", 0, kBig, "full-grown length, m"}), p.length);
    v.field(editable({"petiole_radius", 0, kBig, "base radius, m"}), p.radius);
    v.field(editable({"petiole_pitch", -kBig, kBig, "from the internode axis, degrees"}), p.pitch);
    v.field(editable({"petiole_curvature", -kAnyFloat, kAnyFloat, "degrees per m"}), p.curvature);
    v.legacy("leaflet_scale");  // the listing's value; each leaf here carries its own scale
    v.field(editable({"petiole_taper", 0, kBig, "tip radius / base radius"}), p.taper);
    v.field({"petiole_azimuth", -kBig, kBig, "about the internode axis, degrees"}, p.azimuth);
    v.field({"clearance_axis", -1, 1, "turn out of solid obstacles: world axis", Check::UnitVector},
            p.clearance.axis);
    v.field({"clearance_angle", -kBig, kBig, "turn out of solid obstacles, degrees (0: none)"},
            p.clearance.angle);
    v.objects("object_ID", p.object);
    v.list("leaf", p.leaves);
    v.list("vegetative_bud", p.vegetativeBuds);
    v.list("floral_bud", p.floralBuds);
}

template <class S, class V>
requires SameAs<S, InternodeBend>
void describeState(S& b, V& v) {
    v.field({"axis", -1, 1, "bend turn: world axis", Check::UnitVector}, b.axis);
    v.field({"angle", -360, 360, "bend turn from the rest shape, degrees"}, b.angle);
}

template <class S, class V>
requires SameAs<S, Internode>
void describeState(S& in, V& v) {
    v.field(editable({"internode_length", 0, kBig, "full-grown length, m"}), in.length);
    v.field(editable({"internode_radius", 0, kBig, "current radius, m"}), in.radius);
    v.field({"internode_pitch", -kBig, kBig, "realized zig-zag pitch, degrees"}, in.pitch);
    v.field({"phyllotactic_angle", -kBig, kBig, "roll from the previous phytomer, degrees"},
            in.phyllotacticAngle);
    v.field({"azimuth", -kBig, kBig, "accumulated phyllotactic roll, degrees"}, in.azimuth);
    v.field({"direction", -1, 1, "axis of the internode", Check::UnitVector}, in.direction);
    v.field({"shoot_axis", -1, 1, "shoot axis here (curvature, walk, steering)", Check::UnitVector},
            in.guide);
    v.field({"roll_reference", -1, 1, "azimuth 0 of the petioles", Check::UnitVector},
            in.rollReference);
    v.field({"gravitropic_turn", -kBig, kBig, "degrees"}, in.gravitropicTurn);
    v.field({"walk_zenith", -kBig, kBig, "random-walk perturbation, degrees"}, in.walkZenith);
    v.field({"walk_yaw", -kBig, kBig, "random-walk perturbation, degrees"}, in.walkYaw);
    v.objects("object_ID", in.object);
    v.optional("bend", in.bend);
}

/// A nested element whose content is the table of `member` (a struct of its own), then
/// more(subVisitor): fields or lists of the enclosing object that files keep inside it. A
/// visitor that deals in whole structs (the Python binding) defines member(name, member,
/// more); to every other visitor this is a group.
template <class V, class T, class More>
void nested(V& v, const char* name, T& member, More&& more) {
    if constexpr (requires { v.member(name, member, more); })
        v.member(name, member, more);
    else
        v.group(name, [&](auto& sub) {
            describeState(member, sub);
            more(sub);
        });
}

template <class S, class V>
requires SameAs<S, MeasuredInternode>
void describeState(S& m, V& v) {
    v.field({"radius", 0, kBig, "measured internode radius, m"}, m.radius);
}

template <class S, class V>
requires SameAs<S, Phytomer>
void describeState(S& ph, V& v) {
    v.field({"age", -kTime, kTime, "days"}, ph.age);
    v.field(
        {"birth", -kTime, kTime, "plant age when it was created, days", Check::None, Clock::Age},
        ph.birth);
    v.field(editable({"internode_fraction", 0, kBig, "current / full internode length"}),
            ph.internodeFraction);
    v.field(editable({"leaf_fraction", 0, kBig, "current / full petiole and leaf size"}),
            ph.leafFraction);
    v.field({"internode_fraction_initial", 0, kBig, "at creation"}, ph.internodeFraction0);
    v.field({"leaf_fraction_initial", 0, kBig, "at creation"}, ph.leafFraction0);
    v.field({"radius_initial", 0, kBig, "internode radius at creation, m"}, ph.radiusInitial);
    v.field({"parameters_label", 0, 0, "shoot type whose template built it", Check::Label},
            ph.parametersLabel);
    v.optional("measured", ph.measured);
    // The specification nests the petioles inside the internode.
    nested(v, "internode", ph.internode, [&](auto& sub) { sub.list("petiole", ph.petioles); });
}

template <class S, class V>
requires SameAs<S, Shoot>
void describeState(S& s, V& v) {
    v.field({"shoot_type_label", 0, 0, "shoot type", Check::Label}, s.type);
    v.field({"parent_shoot_ID", -1, kCount, "-1 for the base stem"}, s.parent);
    v.field({"parent_node_index", -1, kCount, "node on the parent"}, s.parentNode);
    v.field({"parent_petiole_index", 0, kCount, "petiole on that node"}, s.parentPetiole);
    v.field({"base_rotation", -kBig, kBig, "pitch, yaw, roll, degrees"}, s.baseRotation);
    v.field({"rank", 0, kCount, "0 base stem, 1 its children, ..."}, s.rank);
    v.field({"insertion_angle", -kBig, kBig, "from the parent axis, degrees"}, s.insertionAngle);
    v.field({"radius_taper", -kBig, kBig, ""}, s.radiusTaper);
    // Realized from integer parameters, which never leave their declared range (<= 100000):
    // this bounds the growth a file can ask for.
    v.field({"max_nodes", 0, 100000, "realized"}, s.maxNodes);
    v.field({"max_nodes_per_season", 0, 100000, "realized"}, s.maxNodesPerSeason);
    v.field({"internode_length_max", 0, kBig, "realized, m"}, s.internodeLengthMax);
    v.field({"phyllochron", -kBig, kBig, "realized, days per node"}, s.phyllochron);
    v.field({"elongation_rate", -kBig, kBig, "realized, per day"}, s.elongationRate);
    v.field({"gravitropic_curvature", -kBig, kBig, "realized, degrees per m"},
            s.gravitropicCurvature);
    v.field({"tortuosity", -kBig, kBig, "realized"}, s.tortuosity);
    v.field({"girth_area_factor", -kBig, kBig, "realized, cm^2 per m^2"}, s.girthAreaFactor);
    v.field({"nodes_this_season", -kCount, kCount, ""}, s.nodesThisSeason);
    v.field({"next_phytomer_time", -kTime, kTime, "plant age, days (negative: none)", Check::None,
             Clock::Scheduled},
            s.nextPhytomerTime);
    v.field({"flowering", 0, 1, ""}, s.flowering);
    v.field({"removed", 0, 1, "pruned away"}, s.removed);
    nested(v, "apical_bud", s.apicalBud, [](auto&) {});
    v.list("phytomer", s.phytomers);
    v.list("terminal_floral_bud", s.terminalFloralBuds);
    v.optional("carbohydrates", s.carbon);
}

template <class S, class V>
requires SameAs<S, ShootCarbon>
void describeState(S& c, V& v) {
    v.field({"sugar", -kBig, kBig, "sugar pool, mol C"}, c.sugar);
    v.field({"starch", 0, kBig, "starch pool, mol C"}, c.starch);
    v.field({"wood_carbon", 0, kBig, "structure in its internodes at the last step, mol C"},
            c.woodCarbon);
    v.field({"leaf_area", 0, kBig, "leaf area at the last step, m^2"}, c.leafArea);
    v.field({"fruit_volume", 0, kBig, "fruit volume at the last step, m^3"}, c.fruitVolume);
    v.field({"flowers", 0, kCount, "flowers formed and paid for"}, c.flowers);
    v.field({"poor_days", 0, kTime, "days below the abortion threshold"}, c.poorDays);
    v.field({"starved_days", 0, kTime, "days below the pruning threshold"}, c.starvedDays);
    v.field({"phyllochron", 0, kBig, "the shoot's own phyllochron, days"}, c.phyllochron);
    v.field({"bud_break_factor", 0, 1, "scales its buds' break probability"}, c.budBreakFactor);
    v.field(
        {"radial_allowance", 0, kBig, "carbon it may spend thickening until the next step, mol C"},
        c.radialAllowance);
}

template <class S, class V>
requires SameAs<S, LeafAngleTarget>
void describeState(S& t, V& v) {
    v.field(editable({"inclination", 0, 90,
                      "of the blade's mean normal from the zenith (of the blade from horizontal), "
                      "degrees"}),
            t.inclination);
    v.field(editable({"azimuth", 0, 360,
                      "the compass direction its upper side faces, degrees clockwise from north"}),
            t.azimuth);
}

template <class S, class V>
requires SameAs<S, LeafNitrogen>
void describeState(S& n, V& v) {
    v.field({"content", 0, kBig, "g N in the leaf"}, n.content);
}

template <class S, class V>
requires SameAs<S, PlantNitrogen>
void describeState(S& n, V& v) {
    v.field({"available", 0, kBig, "g N available to leaves and fruit"}, n.available);
    v.field({"roots", 0, kBig, "g N kept by the roots"}, n.roots);
    v.field({"uptake", 0, kBig, "g N taken up so far"}, n.uptake);
    v.field({"fruit", 0, kBig, "g N in fruit so far"}, n.fruit);
    v.field({"leaves", 0, kBig, "g N in its leaves after the last step"}, n.leaves);
    v.field({"stress", 0, 1, "leaf N over target, at most 1"}, n.stress);
}

// A plant's own attraction points (docs/collision.md): the cone and the points, in world
// coordinates. The shoot types are labels separated by spaces (none: every type).
template <class S, class V>
requires SameAs<S, AttractionPoints>
void describeState(S& a, V& v) {
    v.field({"half_angle", 0, 180, "perception cone half-angle, degrees", Check::Exclusive},
            a.halfAngle);
    v.field({"look_ahead", 0, 100, "perception cone length, m", Check::ExclusiveMin}, a.lookAhead);
    v.field({"inertia", 0, 1, "0: turns fully toward the point, 1: unchanged"}, a.inertia);
    v.field({"shoot_types", 0, 0, "attracted shoot types (none: all)", Check::Label}, a.shootTypes);
    v.values({"point", -kBig, kBig, "an attraction point, world position, m"}, a.points);
}

template <class S, class V>
requires SameAs<S, EpicormicShoots>
void describeState(S& e, V& v) {
    v.field({"shoot_type_label", 0, 0, "type of the water sprouts", Check::Label}, e.shootType);
    v.field({"probability", 0, kBig, "per m of parent shoot per day, at a vertical parent"},
            e.probability);
}

template <class S, class V>
requires SameAs<S, PlantInstance>
void describeState(S& p, V& v) {
    v.field({"plant_name", 0, 0, "species or user label"}, p.name);
    v.field({"base_position", -kBig, kBig, "m"}, p.base);
    v.field({"plant_age", 0, kTime, "days", Check::None, Clock::Age}, p.age);
    v.field({"random_generator", 0, 0, "PCG32 state and increment"}, p.rng);
    v.field({"next_leaf_ID", 0, kMaxLeafID, ""}, p.nextLeafID);
    v.field({"phenology_stage", 0, 0, "dormant, vegetative, reproductive or senescent"}, p.stage);
    v.field({"dormancy_break_time", -kTime, kTime,
             "when the season began, days (negative: not yet)", Check::None, Clock::Scheduled},
            p.dormancyBreakTime);
    v.field({"next_dormancy_break", -kTime, kTime, "days (negative: never)", Check::None,
             Clock::Scheduled},
            p.nextDormancyBreak);
    v.field(
        {"senescence_time", -kTime, kTime, "days (negative: never)", Check::None, Clock::Scheduled},
        p.senescenceTime);
    v.field({"season", 0, kCount, "growing seasons begun"}, p.season);
    v.field({"ground_clearance", 0, 1, "side organs turned to stay above the base's z"},
            p.groundClearance);
    v.optional("attraction_points", p.attraction);
    v.optional("epicormic_shoots", p.epicormic);
    v.optional("nitrogen", p.nitrogen);
    v.parameters("phenology", p.phenology);
    v.parameters("shoot_type", p.shootTypes);
    v.list("shoot", p.shoots, true);
}

// ---- using the declarations ---------------------------------------------------------------

/// Whether `v` lies in the field's range (a NaN never does).
inline bool inside(const FieldInfo& f, double v) {
    const NumberRange r = f.range();
    return (r.openMin ? v > r.min : v >= r.min) && (r.openMax ? v < r.max : v <= r.max);
}

/// Visits a table and keeps the declaration of the field named `name` (fieldInfo below).
struct FieldFinder {
    std::string_view name;
    std::optional<FieldInfo> found;
    template <class T>
    void field(const FieldInfo& f, T&) {
        if (!found && name == f.name) found = f;
    }
    template <class T>
    void field(const params::FieldInfo&, T&) {}
    template <class Fn>
    void group(const char*, Fn&& fn) {
        fn(*this);
    }
    template <class T>
    void list(const char*, std::vector<T>&, bool = false) {}
    template <class T>
    void values(const FieldInfo& f, std::vector<T>&) {
        if (!found && name == f.name) found = f;
    }
    template <class T>
    void optional(const char*, std::optional<T>&) {}
    template <class P>
    void parameters(const char*, P&) {}
    void legacy(const char*) {}
    template <class T>
    void objects(const char*, T&) {}
};

/// The declaration of the field `name` of S's own table (nested groups included, lists of
/// other types not), e.g. fieldInfo<LeafOrgan>("leaf_scale"). Throws std::logic_error for a
/// name the table does not declare: a mistake in plantarch, not in any input.
template <class S>
FieldInfo fieldInfo(std::string_view name) {
    S object;  // only its members' addresses are visited
    FieldFinder finder{name, std::nullopt};
    describeState(object, finder);
    if (!finder.found) throw std::logic_error("plant state table: no field " + std::string(name));
    return *finder.found;
}

}  // namespace plantarch::state
