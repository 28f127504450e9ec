#pragma once
// The valid range of a number, and the one way plantarch states it: in error messages, species
// file comments, `plantarch info`, docs/parameters.md and the Python module's docstrings.
// Each table of declarations turns its own ranges into a NumberRange (params::FieldInfo::range,
// state::FieldInfo::range, ParameterInfo::range) and rangeText() words it.

#include <limits>
#include <string>

namespace plantarch {

/// The numbers from min to max. An infinite bound is no bound; an open bound excludes itself.
struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool whole = false;    ///< whole numbers only: bounds written as integers ("1000000000")
    bool openMin = false;  ///< min < value (else min <= value)
    bool openMax = false;  ///< value < max (else value <= max)
    /// The bounds are floats: written in a float's shortest form ("0.1", not the double
    /// 0.10000000149011612 the float 0.1 is).
    bool single = false;
};

/// The range for people: "0 to 1" (both ends included), "> 0 and <= 100" (an end excluded),
/// ">= 0.001", "< 90" (one bound), and with no bound "any finite number" ("any whole number").
/// Bounds in their shortest round-trip form (text::formatDouble, or text::formatFloat for
/// single), whole ranges' as integers.
std::string rangeText(const NumberRange& range);

}  // namespace plantarch
