// Node rules: conditions on a phytomer's place, its shoot and the plant's age and season, and
// the actions that change the phytomer when they hold (see node_rules.h).

#include "model/node_rules.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/PhytomerActions.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch {

const std::vector<std::string>& NodeRule::formulaVariables() {
    static const std::vector<std::string> names = {"age", "node", "rank", "max_nodes",
                                                   "nodes_from_tip"};
    return names;
}

Formula NodeRule::formula(std::string_view text) {
    return Formula(text, formulaVariables(), false);
}

namespace rules {

namespace {

// The first whole day of plant age in the current dormant period: the day after the plant was
// made for its first winter (no daily rule runs on the day it is made), else the first whole
// day at or after the season's end.
bool firstDayOfWinter(const PlantInstance& plant, double age) {
    if (plant.stage != PhenologyStage::Dormant || plant.nextDormancyBreak < 0.0) return false;
    const double start = plant.nextDormancyBreak - double(plant.phenology.time_to_dormancy_break);
    const double day = plant.season == 0 ? std::floor(start) + 1.0 : std::ceil(start - 1e-9);
    return std::abs(age - day) < 1e-6;
}

// Where a rule is asked about a phytomer.
struct Place {
    PlantInstance& plant;
    Shoot& shoot;
    unsigned node;
    double age;
    const std::function<vec3()>* nodeBase;  ///< null at creation
};

bool holds(const NodeRule& r, const Place& at) {
    const int rank = int(at.shoot.rank);
    const int node = int(at.node);
    const int fromTip = int(at.shoot.phytomers.size()) - 1 - node;
    const int beforeLast = at.shoot.maxNodes - 1 - node;
    if (rank < r.rank_min || rank > r.rank_max) return false;
    if (node < r.node_min || node > r.node_max) return false;
    if (fromTip < r.nodes_from_tip_min || fromTip > r.nodes_from_tip_max) return false;
    if (beforeLast < r.nodes_before_last_min || beforeLast > r.nodes_before_last_max) return false;
    if (at.age < double(r.age_min) || at.age > double(r.age_max)) return false;
    if (r.only_when_dormant && at.plant.stage != PhenologyStage::Dormant) return false;
    const Phytomer& ph = at.shoot.phytomers[at.node];
    if (!(ph.internode.length < r.internode_length_below)) return false;
    if (r.height_below < 1e9f && at.nodeBase) {
        const float height = (*at.nodeBase)().z - at.plant.base.z;
        if (!(height < r.height_below)) return false;
    }
    return true;
}

// Where a rule acts, for its errors: "node 3 of shoot 2 (a stem) at plant age 12 days".
std::string placeText(const Place& at) {
    return "node " + std::to_string(at.node) + " of shoot " + std::to_string(at.shoot.id) + " (" +
           at.shoot.type + ") at plant age " + text::formatDouble(at.age) + " days";
}

// A rule's formula, with what its errors name: the parameter path of the formula as species
// files give it ("stem.phytomer.node_rules[2].leaf_scale": the shoot type whose rules these
// are, the rule counted from 1), whose line the species reader knows (the library layer
// places the error there: species_build.cpp, library_api.cpp).
// The path is made only for an error: daily rules run for every phytomer every day.
struct RuleFormula {
    const Formula& formula;
    const std::string& shootType;
    std::size_t rule;
    const char* field;

    std::string path() const {
        return shootType + ".phytomer.node_rules[" + std::to_string(rule + 1) + "]." + field;
    }
};

RuleFormula ruleFormula(const Formula& f, const Place& at, std::size_t rule, const char* field) {
    return {f, at.shoot.phytomers[at.node].parametersLabel, rule, field};
}

float value(const RuleFormula& f, const Place& at) {
    const std::array<float, 5> v = {float(at.age), float(at.node), float(at.shoot.rank),
                                    float(at.shoot.maxNodes),
                                    float(int(at.shoot.phytomers.size()) - 1 - int(at.node))};
    try {
        return f.formula.evaluateFloat(v);
    } catch (const Error& e) {
        ErrorContext c = e.context();
        if (c.parameter.empty()) c.parameter = f.path();
        throw Error(e.message() + ", at " + placeText(at), c);
    }
}

// The state fields rules change, as the state table declares them.
struct RuleFields {
    state::FieldInfo leafScale = state::fieldInfo<LeafOrgan>("leaf_scale");
    state::FieldInfo internodeLength = state::fieldInfo<Internode>("internode_length");
    state::FieldInfo petiolePitch = state::fieldInfo<Petiole>("petiole_pitch");
    state::FieldInfo leafPitch = state::fieldInfo<LeafOrgan>("leaf_pitch");
};

const RuleFields& ruleFields() {
    static const RuleFields fields;
    return fields;
}

// What a rule's formula makes of a state field: `result` (computed in float, as the field
// holds it) must lie in the field's declared range, else the rule is refused naming the
// formula's value and the range of the field; `exact` is the result in double, for the
// message (a float result may have overflowed).
float checkedResult(const RuleFormula& f, const Place& at, const state::FieldInfo& field,
                    float formulaValue, float current, float result, double exact) {
    if (state::inside(field, result)) return result;
    const std::string shown =
        std::isfinite(result) ? text::formatFloat(result) : text::formatDouble(exact);
    const std::string value = text::formatFloat(formulaValue);
    throw Error(
        "makes " + std::string(field.name) + " " + shown + " from " + text::formatFloat(current) +
            ", out of its range, at " + placeText(at),
        {.parameter = f.path(),
         .value = value == f.formula.text() ? value : value + " (from '" + f.formula.text() + "')",
         .validRange =
             "results keeping " + std::string(field.name) + " within " + rangeText(field.range())});
}

// A factor on a size: size x factor must stay in the size's range.
void scale(const RuleFormula& f, const Place& at, const state::FieldInfo& field, float factor,
           float& size) {
    size = checkedResult(f, at, field, factor, size, size * factor, double(size) * double(factor));
}

// A change of an angle: angle + change must stay in the angle's range.
void turn(const RuleFormula& f, const Place& at, const state::FieldInfo& field, float change,
          float& angle) {
    angle =
        checkedResult(f, at, field, change, angle, angle + change, double(angle) + double(change));
}

// Every floral bud that flowered, fruited or failed becomes an unopened dormant bud again; its
// time is set when dormancy breaks, and its old inflorescence goes when it next flowers.
void renewFloralBuds(Phytomer& ph) {
    for (Petiole& p : ph.petioles)
        for (FloralBud& b : p.floralBuds) {
            if (b.stage == FloralStage::Bud && b.state == BudState::Dormant) continue;
            b.stage = FloralStage::Bud;
            b.state = BudState::Dormant;
            b.nextTime = -1.0;
            b.fruitAge = 0.0f;
            b.fruitGrowth = 1.0f;
        }
}

void floweringFrom(const std::string& type, std::size_t rule, Place& at, Phytomer& ph) {
    if (!at.plant.shootTypes.count(type))
        throw Error("a node rule names a shoot type the plant does not have",
                    {.parameter = ph.parametersLabel + ".phytomer.node_rules[" +
                                  std::to_string(rule + 1) + "].flowering_shoot_type",
                     .value = type,
                     .validRange = "a shoot type of the species"});
    for (Petiole& p : ph.petioles)
        for (FloralBud& b : p.floralBuds)
            if (b.stage == FloralStage::Bud && b.state == BudState::Dormant) {
                b.state = BudState::Active;
                b.parametersLabel = type;
            }
}

// The shoot's N most distal nodes lose their floral buds, the nodes below their vegetative
// buds (N drawn from the plant's stream).
void splitShoot(const RandomInt& distal, Place& at) {
    std::vector<Phytomer>& nodes = at.shoot.phytomers;
    const int n = int(nodes.size());
    const int tip = distal.sample(at.plant.rng);
    for (int k = 0; k < n; ++k) {
        if (k < n - tip)
            killVegetativeBuds(nodes[std::size_t(k)]);
        else
            killFloralBuds(nodes[std::size_t(k)]);
    }
}

void act(const NodeRule& r, std::size_t index, Place& at) {
    Phytomer& ph = at.shoot.phytomers[at.node];
    if (r.remove_vegetative_buds) killVegetativeBuds(ph);
    if (r.remove_floral_buds) killFloralBuds(ph);
    if (r.remove_leaves) removeLeaves(ph);
    if (r.renew_floral_buds) renewFloralBuds(ph);
    if (!r.flowering_shoot_type.empty()) floweringFrom(r.flowering_shoot_type, index, at, ph);
    // Each result is held to the range of the field it sets.
    const RuleFields& fields = ruleFields();
    if (!r.leaf_scale.empty()) {
        const RuleFormula f = ruleFormula(r.leaf_scale, at, index, "leaf_scale");
        const float s = value(f, at);
        for (Petiole& p : ph.petioles)  // refused with the formula named, before any change
            for (LeafOrgan& l : p.leaves) {
                float size = l.scale;
                scale(f, at, fields.leafScale, s, size);
            }
        scaleLeaves(ph, s);
    }
    if (!r.internode_scale.empty()) {
        const RuleFormula f = ruleFormula(r.internode_scale, at, index, "internode_scale");
        scale(f, at, fields.internodeLength, value(f, at), ph.internode.length);
    }
    if (!r.petiole_pitch_change.empty()) {
        const RuleFormula f =
            ruleFormula(r.petiole_pitch_change, at, index, "petiole_pitch_change");
        const float d = value(f, at);
        for (Petiole& p : ph.petioles) turn(f, at, fields.petiolePitch, d, p.pitch);
    }
    if (!r.leaf_pitch_change.empty()) {
        const RuleFormula f = ruleFormula(r.leaf_pitch_change, at, index, "leaf_pitch_change");
        const float d = value(f, at);
        for (Petiole& p : ph.petioles)
            for (LeafOrgan& l : p.leaves) turn(f, at, fields.leafPitch, d, l.pitch);
    }
    if (r.max_nodes_per_season < NodeRule::kNoLimit)
        at.shoot.maxNodesPerSeason = std::min(at.shoot.maxNodesPerSeason, r.max_nodes_per_season);
    if (!(r.distal_vegetative_nodes.isConstant() && r.distal_vegetative_nodes.min() == 0))
        splitShoot(r.distal_vegetative_nodes, at);
}

}  // namespace

void applyAtCreation(PlantInstance& plant, Shoot& shoot, const PhytomerParameters& pp) {
    if (pp.node_rules.empty()) return;
    Place at{plant, shoot, unsigned(shoot.phytomers.size() - 1), plant.age, nullptr};
    for (std::size_t i = 0; i < pp.node_rules.size(); ++i) {
        const NodeRule& r = pp.node_rules[i];
        if (r.when == NodeRuleTime::Creation && holds(r, at)) act(r, i, at);
    }
}

bool hasDailyRules(const std::map<std::string, ShootParameters>& types) {
    for (const auto& [label, t] : types)
        for (const NodeRule& r : t.phytomer_parameters.node_rules)
            if (r.when != NodeRuleTime::Creation) return true;
    return false;
}

void applyDaily(PlantInstance& plant, Shoot& shoot, unsigned node, const PhytomerParameters& pp,
                double age, const std::function<vec3()>& nodeBase) {
    Place at{plant, shoot, node, age, &nodeBase};
    for (std::size_t i = 0; i < pp.node_rules.size(); ++i) {
        const NodeRule& r = pp.node_rules[i];
        if (r.when == NodeRuleTime::Creation) continue;
        if (r.when == NodeRuleTime::Winter && !firstDayOfWinter(plant, age)) continue;
        if (holds(r, at)) act(r, i, at);
    }
}

}  // namespace rules
}  // namespace plantarch
