#pragma once
// Pieces shared by the species reader and writer: the element names of the file format and
// how the table's map fields are spelled in XML.

#include <string>
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

/// How a map field is written: one child element per entry, with the key in an attribute
/// and the value in another attribute (valueAttribute set) or as the element's text.
struct MapSpelling {
    const char* element;
    const char* keyAttribute;
    const char* valueAttribute;  ///< nullptr: the value is the element text
};

/// Spelling of the table's map fields, by field name: child_shoot_types as
/// <type label="..." probability="..."/>, leaf_texture_file as <image leaflet="-1">f.png</image>,
/// other name->number maps as <param name="...">5</param>, other index->text maps as
/// <entry index="...">text</entry>.
inline MapSpelling mapSpelling(const std::string& field, bool integerKeys) {
    if (field == "child_shoot_types") return {"type", "label", "probability"};
    if (field == "leaf_texture_file") return {"image", "leaflet", nullptr};
    if (integerKeys) return {"entry", "index", nullptr};
    return {"param", "name", nullptr};
}

/// Attributes of the build steps, in the order they are written.
inline const std::vector<std::string>& buildStepAttributes(const std::string& kind) {
    static const std::vector<std::string> base = {"id",
                                                  "type",
                                                  "nodes",
                                                  "pitch",
                                                  "yaw",
                                                  "roll",
                                                  "radius",
                                                  "internode_length",
                                                  "internode_scale",
                                                  "leaf_scale",
                                                  "taper",
                                                  "leaves",
                                                  "vegetative_buds",
                                                  "floral_buds",
                                                  "apex"};
    static const std::vector<std::string> append = [] {
        std::vector<std::string> a = {"id", "parent"};
        a.insert(a.end(), base.begin() + 1, base.end());
        return a;
    }();
    static const std::vector<std::string> child = [] {
        std::vector<std::string> a = {"id", "parent", "node", "petiole", "repeat"};
        a.insert(a.end(), base.begin() + 1, base.end());
        return a;
    }();
    if (kind == "append") return append;
    if (kind == "child") return child;
    return base;
}

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

/// The BuildStep member an attribute is stored in.
inline std::string BuildStep::*buildStepMember(const std::string& attribute) {
    if (attribute == "id") return &BuildStep::id;
    if (attribute == "parent") return &BuildStep::parent;
    if (attribute == "type") return &BuildStep::shootType;
    if (attribute == "nodes") return &BuildStep::nodes;
    if (attribute == "node") return &BuildStep::parentNode;
    if (attribute == "petiole") return &BuildStep::petiole;
    if (attribute == "repeat") return &BuildStep::repeat;
    if (attribute == "pitch") return &BuildStep::pitch;
    if (attribute == "yaw") return &BuildStep::yaw;
    if (attribute == "roll") return &BuildStep::roll;
    if (attribute == "radius") return &BuildStep::radius;
    if (attribute == "internode_length") return &BuildStep::internodeLength;
    if (attribute == "internode_scale") return &BuildStep::internodeScale;
    if (attribute == "leaf_scale") return &BuildStep::leafScale;
    if (attribute == "taper") return &BuildStep::taper;
    if (attribute == "leaves") return &BuildStep::leaves;
    if (attribute == "vegetative_buds") return &BuildStep::vegetativeBuds;
    if (attribute == "floral_buds") return &BuildStep::floralBuds;
    if (attribute == "apex") return &BuildStep::apex;
    return nullptr;
}

/// Attributes whose value is true or false rather than an expression.
inline bool isFlagAttribute(const std::string& attribute) {
    return attribute == "leaves" || attribute == "vegetative_buds" || attribute == "floral_buds" ||
           attribute == "apex";
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

/// Attributes whose value is a name rather than an expression.
inline bool isNameAttribute(const std::string& attribute) {
    return attribute == "id" || attribute == "parent" || attribute == "type";
}

}  // namespace plantarch::species_xml
