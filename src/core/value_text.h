#pragma once
// Parameter values as text, the way species files (and other XML files) write them:
//   float/double "0.025", "-1e-05"               (finite; shortest round-trip form on output)
//   RandomFloat  "20", "uniform(10, 30)", "normal(0, 5)", "weibull(1.5, 2)"
//   RandomInt    "3", "uniform(1, 4)", "discrete(2, 5, 11)"
//   unsigned/int "7", "-2"
//   bool         "true" or "false"
//   vec3         "0.2 0.25 0.05" (whitespace or commas between the three numbers)
//
// Parsers trim surrounding whitespace and reject anything else with a plantarch::Error whose
// message says what was expected and whose value is the offending text; the caller adds the
// file, line and parameter path.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Mesh.h"
#include "plantarch/Random.h"

namespace plantarch::text {

std::string_view trim(std::string_view s);
/// Trimmed, with each run of white space inside made one space.
std::string collapseSpaces(std::string_view s);

/// True when `s` is exactly one number of the type: an optional '+' or '-' (no '-' for the
/// unsigned types), digits, and for the floating-point types a fraction and exponent; finite.
/// No surrounding white space.
bool readNumber(std::string_view s, float& out);
bool readNumber(std::string_view s, double& out);
bool readNumber(std::string_view s, int& out);
bool readNumber(std::string_view s, unsigned& out);
bool readNumber(std::string_view s, std::uint64_t& out);

float parseFloat(std::string_view s);
double parseDouble(std::string_view s);
int parseInt(std::string_view s);
unsigned parseUnsigned(std::string_view s);
bool parseBool(std::string_view s);
vec3 parseVec3(std::string_view s);
RandomFloat parseRandomFloat(std::string_view s);
RandomInt parseRandomInt(std::string_view s);

/// The parsers above by the type they return, for code generic over the type: parse<T>(s).
struct Parsers {
    static void read(std::string_view s, float& m) { m = parseFloat(s); }
    static void read(std::string_view s, double& m) { m = parseDouble(s); }
    static void read(std::string_view s, int& m) { m = parseInt(s); }
    static void read(std::string_view s, unsigned& m) { m = parseUnsigned(s); }
    static void read(std::string_view s, bool& m) { m = parseBool(s); }
    static void read(std::string_view s, vec3& m) { m = parseVec3(s); }
    static void read(std::string_view s, RandomFloat& m) { m = parseRandomFloat(s); }
    static void read(std::string_view s, RandomInt& m) { m = parseRandomInt(s); }
};
template <class T>
T parse(std::string_view s) {
    T v{};
    Parsers::read(s, v);
    return v;
}

/// Shortest text that reads back to exactly the same value, in plain notation unless that is
/// more than two characters longer than with an exponent ("0.0001", "1000000", "1e-09").
std::string formatFloat(float v);
std::string formatDouble(double v);
std::string formatVec3(const vec3& v);
/// As RandomFloat::describe() with formatFloat() numbers; RandomInt::describe() is exact.
std::string formatRandomFloat(const RandomFloat& v);
inline std::string formatBool(bool b) {
    return b ? "true" : "false";
}

/// Labels, ids and names: letters, digits, '_' and '-' (no '.', which separates the parts of
/// a parameter path); not empty.
bool isLabel(std::string_view s);

/// The index of `s` (trimmed) in `choices`; else an Error "unknown value 'x'" with the closest
/// choice and the list of them.
std::size_t parseChoice(std::string_view s, const std::vector<std::string>& choices);

/// Edit distance counting a swap of neighbours as one edit (for "did you mean").
std::size_t editDistance(std::string_view a, std::string_view b);
/// The candidate closest to `word` when it is close enough to be a likely misspelling
/// (distance at most a third of the word's length, at least 1, at most 3), else "".
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);
/// "a, b, c"
std::string joinNames(const std::vector<std::string>& names);
/// "one of: a, b, c" ("none" for no names): the valid range of a choice.
std::string oneOf(const std::vector<std::string>& names);
/// "unknown <what> '<name>'<where>", with ", did you mean '...'?" when a candidate is close.
std::string unknownMessage(std::string_view what, std::string_view name,
                           const std::vector<std::string>& candidates, std::string_view where = "");

/// Appends `s` escaped for XML text or a quoted attribute: the five markup characters as
/// entities, and carriage returns, line feeds and tabs as character references (raw ones
/// would be normalized when read back).
void appendXmlEscaped(std::string& out, std::string_view s);
inline std::string xmlEscaped(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    appendXmlEscaped(out, s);
    return out;
}

}  // namespace plantarch::text
