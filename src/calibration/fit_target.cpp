// Reading fit target files (JSON) strictly, each error one line naming the file, the line,
// the key (a JSON pointer without its leading '/'), the value and the valid range; and
// checking a target against the species it fits.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "calibration/json_lines.h"
#include "core/input_file.h"
#include "core/value_text.h"
#include "plantarch/Calibration.h"
#include "plantarch/Error.h"
#include "plantarch/ParameterInfo.h"
#include "project/json_document.h"
#include "project/json_scan.h"

namespace plantarch {

namespace fit {

namespace {

using json = nlohmann::json;

inline constexpr io::InputKind kTargetFile{"fit target file", 16 * io::kMiB};
inline constexpr int kTargetVersion = 1;
inline constexpr std::size_t kMaxAges = 100;
inline constexpr double kMaxAge = 100000.0;

// The value as a person reads it: JSON text, cut short.
std::string shownValue(const json& v) {
    if (v.is_number_float() && std::isfinite(v.get<double>()) &&
        v.get<double>() == std::floor(v.get<double>()) && std::fabs(v.get<double>()) < 1e15)
        return std::to_string(std::int64_t(v.get<double>()));
    std::string text = v.is_structured() ? (v.is_array() ? "[...]" : "{...}")
                                         : v.dump(-1, ' ', false, json::error_handler_t::replace);
    return project::printable(text, 60);
}

class TargetReader {
public:
    TargetReader(std::string file, const JSONLines& lines)
        : file_(std::move(file)), lines_(lines) {}

    [[noreturn]] void fail(const std::string& field, const std::string& message,
                           const json* value = nullptr, const std::string& range = "") const {
        throw Error(message, {.file = file_,
                              .line = lines_.line(field),
                              .parameter = project::printable(field, 160),
                              .value = value ? shownValue(*value) : "",
                              .validRange = range});
    }

    void object(const json& j, const std::string& field,
                const std::vector<std::string>& known) const {
        if (!j.is_object()) fail(field, "expected an object {...}", field.empty() ? nullptr : &j);
        for (const auto& [key, value] : j.items()) {
            if (std::find(known.begin(), known.end(), key) != known.end()) continue;
            const std::string near = text::closestMatch(key, known);
            fail(join(field, key),
                 "unknown key" + (near.empty() ? "" : ", did you mean '" + near + "'?"), nullptr,
                 text::oneOf(known));
        }
    }

    double number(const json& j, const std::string& field, const NumberRange& r) const {
        const std::string range = rangeText(r);
        if (!j.is_number())
            fail(field, r.whole ? "expected a whole number" : "expected a number", &j, range);
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(field, "expected a finite number", &j, range);
        if (r.whole && v != std::floor(v)) fail(field, "expected a whole number", &j, range);
        if (v < r.min || v > r.max || (r.openMin && v == r.min) || (r.openMax && v == r.max))
            fail(field, "out of range", &j, range);
        return v;
    }

    std::string string(const json& j, const std::string& field, const std::string& range) const {
        if (!j.is_string()) fail(field, "expected a text in quotes", &j, range);
        std::string s = j.get<std::string>();
        if (s.empty()) fail(field, "empty", &j, range);
        if (std::any_of(s.begin(), s.end(), [](char c) { return (unsigned char)c < 0x20; }))
            fail(field, "a control character", &j, range);
        return s;
    }

    const json& required(const json& j, const std::string& field, const char* key,
                         const std::string& range) const {
        if (!j.contains(key)) fail(join(field, key), "missing", nullptr, range);
        return j[key];
    }

    int line(const std::string& field) const { return lines_.line(field); }

    static std::string join(const std::string& field, const std::string& key) {
        return field.empty() ? key : field + "/" + key;
    }

private:
    std::string file_;
    const JSONLines& lines_;
};

NumberRange closed(double lo, double hi, bool whole = false) {
    return {.min = lo, .max = hi, .whole = whole};
}
NumberRange positive(double hi = std::numeric_limits<double>::infinity()) {
    return {.min = 0.0, .max = hi, .openMin = true};
}
const NumberRange kAnyNumber{};

// Text -> JSON (project/json_document.h): a number beyond a double's range is an error.
json parseTarget(const std::string& text, const std::string& file) {
    return project::parseJSONDocument(text, file, 16, nullptr, "key");
}

std::optional<FitStatistic> statisticNamed(const std::string& name) {
    for (FitStatistic s : fitStatistics())
        if (name == fitStatisticName(s)) return s;
    return std::nullopt;
}

// A measurement {"value": v, "sd": s, "weight": w} ("values": [9 fractions] for the histogram).
FitMeasurement readMeasurement(const TargetReader& r, const json& j, const std::string& at,
                               FitStatistic s) {
    const bool histogram = s == FitStatistic::LeafInclinationHistogram;
    const bool ranked = s == FitStatistic::InternodeLength;
    std::vector<std::string> keys = {histogram ? "values" : "value", "sd", "weight"};
    if (ranked) keys.push_back("rank");
    r.object(j, at, keys);
    FitMeasurement m;
    m.statistic = s;
    m.line = r.line(at);
    const bool angle = s == FitStatistic::LeafInclination;
    const NumberRange valueRange = histogram ? closed(0.0, 1.0)
                                   : angle   ? closed(0.0, 90.0)
                                             : closed(0.0, 1e6);
    if (histogram) {
        const json& v = r.required(j, at, "values", "9 fractions of leaf area, 0 to 1 each");
        const std::string field = at + "/values";
        if (!v.is_array() || v.size() != 9)
            r.fail(field, "expected 9 fractions [0-10, 10-20, ... 80-90 degrees]", &v,
                   "9 numbers 0 to 1 summing to 1");
        double sum = 0.0;
        for (std::size_t i = 0; i < 9; ++i) {
            m.values.push_back(r.number(v[i], field + "/" + std::to_string(i), valueRange));
            sum += m.values.back();
        }
        if (std::fabs(sum - 1.0) > 0.01)
            r.fail(field, "the fractions sum to " + text::formatDouble(sum), nullptr,
                   "a sum of 1 (within 0.01)");
    } else {
        m.values.push_back(
            r.number(r.required(j, at, "value", rangeText(valueRange)), at + "/value", valueRange));
    }
    if (j.contains("sd")) m.sd = r.number(j["sd"], at + "/sd", positive(1e6));
    if (j.contains("weight")) m.weight = r.number(j["weight"], at + "/weight", closed(0.0, 1e6));
    if (!m.sd)
        for (double v : m.values)
            if (v == 0.0)
                r.fail(at + (histogram ? "/values" : "/value"),
                       "a value of 0 needs an sd (the residual is relative to it without one)",
                       nullptr, "an \"sd\" > 0");
    if (ranked) {
        const NumberRange ranks = closed(0.0, 100.0, true);
        m.rank =
            unsigned(r.number(r.required(j, at, "rank", rangeText(ranks)), at + "/rank", ranks));
    }
    return m;
}

FitAge readAge(const TargetReader& r, const json& j, const std::string& at) {
    std::vector<std::string> keys = {"age"};
    for (FitStatistic s : fitStatistics()) keys.push_back(fitStatisticName(s));
    r.object(j, at, keys);
    FitAge a;
    a.line = r.line(at);
    const NumberRange ages = positive(kMaxAge);
    a.age = r.number(r.required(j, at, "age", "days " + rangeText(ages)), at + "/age", ages);
    for (const auto& [key, value] : j.items()) {
        if (key == "age") continue;
        const FitStatistic s = *statisticNamed(key);
        const std::string field = at + "/" + key;
        if (s == FitStatistic::InternodeLength) {
            if (!value.is_array() || value.empty())
                r.fail(field, "expected a list [{\"rank\": 0, \"value\": ..., \"sd\": ...}, ...]",
                       &value);
            std::set<unsigned> ranks;
            for (std::size_t i = 0; i < value.size(); ++i) {
                const std::string item = field + "/" + std::to_string(i);
                a.measurements.push_back(readMeasurement(r, value[i], item, s));
                if (!ranks.insert(a.measurements.back().rank).second)
                    r.fail(item + "/rank", "this rank is measured twice", &value[i]["rank"],
                           "each rank once per age");
            }
        } else {
            a.measurements.push_back(readMeasurement(r, value, field, s));
        }
    }
    if (a.measurements.empty())
        r.fail(at, "no measurement at this age", nullptr,
               "at least one of: " + text::joinNames({keys.begin() + 1, keys.end()}));
    return a;
}

FitPointCloud readCloud(const TargetReader& r, const json& j, const std::string& folder) {
    const std::string at = "point_cloud";
    r.object(j, at, {"file", "age", "points", "scale", "weight", "offset"});
    FitPointCloud c;
    c.line = r.line(at);
    c.file = r.string(r.required(j, at, "file", "a .ply, .xyz, .txt or .pts file"), at + "/file",
                      "a .ply, .xyz, .txt or .pts file");
    const std::filesystem::path p(c.file);
    c.path = p.is_absolute() || folder.empty() || folder == "."
                 ? c.file
                 : (std::filesystem::path(folder) / p).string();
    const NumberRange ages = positive(kMaxAge);
    c.age = r.number(r.required(j, at, "age", "days " + rangeText(ages)), at + "/age", ages);
    if (j.contains("points"))
        c.points = unsigned(r.number(j["points"], at + "/points", closed(10, 200000, true)));
    if (j.contains("scale")) c.scale = r.number(j["scale"], at + "/scale", positive(100.0));
    if (j.contains("weight")) c.weight = r.number(j["weight"], at + "/weight", closed(0.0, 1e6));
    if (j.contains("offset")) {
        const json& o = j["offset"];
        if (!o.is_array() || o.size() != 3) r.fail(at + "/offset", "expected [x, y, z]", &o);
        for (int i = 0; i < 3; ++i)
            c.offset[i] =
                float(r.number(o[i], at + "/offset/" + std::to_string(i), closed(-1e6, 1e6)));
    }
    return c;
}

FitSkeleton readSkeletonTarget(const TargetReader& r, const json& j, const std::string& folder) {
    const std::string at = "skeleton";
    r.object(j, at, {"file", "age", "scale", "weight", "offset"});
    FitSkeleton k;
    k.line = r.line(at);
    const std::string files = "a skeleton file: .csv, .json or .mtg";
    k.file = r.string(r.required(j, at, "file", files), at + "/file", files);
    const std::filesystem::path p(k.file);
    k.path = p.is_absolute() || folder.empty() || folder == "."
                 ? k.file
                 : (std::filesystem::path(folder) / p).string();
    const NumberRange ages = positive(kMaxAge);
    k.age = r.number(r.required(j, at, "age", "days " + rangeText(ages)), at + "/age", ages);
    if (j.contains("scale")) k.scale = r.number(j["scale"], at + "/scale", positive(100.0));
    if (j.contains("weight")) k.weight = r.number(j["weight"], at + "/weight", closed(0.0, 1e6));
    if (j.contains("offset")) {
        const json& o = j["offset"];
        if (!o.is_array() || o.size() != 3) r.fail(at + "/offset", "expected [x, y, z]", &o);
        for (int i = 0; i < 3; ++i)
            k.offset[i] =
                float(r.number(o[i], at + "/offset/" + std::to_string(i), closed(-1e6, 1e6)));
    }
    return k;
}

FitTarget readTarget(const TargetReader& r, const json& j, const std::string& file,
                     const std::string& folder) {
    r.object(
        j, "",
        {"plantarch_fit", "parameters", "seeds", "optimizer", "ages", "point_cloud", "skeleton"});
    if (!j.contains("plantarch_fit"))
        r.fail("plantarch_fit", "not a plantarch fit target: no \"plantarch_fit\": 1", nullptr,
               "1");
    const json& version = j["plantarch_fit"];
    if (!version.is_number_integer() || version.get<std::int64_t>() != kTargetVersion)
        r.fail("plantarch_fit", "unsupported target version", &version, "1");
    FitTarget t;
    t.file = file;

    const json& params = r.required(j, "", "parameters", "a list of parameters to fit");
    if (!params.is_array() || params.empty() || params.size() > kMaxFitParameters)
        r.fail("parameters",
               params.is_array()
                   ? "expected 1 to " + std::to_string(kMaxFitParameters) + " parameters"
                   : "expected a list [{\"path\": ..., \"lower\": ..., \"upper\": "
                     "...}, ...]",
               &params, "1 to " + std::to_string(kMaxFitParameters) + " parameters");
    std::set<std::string> paths;
    for (std::size_t i = 0; i < params.size(); ++i) {
        const std::string at = "parameters/" + std::to_string(i);
        const json& p = params[i];
        r.object(p, at, {"path", "lower", "upper", "start"});
        FitParameter fp;
        fp.line = r.line(at);
        fp.path = r.string(r.required(p, at, "path", "a parameter path"), at + "/path",
                           "a parameter path, e.g. shoot_types.LABEL.internode_length_max");
        fp.lower =
            r.number(r.required(p, at, "lower", "a finite number"), at + "/lower", kAnyNumber);
        fp.upper =
            r.number(r.required(p, at, "upper", "a finite number"), at + "/upper", kAnyNumber);
        if (!(fp.lower < fp.upper))
            r.fail(at + "/upper", "not above the lower bound", &p["upper"],
                   "> " + text::formatDouble(fp.lower));
        if (p.contains("start"))
            fp.start = r.number(p["start"], at + "/start", closed(fp.lower, fp.upper));
        if (!paths.insert(fp.path).second)
            r.fail(at + "/path", "this parameter is fitted twice", &p["path"], "each path once");
        t.parameters.push_back(fp);
    }

    if (j.contains("seeds")) {
        const json& s = j["seeds"];
        if (!s.is_array() || s.empty() || s.size() > kMaxFitSeeds)
            r.fail("seeds", "expected a list of 1 to " + std::to_string(kMaxFitSeeds) + " seeds",
                   &s, "1 to " + std::to_string(kMaxFitSeeds) + " whole numbers");
        t.seeds.clear();
        std::set<std::uint64_t> seen;
        for (std::size_t i = 0; i < s.size(); ++i) {
            const std::string at = "seeds/" + std::to_string(i);
            const double v = r.number(s[i], at, closed(0, 9007199254740991.0, true));
            if (!seen.insert(std::uint64_t(v)).second)
                r.fail(at, "this seed is given twice", &s[i], "each seed once");
            t.seeds.push_back(std::uint64_t(v));
        }
    }

    if (j.contains("optimizer")) {
        const json& o = j["optimizer"];
        r.object(o, "optimizer", {"algorithm", "max_evaluations", "tolerance"});
        if (o.contains("algorithm")) {
            const std::vector<std::string> names = {"bobyqa", "subplex", "nelder-mead", "cobyla"};
            const std::string a =
                r.string(o["algorithm"], "optimizer/algorithm", text::oneOf(names));
            const auto it = std::find(names.begin(), names.end(), a);
            if (it == names.end()) {
                const std::string near = text::closestMatch(a, names);
                r.fail("optimizer/algorithm",
                       "unknown algorithm" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                       &o["algorithm"], text::oneOf(names));
            }
            t.algorithm = FitAlgorithm(it - names.begin());
        }
        if (o.contains("max_evaluations"))
            t.maxEvaluations = unsigned(r.number(o["max_evaluations"], "optimizer/max_evaluations",
                                                 closed(1, kMaxFitEvaluations, true)));
        if (o.contains("tolerance"))
            t.tolerance = r.number(o["tolerance"], "optimizer/tolerance", closed(1e-12, 0.5));
    }

    if (j.contains("ages")) {
        const json& a = j["ages"];
        if (!a.is_array() || a.size() > kMaxAges)
            r.fail("ages", "expected a list of ages [{\"age\": ..., \"height\": ...}, ...]", &a,
                   "at most " + std::to_string(kMaxAges) + " ages");
        std::set<double> seen;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const std::string at = "ages/" + std::to_string(i);
            t.ages.push_back(readAge(r, a[i], at));
            if (!seen.insert(t.ages.back().age).second)
                r.fail(at + "/age", "this age is given twice", &a[i]["age"],
                       "each age once (its measurements together)");
        }
    }
    if (j.contains("point_cloud") && !j["point_cloud"].is_null())
        t.pointCloud = readCloud(r, j["point_cloud"], folder);
    if (j.contains("skeleton") && !j["skeleton"].is_null())
        t.skeleton = readSkeletonTarget(r, j["skeleton"], folder);
    if (t.ages.empty() && !t.pointCloud && !t.skeleton)
        r.fail("ages", "nothing to fit to", nullptr,
               "measurements at one age at least (\"ages\"), a \"point_cloud\" or a "
               "\"skeleton\"");
    return t;
}

}  // namespace

}  // namespace fit

const char* fitStatisticName(FitStatistic s) {
    switch (s) {
        case FitStatistic::Height:
            return "height";
        case FitStatistic::LeafArea:
            return "leaf_area";
        case FitStatistic::Leaves:
            return "leaves";
        case FitStatistic::Shoots:
            return "shoots";
        case FitStatistic::Branches:
            return "branches";
        case FitStatistic::MainNodes:
            return "main_nodes";
        case FitStatistic::WidthX:
            return "width_x";
        case FitStatistic::WidthY:
            return "width_y";
        case FitStatistic::WidthLong:
            return "width_long";
        case FitStatistic::WidthShort:
            return "width_short";
        case FitStatistic::InternodeLength:
            return "internode_length";
        case FitStatistic::LeafInclination:
            return "leaf_inclination";
        case FitStatistic::LeafInclinationHistogram:
            return "leaf_inclination_histogram";
    }
    return "?";
}

const std::vector<FitStatistic>& fitStatistics() {
    static const std::vector<FitStatistic> all = {FitStatistic::Height,
                                                  FitStatistic::LeafArea,
                                                  FitStatistic::Leaves,
                                                  FitStatistic::Shoots,
                                                  FitStatistic::Branches,
                                                  FitStatistic::MainNodes,
                                                  FitStatistic::WidthX,
                                                  FitStatistic::WidthY,
                                                  FitStatistic::WidthLong,
                                                  FitStatistic::WidthShort,
                                                  FitStatistic::InternodeLength,
                                                  FitStatistic::LeafInclination,
                                                  FitStatistic::LeafInclinationHistogram};
    return all;
}

const char* fitAlgorithmName(FitAlgorithm a) {
    switch (a) {
        case FitAlgorithm::Bobyqa:
            return "bobyqa";
        case FitAlgorithm::Subplex:
            return "subplex";
        case FitAlgorithm::NelderMead:
            return "nelder-mead";
        case FitAlgorithm::Cobyla:
            return "cobyla";
    }
    return "?";
}

FitTarget readFitTargetString(const std::string& text, const std::string& nameForErrors,
                              const std::string& folder) {
    const std::string file = nameForErrors.empty() ? "fit target" : nameForErrors;
    const fit::JSONLines lines(text);
    const nlohmann::json j = fit::parseTarget(text, file);
    const fit::TargetReader r(file, lines);
    return fit::readTarget(r, j, file, folder);
}

FitTarget readFitTargetFile(const std::string& path) {
    const std::string text = io::readWholeFile(path, fit::kTargetFile);
    const std::string folder = std::filesystem::path(path).parent_path().string();
    return readFitTargetString(text, path, folder.empty() ? "." : folder);
}

namespace fit {

namespace {

// The field a parameter path names, with the kind and range it holds.
struct FieldOf {
    ParameterKind kind = ParameterKind::Number;
    NumberRange range;
    std::string value;  ///< as the species holds it
};

FieldOf fieldOf(const SpeciesModel& species, const std::string& key, const Error& where) {
    const auto fail = [&](const std::string& message, const std::string& range) {
        throw Error(message, {.file = where.file(),
                              .line = where.line(),
                              .parameter = where.parameter().empty() ? key : where.parameter(),
                              .value = where.value(),
                              .validRange = range});
    };
    std::vector<std::string> parts;
    for (std::size_t a = 0, b; a <= key.size(); a = b + 1) {
        b = key.find('.', a);
        if (b == std::string::npos) b = key.size();
        parts.push_back(key.substr(a, b - a));
    }
    const std::string forms = "shoot_types.LABEL.PATH, phenology.PATH, build_parameters.NAME";
    if (parts.size() == 2 && parts[0] == "build_parameters") {
        std::vector<std::string> names;
        for (const BuildParameter& p : species.buildParameters) {
            if (p.name == parts[1])
                return {ParameterKind::Number,
                        {.min = p.min, .max = p.max},
                        text::formatFloat(p.value)};
            names.push_back(p.name);
        }
        fail(text::unknownMessage("build parameter", parts[1], names, " in " + species.name),
             text::oneOf(names));
    }
    std::vector<ParameterInfo> fields;
    std::string path;
    if (parts.size() >= 3 && parts[0] == "shoot_types") {
        const auto type = species.shootTypes.find(parts[1]);
        if (type == species.shootTypes.end()) {
            std::vector<std::string> labels;
            for (const auto& [l, p] : species.shootTypes) labels.push_back(l);
            fail(text::unknownMessage("shoot type", parts[1], labels, " in " + species.name),
                 text::oneOf(labels));
        }
        fields = parameterInfo(type->second);
        path = key.substr(parts[0].size() + parts[1].size() + 2);
    } else if (parts.size() >= 2 && parts[0] == "phenology") {
        fields = parameterInfo(species.phenology);
        path = key.substr(parts[0].size() + 1);
    } else {
        fail("unknown parameter group", forms);
    }
    std::vector<std::string> paths;
    for (const ParameterInfo& f : fields) {
        paths.push_back(f.path);
        if (f.path != path) continue;
        if (f.kind != ParameterKind::Number && f.kind != ParameterKind::RandomNumber &&
            f.kind != ParameterKind::WholeNumber && f.kind != ParameterKind::RandomWholeNumber)
            fail(std::string("not a number (it holds ") + parameterKindText(f.kind) +
                     "): it cannot be fitted",
                 "a field of one number");
        return {f.kind, f.range(), f.value};
    }
    throw Error(text::unknownMessage("parameter", path, paths),
                {.file = where.file(),
                 .line = where.line(),
                 .parameter = where.parameter().empty() ? key : where.parameter(),
                 .value = where.value(),
                 .validRange = "a field of the species (plantarch info --parameters)"});
}

}  // namespace

// The canonical form of a target's parameter path: "LABEL.PATH" of a shoot type becomes
// "shoot_types.LABEL.PATH".
std::string canonicalPath(const SpeciesModel& species, const std::string& path) {
    const auto dot = path.find('.');
    if (dot == std::string::npos) return path;
    const std::string first = path.substr(0, dot);
    if (first != "shoot_types" && first != "phenology" && first != "build_parameters" &&
        species.shootTypes.count(first))
        return "shoot_types." + path;
    return path;
}

// Whether `kind` holds whole numbers.
bool wholeKind(const SpeciesModel& species, const std::string& path) {
    const FieldOf f = fieldOf(species, canonicalPath(species, path), Error(""));
    return f.kind == ParameterKind::WholeNumber || f.kind == ParameterKind::RandomWholeNumber;
}

// The species' own value of a parameter (checked by checkFitTarget).
double speciesValue(const SpeciesModel& species, const std::string& path) {
    const FieldOf f = fieldOf(species, canonicalPath(species, path), Error(""));
    double v = 0.0;
    std::from_chars(f.value.data(), f.value.data() + f.value.size(), v);
    return v;
}

}  // namespace fit

void checkFitTarget(const SpeciesModel& species, const FitTarget& target) {
    for (std::size_t i = 0; i < target.parameters.size(); ++i) {
        const FitParameter& p = target.parameters[i];
        const std::string key = fit::canonicalPath(species, p.path);
        const std::string field = "parameters/" + std::to_string(i);
        const Error where(
            "",
            {.file = target.file, .line = p.line, .parameter = field + "/path", .value = p.path});
        const fit::FieldOf f = fit::fieldOf(species, key, where);
        const auto fail = [&](const std::string& at, const std::string& message,
                              const std::string& value, const std::string& range) {
            throw Error(message, {.file = target.file,
                                  .line = p.line,
                                  .parameter = field + at,
                                  .value = value,
                                  .validRange = range});
        };
        double v = 0.0;
        const char* end = f.value.data() + f.value.size();
        const auto [used, ec] = std::from_chars(f.value.data(), end, v);
        if (ec != std::errc() || used != end)
            fail("/path",
                 "the species holds a distribution there (" + f.value + "), not one number", p.path,
                 "a field holding one number (write one in the species file to fit it)");
        const bool whole =
            f.kind == ParameterKind::WholeNumber || f.kind == ParameterKind::RandomWholeNumber;
        const NumberRange& r = f.range;
        const auto outside = [&](double x) {
            return x < r.min || x > r.max || (r.openMin && x == r.min) || (r.openMax && x == r.max);
        };
        if (outside(p.lower))
            fail("/lower", "outside the valid range of " + key, text::formatDouble(p.lower),
                 rangeText(r));
        if (outside(p.upper))
            fail("/upper", "outside the valid range of " + key, text::formatDouble(p.upper),
                 rangeText(r));
        if (whole && std::floor(p.upper) - std::ceil(p.lower) < 1.0)
            fail("", "a whole-number parameter needs two whole numbers between its bounds",
                 text::formatDouble(p.lower) + " to " + text::formatDouble(p.upper),
                 "bounds at least 1 apart");
        if (!p.start && (v < p.lower || v > p.upper))
            fail("", "the species' value " + f.value + " is outside the bounds: give a start",
                 p.path, text::formatDouble(p.lower) + " to " + text::formatDouble(p.upper));
    }
}

}  // namespace plantarch
