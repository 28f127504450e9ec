#pragma once
// plantarch::Formula: an arithmetic formula of named variables, parsed once and evaluated many
// times, e.g. "min(1, 0.6 + 0.4 * age / 8)". Species files use formulas in build steps and in
// node rules (docs/species-format.md).
//
// Grammar (usual precedence, left to right):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | primary
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Names are the variables the formula was compiled with, or the constant `pi`. Functions:
// min(a, b, ...), max(a, b, ...), floor(x), ceil(x), round(x), abs(x), and, where the user of
// the formula allows random draws, uniform(min, max) and normal(mean, stddev), drawn from the
// caller's stream in reading order.
//
// A formula evaluates in double or in float precision. In float precision every number,
// variable and intermediate result is a float and the operations run in reading order, so
// "0.6 + 0.4 * age / 8" gives the same bits as the C++ expression 0.6f + 0.4f * age / 8.0f.

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Random.h"

namespace plantarch {

class Formula {
public:
    /// The empty formula: not set (see empty()); evaluating it is an error.
    Formula() = default;
    /// Parses `text` with the given variable names. Throws plantarch::Error for a syntax error,
    /// an unknown name or function, a wrong argument count, or a random function when
    /// `allowRandom` is false; the message gives the column and the value is the text.
    Formula(std::string_view text, std::vector<std::string> variables, bool allowRandom = false);

    bool empty() const { return program_ == nullptr; }
    const std::string& text() const { return text_; }
    /// Variable names, in the order evaluate() takes their values.
    const std::vector<std::string>& variables() const;

    /// The value for variable values given in the order of variables(). `rng` is needed only
    /// by a formula with random functions. Throws plantarch::Error on division by zero, a bad
    /// random argument or a non-finite result.
    double evaluate(std::span<const double> values, Rng* rng = nullptr) const;
    float evaluateFloat(std::span<const float> values) const;

    /// Formulas are equal when their texts are.
    bool operator==(const Formula& other) const { return text_ == other.text_; }

    /// Names that cannot be variables: functions and constants.
    static const std::vector<std::string>& reservedNames();

    struct Program;

private:
    void checkCall(std::size_t valueCount) const;

    std::string text_;
    std::shared_ptr<const Program> program_;
};

}  // namespace plantarch
