#pragma once
// The parameter table as data: every field of a parameter struct with its declared unit,
// valid range, description and valid values, and its value in a given struct. For front ends
// that show parameters to people (`plantarch info`, docs/parameters.md, bindings); the
// library itself reads the table directly.
//
//   for (const ParameterInfo& p : parameterInfo(ShootParameters{}))
//       std::cout << p.path << " = " << p.value << " " << p.unit << "\n";

#include <string>
#include <vector>

#include "plantarch/NumberRange.h"
#include "plantarch/Parameters.h"

namespace plantarch {

/// What a field holds, and so how its value is written in a species file.
enum class ParameterKind {
    Number,             ///< "0.25"
    RandomNumber,       ///< a number or a distribution: "20", "uniform(10, 30)", "normal(0, 5)"
    WholeNumber,        ///< "7"
    RandomWholeNumber,  ///< "3", "uniform(1, 4)", "discrete(2, 5, 11)"
    Flag,               ///< "true" or "false"
    Triple,             ///< three numbers "0.2 0.25 0.05" (colours: RGB in 0 to 1)
    Text,               ///< any text (a file or a registered function name; empty: none)
    Choice,             ///< one of `choices`
    NumberMap,          ///< entries of a name and a number (see ParameterInfo::entry)
    TextMap,            ///< entries of a whole number and a text (see ParameterInfo::entry)
    Formula,            ///< a formula of named variables: "min(1, 0.5 + age / 10)"
    List,               ///< a list of elements (see ParameterInfo::entry), whose fields follow
};

/// One valid value of an enum-like field.
struct ParameterChoice {
    std::string name;
    std::string doc;
};

/// One field of the table and its value in the struct described.
struct ParameterInfo {
    std::string path;  ///< dotted path in the struct described: "phytomer.leaf.pitch"
    std::string name;  ///< the last part of the path, the element name in files
    std::string unit;  ///< "" when dimensionless
    std::string doc;
    ParameterKind kind = ParameterKind::Number;
    /// Valid range of every value the field can take (each component of a triple, each value
    /// of a number map); meaningful when hasRange().
    double min = 0.0;
    double max = 0.0;
    std::vector<ParameterChoice> choices;  ///< kind Choice: the valid values, in order
    /// Map kinds: how one entry is written, e.g. `<type label="NAME" probability="VALUE"/>`.
    std::string entry;
    bool probabilities = false;  ///< NumberMap: the values are probabilities summing to 1
    std::string value;           ///< the value as a species file writes it

    /// Whether min and max bound the value (numbers, triples, number maps).
    bool hasRange() const;
    /// The range (whole numbers for the whole-number kinds); meaningful when hasRange().
    NumberRange range() const;
    /// plantarch::rangeText(range()) ("0 to 1", ">= 0.001", "any finite number"), or ""
    /// without a range.
    std::string rangeText() const;
};

/// Every field of a shoot type, in the order files list them, paths relative to the
/// <shoot_type> element ("max_nodes", "phytomer.internode.pitch").
std::vector<ParameterInfo> parameterInfo(const ShootParameters& shoot);
/// Every field of <phenology>.
std::vector<ParameterInfo> parameterInfo(const PhenologyParameters& phenology);

/// The fields as JSON text, the one JSON form of ParameterInfo (the builder's species endpoint
/// and the Python module's parameterInfo() both give it): an array with, per field, the object
///   {"path", "name", "unit", "doc", "kind" (parameterKindText), "min", "max" (null without a
///    range or for no bound), "range" (rangeText()), "choices": [{"name", "doc"}], "entry",
///    "probabilities", "value"}
/// in the order of `fields`, keys in that order, on one line.
std::string parameterInfoJson(const std::vector<ParameterInfo>& fields);

/// "random number", "true or false", ...: the kind of value, as docs/species-format.md names
/// them (its section *Values* shows how each is written).
const char* parameterKindText(ParameterKind kind);

}  // namespace plantarch
