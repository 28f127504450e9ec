// The physiology options of build and grow (docs/physiology.md): the carbohydrate budget and
// the nitrogen model driven day by day by traced light, from a weather file or clear days.

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

void addPhysiologyOptions(CLI::App& app, PhysiologyArgs& a, bool withFrom) {
    app.add_flag("--carbon", a.carbon,
                 "Grow with the carbohydrate budget, fed by traced light (docs/physiology.md)");
    app.add_flag("--nitrogen", a.nitrogen, "Grow with the nitrogen model");
    app.add_option("--location", a.location,
                   "With --carbon/--nitrogen: LAT,LON in degrees (north and east positive)");
    app.add_option("--start", a.start,
                   "With --carbon/--nitrogen: the first of the clear days, YYYY-MM-DD");
    app.add_option("--clearness", a.clearness,
                   "With --start: global radiation over that above the atmosphere (default 0.75)")
        ->check(numberCheck("--clearness", "a share", 0.0, 1.0, false, "0 to 1"));
    app.add_option("--weather", a.weather,
                   "With --carbon/--nitrogen: weather file (CSV), one day of growth per date");
    app.add_option("--fertilise", a.fertilise,
                   "Add nitrogen AGE:GRAMS at a plant age, days (repeatable; needs --nitrogen)");
    app.add_option("--light-every", a.lightEvery,
                   "Trace the light every N hours of daylight (1 to 24; default 1)")
        ->check(numberCheck("--light-every", "hours", 1, 24, true, "1 to 24"));
    app.add_option("--series", a.series, "The physiology's daily records (.csv)");
    if (withFrom)
        app.add_option("--from", a.from,
                       "With --carbon/--nitrogen: the age (whole days, default 10) from which "
                       "the plants grow with them; built as without them up to it")
            ->check(daysCheck("--from"));
}

float physiologyBuildAge(const PhysiologyArgs& a, float age, bool frames) {
    if (!physiologyOn(a)) return age;
    if (frames || a.from > age || age != std::floor(age) || a.from != std::floor(a.from))
        throw Error(
            fmt::format("--carbon/--nitrogen grow whole days from --from ({}) to --age ({}): "
                        "whole numbers, --from <= --age, no --frames",
                        a.from, age));
    return a.from;
}

bool physiologyOn(const PhysiologyArgs& a) {
    return a.carbon || a.nitrogen;
}

void checkPhysiologyOptions(const PhysiologyArgs& a) {
    const bool any = !a.location.empty() || !a.start.empty() || !a.weather.empty() ||
                     !a.fertilise.empty() || !a.series.empty();
    if (!physiologyOn(a)) {
        if (any)
            throw Error(
                "--location, --start, --weather, --fertilise and --series need --carbon "
                "or --nitrogen");
        return;
    }
    if (a.location.empty())
        throw Error("--carbon/--nitrogen need --location LAT,LON (where the sun is)");
    if (a.weather.empty() == a.start.empty())
        throw Error(
            "--carbon/--nitrogen need either --weather FILE or --start YYYY-MM-DD "
            "(clear days), not both");
    if (!a.fertilise.empty() && !a.nitrogen) throw Error("--fertilise needs --nitrogen");
    for (const std::string& f : a.fertilise) {
        const auto [age, grams] =
            parseTwoNumbers(f, ':', "--fertilise", "AGE:GRAMS", "e.g. 20:0.5");
        if (age < 0.0 || !(grams > 0.0))
            throw Error("--fertilise " + f + ": the age must be >= 0 and the grams > 0");
    }
    if (!a.start.empty()) parseUTCTime(a.start);
}

std::vector<PhysiologyRecord> growWithPhysiology(PlantArchitecture& arch,
                                                 const std::vector<unsigned>& plants,
                                                 const PhysiologyArgs& a, double days) {
    if (days != std::floor(days) || days < 0.0 || days > 100000.0)
        throw Error(fmt::format("--carbon/--nitrogen grow whole days: {} is not one", days));
    const auto [lat, lon] =
        parseTwoNumbers(a.location, ',', "--location", "LAT,LON in degrees", "e.g. 38.54,-121.74");
    PhysiologySeason season;
    season.carbon = a.carbon;
    season.nitrogen = a.nitrogen;
    season.location = {lat, lon};
    season.lightEvery = a.lightEvery;
    season.clearness = a.clearness;
    if (!a.weather.empty())
        season.weather = readWeatherFile(a.weather);
    else
        season.start = parseUTCTime(a.start);
    for (const std::string& f : a.fertilise) {  // checked already
        const auto [age, grams] =
            parseTwoNumbers(f, ':', "--fertilise", "AGE:GRAMS", "e.g. 20:0.5");
        season.fertilise.push_back({age, grams});
    }
    std::vector<PhysiologyRecord> records;
    try {
        records = growPhysiologySeason(arch, plants, season, unsigned(days), terminalProgress());
    } catch (const Error& e) {
        if (e.parameter() == "weather") throw Error(a.weather + ": " + e.message());
        throw;
    }
    if (!a.series.empty()) writePhysiologyCSV(a.series, records);
    return records;
}

}  // namespace plantarch::cli
