// The physiology options of build and grow (docs/physiology.md): the carbohydrate budget and
// the nitrogen model driven day by day by traced light, from a weather file or clear days.

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

UTCTime nextDay(UTCTime t) {
    const int lengths[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (t.year % 4 == 0 && t.year % 100 != 0) || t.year % 400 == 0;
    const int length = t.month == 2 && leap ? 29 : lengths[t.month - 1];
    if (++t.day > length) {
        t.day = 1;
        if (++t.month > 12) {
            t.month = 1;
            ++t.year;
        }
    }
    return t;
}

}  // namespace

void addPhysiologyOptions(CLI::App& app, PhysiologyArgs& a) {
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
    if (days != std::floor(days))
        throw Error(fmt::format("--carbon/--nitrogen grow whole days: {} is not one", days));
    const auto [lat, lon] =
        parseTwoNumbers(a.location, ',', "--location", "LAT,LON in degrees", "e.g. 38.54,-121.74");
    PhysiologyOptions options;
    options.location = {lat, lon};
    options.lightEvery = a.lightEvery;
    sunPosition(options.location, UTCTime{});  // checks the place before any work
    // The hours of each day.
    std::vector<std::vector<WeatherHour>> byDay;
    if (!a.weather.empty()) {
        for (const WeatherHour& h : readWeatherFile(a.weather)) {
            if (byDay.empty() || byDay.back().back().time.day != h.time.day ||
                byDay.back().back().time.month != h.time.month ||
                byDay.back().back().time.year != h.time.year)
                byDay.emplace_back();
            byDay.back().push_back(h);
        }
        if (double(byDay.size()) < days)
            throw Error(fmt::format("{}: {} day(s) of weather for {} days of growth", a.weather,
                                    byDay.size(), days),
                        {.file = a.weather});
    } else {
        const UTCTime first = parseUTCTime(a.start);
        UTCTime t{first.year, first.month, first.day, 0.0};
        for (int d = 0; d < int(days); ++d) {
            byDay.push_back(clearSkyDay(options.location, t.year, t.month, t.day, a.clearness));
            t = nextDay(t);
        }
    }
    for (unsigned id : plants) {
        if (a.carbon) arch.enableCarbohydrateModel(id);
        if (a.nitrogen) arch.enableNitrogenModel(id);
    }
    std::vector<std::pair<double, double>> events;  // (age, grams), checked already
    for (const std::string& f : a.fertilise)
        events.push_back(parseTwoNumbers(f, ':', "--fertilise", "AGE:GRAMS", "e.g. 20:0.5"));
    std::map<std::pair<unsigned, std::size_t>, bool> fertilised;
    std::vector<PhysiologyRecord> records;
    for (int d = 0; d < int(days); ++d) {
        for (unsigned id : plants)
            for (std::size_t i = 0; i < events.size(); ++i)
                if (arch.getPlantAge(id) >= events[i].first && !fertilised[{id, i}]) {
                    arch.addPlantNitrogen(id, events[i].second);
                    fertilised[{id, i}] = true;
                }
        const auto day = growPhysiology(arch, byDay[std::size_t(d)], options);
        records.insert(records.end(), day.begin(), day.end());
    }
    if (!a.series.empty()) writePhysiologyCSV(a.series, records);
    return records;
}

}  // namespace plantarch::cli
