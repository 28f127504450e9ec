// The library species against the reference system's numbers (tests/data/
// reference_parameters.tsv): every numeric parameter the reference gives a shoot type, its
// phenology and its build parameters must be in our species file with the same value (a
// constant exactly, a random value with the same distribution and bounds), or with the value
// the table gives for a deliberate difference together with its reason.
//
// The table is read and its values parsed here, independently of plantarch's own parsers, so
// a species file that drifts from the reference fails even when the reader, the writer and the
// rest of the test suite agree with it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "plantarch/ParameterTable.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

const std::string kTable =
    std::string(PLANTARCH_SOURCE_DIR) + "/tests/data/reference_parameters.tsv";

// ---- values ----------------------------------------------------------------------------

// A parameter value as the table writes it: a kind and its numbers.
struct Value {
    std::string kind;  // number, uniform, normal, weibull, discrete, vector, bool
    std::vector<double> numbers;
};

std::string describe(const Value& v) {
    std::ostringstream out;
    out.precision(9);
    if (v.kind == "number" || v.kind == "vector") {
        for (std::size_t i = 0; i < v.numbers.size(); ++i) out << (i ? " " : "") << v.numbers[i];
    } else if (v.kind == "bool") {
        out << (v.numbers.at(0) != 0 ? "true" : "false");
    } else {
        out << v.kind << "(";
        for (std::size_t i = 0; i < v.numbers.size(); ++i) out << (i ? ", " : "") << v.numbers[i];
        out << ")";
    }
    return out.str();
}

// Equal as the species file's floats: every number compared after rounding to float.
bool sameValue(const Value& a, const Value& b) {
    if (a.kind != b.kind || a.numbers.size() != b.numbers.size()) return false;
    for (std::size_t i = 0; i < a.numbers.size(); ++i)
        if (float(a.numbers[i]) != float(b.numbers[i])) return false;
    return true;
}

std::vector<double> numbersIn(const std::string& text, char separator) {
    std::vector<double> out;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, separator)) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        while (end && *end == ' ') ++end;
        if (end == item.c_str() || (end && *end)) {
            ADD_FAILURE() << "table: not a number: '" << item << "' in '" << text << "'";
            return {};
        }
        out.push_back(v);
    }
    return out;
}

Value parseValue(const std::string& text) {
    if (text == "true" || text == "false") return {"bool", {text == "true" ? 1.0 : 0.0}};
    const auto open = text.find('(');
    if (open != std::string::npos && text.back() == ')') {
        const std::string kind = text.substr(0, open);
        const std::vector<double> n = numbersIn(text.substr(open + 1, text.size() - open - 2), ',');
        if (kind != "uniform" && kind != "normal" && kind != "weibull" && kind != "discrete")
            ADD_FAILURE() << "table: unknown distribution '" << text << "'";
        return {kind, n};
    }
    std::vector<double> n = numbersIn(text, ' ');
    return {n.size() == 1 ? "number" : "vector", n};
}

// ---- our species' values -----------------------------------------------------------------

// Collects every numeric field of a parameter struct by its path in the parameter table.
struct Collector {
    std::map<std::string, Value>& out;
    std::string prefix;

    void put(const char* name, Value v) { out[prefix + name] = std::move(v); }

    void field(const params::FieldInfo& f, const RandomFloat& m) {
        switch (m.kind()) {
            case RandomFloat::Kind::Constant:
                put(f.name, {"number", {m.a()}});
                break;
            case RandomFloat::Kind::Uniform:
                put(f.name, {"uniform", {m.a(), m.b()}});
                break;
            case RandomFloat::Kind::Normal:
                put(f.name, {"normal", {m.a(), m.b()}});
                break;
            case RandomFloat::Kind::Weibull:
                put(f.name, {"weibull", {m.a(), m.b()}});
                break;
        }
    }
    void field(const params::FieldInfo& f, const RandomInt& m) {
        switch (m.kind()) {
            case RandomInt::Kind::Constant:
                put(f.name, {"number", {double(m.min())}});
                break;
            case RandomInt::Kind::Uniform:
                put(f.name, {"uniform", {double(m.min()), double(m.max())}});
                break;
            case RandomInt::Kind::Discrete:
                put(f.name,
                    {"discrete", std::vector<double>(m.values().begin(), m.values().end())});
                break;
        }
    }
    void field(const params::FieldInfo& f, const bool& m) {
        put(f.name, {"bool", {m ? 1.0 : 0.0}});
    }
    void field(const params::FieldInfo& f, const vec3& m) {
        put(f.name, {"vector", {m.x, m.y, m.z}});
    }
    template <class T>
    requires std::is_arithmetic_v<T>
    void field(const params::FieldInfo& f, const T& m) { put(f.name, {"number", {double(m)}}); }
    void field(const params::FieldInfo& f, const std::map<std::string, float>& m) {
        if (std::string(f.name) != "child_shoot_types") return;  // prototype shape parameters
        for (const auto& [label, p] : m) out[prefix + f.name + "." + label] = {"number", {p}};
    }
    template <class T>  // strings, choices, other maps, formulas: not numbers
    void field(const params::FieldInfo&, const T&) {}

    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) {
        Collector sub{out, prefix + name + "."};
        visit(sub);
    }
    template <class E, class Fn>  // node rules have no counterpart in the reference's numbers
    void list(const params::FieldInfo&, const char*, const std::vector<E>&, Fn&&) {}
};

// Parameters of one shoot type ("-": phenology and build parameters) by path.
std::map<std::string, Value> ourValues(const SpeciesModel& species, const std::string& type) {
    std::map<std::string, Value> out;
    if (type == "-") {
        PhenologyParameters phenology = species.phenology;
        Collector c{out, "phenology."};
        params::describeParameters(phenology, c);
        for (const BuildParameter& b : species.buildParameters) {
            out["build." + b.name + ".default"] = {"number", {b.value}};
            out["build." + b.name + ".min"] = {"number", {b.min}};
            out["build." + b.name + ".max"] = {"number", {b.max}};
        }
        return out;
    }
    Collector c{out, ""};
    params::describeParameters(species.shootTypes.at(type), c);
    return out;
}

// ---- the table -----------------------------------------------------------------------------

struct Row {
    int line;
    std::string species, type, parameter, reference, expected, reason;
};

std::vector<Row> readTable() {
    std::ifstream in(kTable);
    EXPECT_TRUE(in) << "cannot read " << kTable;
    std::vector<Row> rows;
    std::string line;
    bool header = true;
    for (int n = 1; std::getline(in, line); ++n) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        std::string cell;
        std::istringstream fields(line);
        while (std::getline(fields, cell, '\t')) cells.push_back(cell);
        if (cells.size() == 5) cells.emplace_back();  // empty reason
        if (cells.size() != 6) {
            ADD_FAILURE() << kTable << ":" << n << ": expected 6 tab-separated columns";
            continue;
        }
        if (header) {  // the column names
            header = false;
            continue;
        }
        rows.push_back({n, cells[0], cells[1], cells[2], cells[3], cells[4], cells[5]});
    }
    return rows;
}

struct Table {
    std::map<std::string, std::string> defaults;  // parameter -> expected
    // species -> shoot type -> parameter -> row
    std::map<std::string, std::map<std::string, std::map<std::string, Row>>> rows;
};

Table tableByType(const std::vector<Row>& rows) {
    Table t;
    for (const Row& r : rows) {
        if (r.species == "*") {
            t.defaults[r.parameter] = r.expected;
            continue;
        }
        auto& type = t.rows[r.species][r.type];
        EXPECT_TRUE(type.emplace(r.parameter, r).second)
            << "table line " << r.line << ": " << r.parameter << " listed twice";
    }
    return t;
}

// What the table expects of one of our shoot types: the defaults, then the reference shoot
// type's rows, then (for a type standing for another) the type's own rows.
std::map<std::string, std::string> expectedFor(const Table& t, const std::string& species,
                                               const std::string& type, std::string& problem) {
    std::map<std::string, std::string> expected;
    const auto& types = t.rows.at(species);
    const auto own = types.find(type);
    if (type == "-") {  // phenology and build parameters
        if (own != types.end())
            for (const auto& [p, row] : own->second) expected[p] = row.expected;
        return expected;
    }
    std::string base = type;
    if (own != types.end() && own->second.count("reference_shoot_type"))
        base = own->second.at("reference_shoot_type").expected;
    const auto ref = types.find(base);
    if (ref == types.end()) {
        problem = "shoot type '" + type + "' has no reference shoot type in the table";
        return expected;
    }
    expected = t.defaults;
    for (const auto& [p, row] : ref->second) expected[p] = row.expected;
    if (base != type)
        for (const auto& [p, row] : own->second)
            if (p != "reference_shoot_type") expected[p] = row.expected;
    return expected;
}

// ---- tests ---------------------------------------------------------------------------------

// The table itself: a row whose expected value is not the reference's says why, and a row
// with a reason differs from the reference (a reason left behind by a fix is stale).
TEST(ConformanceSpecies, EveryDepartureInTheTableHasAReason) {
    const std::vector<Row> rows = readTable();
    ASSERT_GT(rows.size(), 3000u);
    for (const Row& r : rows) {
        if (r.parameter == "reference_shoot_type") {
            EXPECT_FALSE(r.reason.empty()) << "line " << r.line << ": say what the type stands for";
            continue;
        }
        const bool same = sameValue(parseValue(r.reference), parseValue(r.expected));
        if (same)
            EXPECT_TRUE(r.reason.empty())
                << "line " << r.line << ": " << r.species << " " << r.type << " " << r.parameter
                << " agrees with the reference but gives a reason";
        else
            EXPECT_FALSE(r.reason.empty())
                << "line " << r.line << ": " << r.species << " " << r.type << " " << r.parameter
                << ": expected " << r.expected << ", reference " << r.reference
                << ", and no reason";
    }
}

TEST(ConformanceSpecies, LibraryParametersAreTheReferenceNumbers) {
    const Table table = tableByType(readTable());
    const std::vector<std::string> library = listSpecies();
    ASSERT_EQ(library.size(), 30u);
    std::set<std::string> tableSpecies;
    for (const auto& [s, types] : table.rows) tableSpecies.insert(s);
    EXPECT_EQ(tableSpecies, std::set<std::string>(library.begin(), library.end()));

    std::vector<std::string> differences;
    std::size_t compared = 0;
    for (const std::string& name : library) {
        if (!table.rows.count(name)) continue;
        const SpeciesModel species = loadSpecies(name);
        std::set<std::string> ours{"-"};
        for (const auto& [label, params] : species.shootTypes) ours.insert(label);
        // Every reference shoot type is one of ours.
        for (const auto& [type, rows] : table.rows.at(name))
            if (!ours.count(type)) differences.push_back(name + ": no shoot type '" + type + "'");
        for (const std::string& type : ours) {
            std::string problem;
            const std::map<std::string, std::string> expected =
                expectedFor(table, name, type, problem);
            if (!problem.empty()) {
                differences.push_back(name + ": " + problem);
                continue;
            }
            const std::map<std::string, Value> values = ourValues(species, type);
            for (const auto& [path, text] : expected) {
                const auto it = values.find(path);
                const bool child = path.rfind("child_shoot_types.", 0) == 0;
                if (it == values.end()) {
                    differences.push_back(
                        name + " " + type + " " + path +
                        (child ? ": no such child type" : ": not a parameter of plantarch"));
                    continue;
                }
                ++compared;
                const Value want = parseValue(text);
                if (!sameValue(it->second, want))
                    differences.push_back(name + " " + type + " " + path + ": " +
                                          describe(it->second) + ", expected " + text);
            }
            // Child types the reference does not have.
            for (const auto& [path, v] : values)
                if (path.rfind("child_shoot_types.", 0) == 0 && !expected.count(path))
                    differences.push_back(name + " " + type + " " + path +
                                          ": a child type the reference does not have");
        }
    }
    std::string list;
    for (const std::string& d : differences) list += "\n  " + d;
    EXPECT_TRUE(differences.empty()) << differences.size() << " differences:" << list;
    EXPECT_GT(compared, 5000u);  // every shoot type with every shared parameter
}

}  // namespace
