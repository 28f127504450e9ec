// Helpers shared by the commands that build and grow plants: days, -D build parameters and
// the --stats JSON of one plant.

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>
#include <type_traits>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"

namespace plantarch::cli {

CLI::Validator numberCheck(const std::string& option, const std::string& what, double lo, double hi,
                           bool whole, const std::string& range) {
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            double v = 0.0;
            const char* end = text.data() + text.size();
            const auto [used, ec] = std::from_chars(text.data(), end, v);
            // A whole number is written in digits: "1e1" and "2.0" convert to doubles but not
            // to the integer the option holds.
            const bool digits =
                !text.empty() &&
                text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0) == std::string::npos &&
                text != "-";
            if (ec == std::errc() && used == end && std::isfinite(v) && v >= lo && v <= hi &&
                (!whole || digits))
                return "";
            return option + " = " + text + ": not " + what + " (valid: " + range + ")";
        },
        range);
}

CLI::Validator daysCheck(const std::string& option) {
    return numberCheck(option, "a number of days", 0.0, 100000.0, false, "0 to 100000");
}

CLI::Option* addPlantOptions(CLI::App& app, std::string& species, float& age,
                             std::vector<std::string>& defines, bool& noTrellis) {
    app.add_option("species", species, "Library species name or species file (.xml)")->required();
    CLI::Option* ageOption =
        app.add_option("--age", age, "Plant age in days (0 to 100000)")->check(daysCheck("--age"));
    app.add_option("-D", defines, "Build parameter override, name=value (repeatable)");
    app.add_flag("--no-trellis", noTrellis,
                 "Leave out the species' trellis (posts and wires drawn with trellis species)");
    return ageOption;
}

std::map<std::string, float> parseDefines(const std::vector<std::string>& defines) {
    std::map<std::string, float> out;
    for (const std::string& d : defines) {
        const auto eq = d.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("a build parameter is written name=value",
                        {.parameter = "-D", .value = d, .validRange = "name=value"});
        const std::string name = d.substr(0, eq), text = d.substr(eq + 1);
        // Decimal only (from_chars' general format): no hex, no "inf", no leading '+'.
        float value = 0.0f;
        const char* end = text.data() + text.size();
        const auto [used, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || ec != std::errc() || used != end || !std::isfinite(value))
            throw Error(
                "build parameter value is not a number",
                {.parameter = name, .value = text, .validRange = "a finite decimal number"});
        if (!out.emplace(name, value).second)
            throw Error("build parameter '" + name + "' is given twice",
                        {.parameter = "-D", .value = d, .validRange = "each name once"});
    }
    return out;
}

namespace {

// A JSON string: quotes, backslashes and control characters escaped (a plant's name comes
// from a file and may hold any of them).
std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\')
            out += std::string("\\") + c;
        else if (static_cast<unsigned char>(c) < 0x20)
            out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        else
            out += c;
    }
    return out + "\"";
}

// A number of the statistics: JSON has no infinity or NaN, so such a value is refused rather
// than written as text no JSON reader takes.
double finite(const char* name, double v) {
    if (!std::isfinite(v))
        throw Error("the plant's statistic is not a finite number, so it has no JSON form",
                    {.parameter = std::string("--stats ") + name,
                     .value = fmt::format("{}", v),
                     .validRange = "a finite number"});
    return v;
}

}  // namespace

std::string plantStatsJSON(const PlantArchitecture& arch, const Context&, unsigned plant,
                           std::uint64_t seed) {
    const PlantInstance& p = arch.plant(plant);
    const PlantSummary s = summarizePlant(arch, plant);
    const auto numbers = [](const auto& values, const char* name) {
        std::string text;
        for (const auto v : values) {
            text += text.empty() ? "" : ", ";
            if constexpr (std::is_floating_point_v<decltype(v)>)
                text += fmt::format("{:.4f}", finite(name, v));
            else
                text += fmt::format("{}", v);
        }
        return "[" + text + "]";
    };
    return fmt::format(
        "{{\"species\": {}, \"plant\": {}, \"age\": {}, \"seed\": {}, \"height\": {:.4f}, "
        "\"leaves\": {}, \"leaf_area\": {:.5f}, \"shoots\": {}, \"flowers\": {}, \"fruit\": {}, "
        "\"triangles\": {}, \"width_x\": {:.4f}, \"width_y\": {:.4f}, \"width_long\": {:.4f}, "
        "\"width_short\": {:.4f}, \"main_nodes\": {}, \"shoots_by_rank\": {}, "
        "\"phytomers_by_rank\": {}, \"leaf_inclination\": {}, \"leaf_inclination_mean\": "
        "{:.4f}}}",
        jsonString(p.name), plant, finite("age", p.age), seed, finite("height", s.height), s.leaves,
        finite("leaf_area", s.leafArea), arch.getShootCount(plant), s.flowers, s.fruit, s.triangles,
        finite("width_x", s.widthX), finite("width_y", s.widthY), finite("width_long", s.widthLong),
        finite("width_short", s.widthShort), s.mainNodes, numbers(s.shootsByRank, "shoots_by_rank"),
        numbers(s.phytomersByRank, "phytomers_by_rank"),
        numbers(s.leafInclination, "leaf_inclination"),
        finite("leaf_inclination_mean", meanLeafInclination(arch, plant)));
}

}  // namespace plantarch::cli
