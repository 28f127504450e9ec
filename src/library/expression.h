#pragma once
// Arithmetic expressions of species build steps, e.g. "trunk_height / 0.05",
// "uniform(0, 360)", "90 + i * 360 / scaffold_count".
//
// Grammar (recursive descent, usual precedence, left to right):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | primary
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Names are variables (build parameters, `i`, `parent_i`) or the constant `pi`. Functions:
// uniform(min, max), normal(mean, stddev) (random draws from the caller's stream, made in
// reading order), min(a, b, ...), max(a, b, ...), floor(x), ceil(x), round(x), abs(x).
//
// Errors are plantarch::Error with the expression as value and the column in the message;
// the caller adds the file, line and attribute.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Random.h"

namespace plantarch::expr {

/// Value of `text` with the given variables; random functions draw from `rng`. Throws for a
/// syntax error, an unknown name, a bad argument, division by zero or a non-finite result.
double evaluate(std::string_view text, const std::map<std::string, double>& variables, Rng& rng);

/// Checks syntax, function names and argument counts, and that every variable is one of
/// `names`, without evaluating anything (no draws, no domain errors).
void check(std::string_view text, const std::vector<std::string>& names);

/// Names that cannot be variables: functions and constants.
const std::vector<std::string>& reservedNames();

}  // namespace plantarch::expr
