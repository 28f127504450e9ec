// Build-step expressions (see expression.h), evaluated as plantarch::Formula in double
// precision with random draws allowed.

#include "library/expression.h"

#include "plantarch/Formula.h"

namespace plantarch::expr {

double evaluate(std::string_view text, const std::map<std::string, double>& variables, Rng& rng) {
    std::vector<std::string> names;
    std::vector<double> values;
    names.reserve(variables.size());
    values.reserve(variables.size());
    for (const auto& [name, value] : variables) {
        names.push_back(name);
        values.push_back(value);
    }
    return Formula(text, std::move(names), true).evaluate(values, &rng);
}

void check(std::string_view text, const std::vector<std::string>& names) {
    Formula(text, names, true);
}

const std::vector<std::string>& reservedNames() {
    return Formula::reservedNames();
}

}  // namespace plantarch::expr
