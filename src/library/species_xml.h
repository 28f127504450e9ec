#pragma once
// Pieces shared by the species reader and writer: the element names of the file format and
// the attributes of the build steps.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Species.h"

namespace plantarch::species_xml {

inline constexpr const char* kRoot = "plantarch_species";
inline constexpr const char* kFormatVersion = "1";

/// Valid values of <plant_type>.
inline const std::vector<std::string>& plantTypes() {
    static const std::vector<std::string> types = {"herbaceous", "weed", "tree"};
    return types;
}

/// What the value of a build step attribute is.
enum class StepValue {
    Name,        ///< a step id or shoot type label
    Expression,  ///< an expression over the build parameters
    Flag,        ///< true or false
};

/// One attribute of the build steps: its name, what its value is, the BuildStep member
/// holding it (`text` for names and expressions, `flag` for flags) and the step kinds that
/// take it.
struct StepAttribute {
    const char* name;
    StepValue value;
    std::string BuildStep::*text;
    bool BuildStep::*flag;
    bool base, append, child;
};

/// Every build step attribute, in the order they are written.
inline const std::vector<StepAttribute>& allStepAttributes() {
    using B = BuildStep;
    constexpr auto N = StepValue::Name;
    constexpr auto X = StepValue::Expression;
    constexpr auto F = StepValue::Flag;
    static const std::vector<StepAttribute> all = {
        {"id", N, &B::id, nullptr, true, true, true},
        {"parent", N, &B::parent, nullptr, false, true, true},
        {"node", X, &B::parentNode, nullptr, false, false, true},
        {"petiole", X, &B::petiole, nullptr, false, false, true},
        {"repeat", X, &B::repeat, nullptr, false, false, true},
        {"type", N, &B::shootType, nullptr, true, true, true},
        {"nodes", X, &B::nodes, nullptr, true, true, true},
        {"pitch", X, &B::pitch, nullptr, true, true, true},
        {"yaw", X, &B::yaw, nullptr, true, true, true},
        {"roll", X, &B::roll, nullptr, true, true, true},
        {"radius", X, &B::radius, nullptr, true, true, true},
        {"internode_length", X, &B::internodeLength, nullptr, true, true, true},
        {"internode_scale", X, &B::internodeScale, nullptr, true, true, true},
        {"leaf_scale", X, &B::leafScale, nullptr, true, true, true},
        {"taper", X, &B::taper, nullptr, true, true, true},
        {"leaves", F, nullptr, &B::leaves, true, true, true},
        {"vegetative_buds", F, nullptr, &B::vegetativeBuds, true, true, true},
        {"floral_buds", F, nullptr, &B::floralBuds, true, true, true},
        {"apex", F, nullptr, &B::apex, true, true, true},
    };
    return all;
}

/// The attributes a step of `kind` takes, in the order they are written.
inline const std::vector<StepAttribute>& buildStepAttributes(BuildStep::Kind kind) {
    auto of = [](bool StepAttribute::*takes) {
        std::vector<StepAttribute> out;
        for (const StepAttribute& a : allStepAttributes())
            if (a.*takes) out.push_back(a);
        return out;
    };
    static const std::vector<StepAttribute> base = of(&StepAttribute::base);
    static const std::vector<StepAttribute> append = of(&StepAttribute::append);
    static const std::vector<StepAttribute> child = of(&StepAttribute::child);
    switch (kind) {
        case BuildStep::Kind::Append:
            return append;
        case BuildStep::Kind::Child:
            return child;
        case BuildStep::Kind::BaseStem:
            break;
    }
    return base;
}

inline constexpr BuildStep::Kind kBuildStepKinds[] = {
    BuildStep::Kind::BaseStem, BuildStep::Kind::Append, BuildStep::Kind::Child};

/// Element name of a build step kind.
inline const char* buildStepElement(BuildStep::Kind kind) {
    switch (kind) {
        case BuildStep::Kind::BaseStem:
            return "base_stem";
        case BuildStep::Kind::Append:
            return "append";
        case BuildStep::Kind::Child:
            return "child";
    }
    return "base_stem";
}

/// The element names of the build step kinds.
inline std::vector<std::string> buildStepElements() {
    std::vector<std::string> names;
    for (BuildStep::Kind kind : kBuildStepKinds) names.emplace_back(buildStepElement(kind));
    return names;
}

/// The kind of a build step element; nullopt for a name that is none.
inline std::optional<BuildStep::Kind> buildStepKind(std::string_view element) {
    for (BuildStep::Kind kind : kBuildStepKinds)
        if (element == buildStepElement(kind)) return kind;
    return std::nullopt;
}

/// The parts of a vector of expressions "x, y, z": split at the commas outside parentheses
/// (so "uniform(0, 1), 0, h" has three parts). Parts are trimmed.
inline std::vector<std::string> splitVector(const std::string& text) {
    std::vector<std::string> parts(1);
    int depth = 0;
    for (char c : text) {
        if (c == '(') ++depth;
        if (c == ')') --depth;
        if (c == ',' && depth == 0) {
            parts.emplace_back();
            continue;
        }
        parts.back() += c;
    }
    for (std::string& p : parts) {
        const auto a = p.find_first_not_of(" \t\n\r");
        const auto b = p.find_last_not_of(" \t\n\r");
        p = a == std::string::npos ? std::string() : p.substr(a, b - a + 1);
    }
    return parts;
}

}  // namespace plantarch::species_xml
