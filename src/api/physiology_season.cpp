// growPhysiologySeason: a season of days through given or clear-day weather, with
// fertilisation at plant ages (plantarch/Physiology.h).

#include <algorithm>
#include <cmath>
#include <set>

#include "plantarch/Error.h"
#include "plantarch/Physiology.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

UTCTime nextDate(UTCTime t) {
    const int lengths[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (t.year % 4 == 0 && t.year % 100 != 0) || t.year % 400 == 0;
    const int length = t.month == 2 && leap ? 29 : lengths[std::clamp(t.month, 1, 12) - 1];
    if (++t.day > length) {
        t.day = 1;
        if (++t.month > 12) {
            t.month = 1;
            ++t.year;
        }
    }
    return t;
}

void checkPhysiologySeason(const PhysiologySeason& s) {
    if (!s.carbon && !s.nitrogen)
        throw Error("a physiology season runs the carbohydrate budget, the nitrogen model or both",
                    {.parameter = "carbon", .validRange = "carbon or nitrogen on"});
    sunPosition(s.location, s.weather.empty() ? s.start : s.weather.front().time);
    if (s.weather.empty())  // the clear days' date and clearness, as clearSkyDay checks them
        clearSkyDay(s.location, s.start.year, s.start.month, s.start.day, s.clearness);
    if (s.lightEvery < 1 || s.lightEvery > 24)
        throw Error("light every N hours out of range", {.parameter = "light_every",
                                                         .value = std::to_string(s.lightEvery),
                                                         .validRange = "1 to 24"});
    for (const Fertilisation& f : s.fertilise) {
        if (!s.nitrogen)
            throw Error("fertilisation adds nitrogen: it needs the nitrogen model",
                        {.parameter = "fertilise", .validRange = "with nitrogen on"});
        if (!(f.age >= 0.0 && f.age <= 100000.0))
            throw Error("fertilisation age out of range", {.parameter = "fertilise/age",
                                                           .value = std::to_string(f.age),
                                                           .validRange = "0 to 100000 days"});
        if (!(f.grams > 0.0 && f.grams <= 1e6))
            throw Error("fertilisation out of range", {.parameter = "fertilise/grams",
                                                       .value = std::to_string(f.grams),
                                                       .validRange = "> 0 to 1000000 g N"});
    }
}

namespace {

// The season's hours, one list per date.
std::vector<std::vector<WeatherHour>> seasonDays(const PhysiologySeason& s, unsigned days) {
    std::vector<std::vector<WeatherHour>> byDay;
    if (s.weather.empty()) {
        UTCTime t{s.start.year, s.start.month, s.start.day, 0.0};
        for (unsigned d = 0; d < days; ++d) {
            byDay.push_back(clearSkyDay(s.location, t.year, t.month, t.day, s.clearness));
            t = nextDate(t);
        }
        return byDay;
    }
    for (const WeatherHour& h : s.weather) {
        const UTCTime& last = byDay.empty() ? h.time : byDay.back().back().time;
        if (byDay.empty() || last.day != h.time.day || last.month != h.time.month ||
            last.year != h.time.year)
            byDay.emplace_back();
        byDay.back().push_back(h);
    }
    if (byDay.size() < days)
        throw Error("the weather has " + std::to_string(byDay.size()) + " date(s) for " +
                        std::to_string(days) + " days of growth",
                    {.parameter = "weather", .validRange = "a date of weather per day"});
    byDay.resize(days);
    return byDay;
}

}  // namespace

std::vector<PhysiologyRecord> growPhysiologySeason(PlantArchitecture& arch,
                                                   const std::vector<unsigned>& plants,
                                                   const PhysiologySeason& s, unsigned days,
                                                   const ProgressCallback& progress) {
    checkPhysiologySeason(s);
    const auto byDay = seasonDays(s, days);
    for (unsigned id : plants) {
        if (s.carbon) arch.enableCarbohydrateModel(id);
        if (s.nitrogen) arch.enableNitrogenModel(id);
    }
    PhysiologyOptions options;
    options.location = s.location;
    options.lightEvery = s.lightEvery;
    std::set<std::pair<unsigned, std::size_t>> fertilised;  // (plant, event)
    std::vector<PhysiologyRecord> records;
    for (unsigned d = 0; d < days; ++d) {
        if (progress) progress("physiology", double(d) / double(days));
        for (unsigned id : plants)
            for (std::size_t i = 0; i < s.fertilise.size(); ++i)
                if (arch.getPlantAge(id) >= s.fertilise[i].age && !fertilised.count({id, i})) {
                    arch.addPlantNitrogen(id, s.fertilise[i].grams);
                    fertilised.insert({id, i});
                }
        const auto day = growPhysiology(arch, byDay[d], options);
        records.insert(records.end(), day.begin(), day.end());
    }
    if (progress) progress("physiology", 1.0);
    return records;
}

}  // namespace plantarch
