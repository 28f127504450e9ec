// Validation of species parameters, driven by the declaration table.

#include <charconv>
#include <cmath>
#include <tuple>
#include <type_traits>
#include <utility>

#include "core/value_text.h"
#include "model/leaf_angle_distribution.h"
#include "plantarch/Error.h"
#include "plantarch/ParameterCheck.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/PlantState.h"

namespace plantarch {

namespace {

std::string number(double v) {
    return text::formatDouble(v);
}

// Visits every field and throws on the first value outside its declared range.
struct Validator {
    std::string path;

    std::string at(const params::FieldInfo& f) const {
        return path.empty() ? f.name : path + "." + f.name;
    }
    [[noreturn]] void fail(const params::FieldInfo& f, const std::string& value,
                           const std::string& why, std::string range = "") const {
        throw Error(why, {.parameter = at(f),
                          .value = value,
                          .validRange = range.empty() ? rangeText(f.range()) : range});
    }
    void checkNumber(const params::FieldInfo& f, double lo, double hi,
                     const std::string& text) const {
        if (!std::isfinite(lo) && lo != -params::kInf) fail(f, text, "not a number");
        if (lo < f.min || hi > f.max) fail(f, text, "out of range");
    }

    void field(const params::FieldInfo& f, const RandomFloat& v) const {
        // Normal and Weibull draws are limited (RandomFloat::kNormalLimit, kWeibullLimit),
        // so the bounds below are every value a draw can realize.
        checkNumber(f, v.lowerBound(), v.upperBound(), v.describe());
    }
    void field(const params::FieldInfo& f, const RandomInt& v) const {
        checkNumber(f, v.min(), v.max(), v.describe());
    }
    void field(const params::FieldInfo& f, const float& v) const {
        checkNumber(f, v, v, number(v));
    }
    void field(const params::FieldInfo& f, const unsigned& v) const {
        checkNumber(f, v, v, std::to_string(v));
    }
    void field(const params::FieldInfo& f, const int& v) const {
        checkNumber(f, v, v, std::to_string(v));
    }
    void field(const params::FieldInfo&, const bool&) const {}
    void field(const params::FieldInfo& f, const vec3& v) const {
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(v[i]) || v[i] < f.min || v[i] > f.max)
                fail(f, number(v.x) + " " + number(v.y) + " " + number(v.z), "out of range");
    }
    void field(const params::FieldInfo&, const std::string&) const {}
    template <params::ChoiceType E>
    void field(const params::FieldInfo& f, const E& v) const {
        if (params::choiceName(v)) return;
        std::string valid;
        for (const std::string& name : params::choiceNames<E>())
            valid += (valid.empty() ? "" : ", ") + name;
        fail(f, std::to_string(int(v)), "not a declared value", "one of: " + valid);
    }
    void field(const params::FieldInfo&, const std::map<int, std::string>&) const {}
    void field(const params::FieldInfo& f, const std::map<std::string, float>& types) const {
        if (!f.probabilities) {
            for (const auto& [key, value] : types)
                if (!std::isfinite(value) || value < f.min || value > f.max)
                    throw Error("out of range", {.parameter = at(f) + "." + key,
                                                 .value = number(value),
                                                 .validRange = rangeText(f.range())});
            return;
        }
        if (types.empty()) return;
        double sum = 0.0;
        for (const auto& [label, prob] : types) {
            if (!(prob >= f.min && prob <= f.max))
                throw Error("probability out of range", {.parameter = at(f) + "." + label,
                                                         .value = number(prob),
                                                         .validRange = rangeText(f.range())});
            sum += prob;
        }
        if (std::abs(sum - 1.0) > 1e-4)
            fail(f, number(sum), "probabilities must sum to 1", "sum of 1");
    }
    void field(const params::FieldInfo&, const Formula&) const {}  // checked when parsed
    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) const {
        Validator sub{path.empty() ? name : path + "." + name};
        visit(sub);
    }
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char*, const std::vector<E>& items,
              Fn&& visit) const {
        for (std::size_t i = 0; i < items.size(); ++i) {
            Validator sub{(path.empty() ? std::string(f.name) : path + "." + f.name) + "[" +
                          std::to_string(i + 1) + "]"};
            visit(items[i], sub);
            sub.whole(items[i]);
        }
    }

    // Checks across the fields of one node rule: ranges that can hold, conditions that apply
    // at the rule's time, a shoot type label that can name one.
    void whole(const NodeRule& r) const {
        auto fail = [&](const char* field, const std::string& value, const std::string& why,
                        const std::string& range) {
            throw Error(why,
                        {.parameter = path + "." + field, .value = value, .validRange = range});
        };
        using Range = std::tuple<const char*, const char*, int, int>;
        for (const auto& [lo, hi, a, b] : {Range{"rank_min", "rank_max", r.rank_min, r.rank_max},
                                           Range{"node_min", "node_max", r.node_min, r.node_max},
                                           Range{"nodes_from_tip_min", "nodes_from_tip_max",
                                                 r.nodes_from_tip_min, r.nodes_from_tip_max},
                                           Range{"nodes_before_last_min", "nodes_before_last_max",
                                                 r.nodes_before_last_min, r.nodes_before_last_max}})
            if (a > b)
                fail(lo, std::to_string(a),
                     std::string("the rule can never hold: ") + lo + " exceeds " + hi,
                     std::string("at most ") + hi + " = " + std::to_string(b));
        if (r.age_min > r.age_max)
            fail("age_min", number(r.age_min), "the rule can never hold: age_min exceeds age_max",
                 "at most age_max = " + number(r.age_max));
        if (r.when == NodeRuleTime::Creation && r.height_below < 1e9f)
            fail("height_below", number(r.height_below),
                 "height_below needs a daily or winter rule (a node has no height as it is made)",
                 "<when>daily</when> or <when>winter</when>");
        if (!r.flowering_shoot_type.empty() && !text::isLabel(r.flowering_shoot_type))
            fail("flowering_shoot_type", r.flowering_shoot_type,
                 "a shoot type label is letters, digits, '_' or '-'", "a shoot type label");
    }
    template <class E>
    void whole(const E&) const {}
};

// Validates the probability maps of a shoot's own level only, as declared in the table
// (defineChildShootTypes checks child_shoot_types with it).
struct ChildTypesOnly {
    template <class T>
    void field(const params::FieldInfo& f, const T& member) const {
        if constexpr (std::is_same_v<T, std::map<std::string, float>>)
            if (f.probabilities) Validator{}.field(f, member);
    }
    template <class G, class Fn>
    void group(const char*, const G&, Fn&&) const {}
};

}  // namespace

namespace params {

#define PLANTARCH_CHECK_FIELD(T)                                                   \
    void checkField(const FieldInfo& f, const std::string& path, const T& value) { \
        Validator{path}.field(f, value);                                           \
    }
PLANTARCH_CHECK_FIELD(RandomFloat)
PLANTARCH_CHECK_FIELD(RandomInt)
PLANTARCH_CHECK_FIELD(float)
PLANTARCH_CHECK_FIELD(unsigned)
PLANTARCH_CHECK_FIELD(int)
PLANTARCH_CHECK_FIELD(bool)
PLANTARCH_CHECK_FIELD(vec3)
PLANTARCH_CHECK_FIELD(std::string)
PLANTARCH_CHECK_FIELD(LeafShape)
PLANTARCH_CHECK_FIELD(FlowerArrangement)
PLANTARCH_CHECK_FIELD(NodeRuleTime)
PLANTARCH_CHECK_FIELD(LeafInclinationDistribution)
PLANTARCH_CHECK_FIELD(LeafAzimuthDistribution)
PLANTARCH_CHECK_FIELD(Formula)
#undef PLANTARCH_CHECK_FIELD

void checkField(const FieldInfo& f, const std::string& path,
                const std::map<int, std::string>& value) {
    Validator{path}.field(f, value);
}

void checkField(const FieldInfo& f, const std::string& path,
                const std::map<std::string, float>& value) {
    Validator{path}.field(f, value);
}

void checkField(const FieldInfo& f, const std::string& path, const std::vector<NodeRule>& value) {
    Validator{path}.list(f, "rule", value,
                         [](const NodeRule& rule, auto& sub) { describeParameters(rule, sub); });
}

}  // namespace params

void validate(const PhytomerParameters& p, const std::string& prefix) {
    Validator v{prefix};
    params::describeParameters(p, v);
}

void validate(const PhenologyParameters& p, const std::string& prefix) {
    Validator v{prefix};
    params::describeParameters(p, v);
    auto at = [&](const char* name) { return prefix.empty() ? name : prefix + "." + name; };
    const LeafPhysiologyParameters& leaf = p.leaf_physiology;
    if (leaf.leaf_reflectance + leaf.leaf_transmittance > 1.0f)
        throw Error("a leaf cannot reflect and transmit more than the light it gets",
                    {.parameter = at("leaf_physiology.leaf_transmittance"),
                     .value = std::to_string(leaf.leaf_transmittance),
                     .validRange = "<= 1 - leaf_reflectance"});
    if (p.nitrogen.minimum_leaf_nitrogen > p.nitrogen.target_leaf_nitrogen)
        throw Error("a leaf's minimum nitrogen exceeds its target",
                    {.parameter = at("nitrogen.minimum_leaf_nitrogen"),
                     .value = std::to_string(p.nitrogen.minimum_leaf_nitrogen),
                     .validRange = "<= target_leaf_nitrogen"});
    leaf_angles::check(p.leaf_angles, at("leaf_angles"));
}

void validate(const ShootParameters& p, const std::string& prefix) {
    Validator v{prefix};
    params::describeParameters(p, v);
    auto at = [&](const char* name) { return prefix.empty() ? name : prefix + "." + name; };
    if (p.internode_length_min.lowerBound() > p.internode_length_max.upperBound())
        throw Error(
            "internode_length_min exceeds internode_length_max",
            {.parameter = at("internode_length_min"),
             .value = p.internode_length_min.describe(),
             .validRange = "<= internode_length_max (" + p.internode_length_max.describe() + ")"});
    if (p.vegetative_bud_break_probability_min.lowerBound() >
        p.vegetative_bud_break_probability_max.upperBound())
        throw Error("vegetative_bud_break_probability_min exceeds the maximum",
                    {.parameter = at("vegetative_bud_break_probability_min"),
                     .value = p.vegetative_bud_break_probability_min.describe(),
                     .validRange = "<= vegetative_bud_break_probability_max"});
    if (p.max_nodes_per_season.min() < 1 || p.max_nodes.min() < 1)
        throw Error("node limits must be at least 1", {.parameter = at("max_nodes")});
}

void ShootParameters::defineChildShootTypes(const std::vector<std::string>& labels,
                                            const std::vector<float>& probabilities) {
    if (labels.size() != probabilities.size())
        throw Error("one probability per child shoot type is needed",
                    {.parameter = "child_shoot_types",
                     .value = std::to_string(labels.size()) + " labels, " +
                              std::to_string(probabilities.size()) + " probabilities"});
    std::map<std::string, float> types;
    for (std::size_t i = 0; i < labels.size(); ++i) types[labels[i]] = probabilities[i];
    ShootParameters probe;
    probe.child_shoot_types = types;
    ChildTypesOnly check;
    params::describeParameters(std::as_const(probe), check);
    child_shoot_types = std::move(types);
}

}  // namespace plantarch
