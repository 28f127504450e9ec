// Weather files (CSV, one row per interval) and generated clear-sky days.

#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/input_file.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Light.h"

namespace plantarch {

namespace {

// Every column a weather file may have, declared once: its name, unit, range and field.
struct Column {
    const char* name;
    const char* unit;
    double min, max;
    double WeatherHour::*field;  // null for time and global radiation
};

const std::vector<Column>& columns() {
    static const std::vector<Column> all{
        {"time", "UTC", 0, 0, nullptr},
        {"par", "µmol m-2 s-1", 0, 5000, &WeatherHour::par},
        {"global_radiation", "W m-2", 0, 2000, nullptr},
        {"diffuse_fraction", "0 to 1", 0, 1, &WeatherHour::diffuseFraction},
        {"air_temperature", "°C", -90, 70, &WeatherHour::airTemperature},
        {"relative_humidity", "%", 0, 100, &WeatherHour::relativeHumidity},
        {"vpd", "kPa", 0, 20, &WeatherHour::vpd},
        {"co2", "ppm", 0, 100000, &WeatherHour::co2},
        {"wind_speed", "m s-1", 0, 200, &WeatherHour::wind},
    };
    return all;
}

std::string columnNames() {
    std::string s;
    for (const Column& c : columns()) s += (s.empty() ? "" : ", ") + std::string(c.name);
    return s;
}

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    const auto b = s.find_last_not_of(" \t\r");
    return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> parts;
    std::stringstream ss(line);
    for (std::string part; std::getline(ss, part, ',');) parts.push_back(trim(part));
    if (!line.empty() && line.back() == ',') parts.push_back("");
    return parts;
}

}  // namespace

std::vector<WeatherHour> readWeatherFile(const std::string& path) {
    std::istringstream in(io::readWholeFile(path, io::kWeatherFile));
    std::vector<int> which;  // column index per field of the header
    std::vector<WeatherHour> hours;
    std::string line;
    int number = 0;
    const auto fail = [&](const std::string& why, const std::string& parameter,
                          const std::string& value, const std::string& valid) {
        throw Error(why, {.file = path,
                          .line = number,
                          .parameter = parameter,
                          .value = value.substr(0, 60),
                          .validRange = valid});
    };
    bool hasGlobal = false, hasPar = false;  // exactly one of them, checked at the header
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        const std::vector<std::string> parts = split(line);
        if (which.empty()) {  // the header
            for (const std::string& name : parts) {
                int found = -1;
                for (std::size_t c = 0; c < columns().size(); ++c)
                    if (name == columns()[c].name) found = int(c);
                if (found < 0) fail("unknown column", "column", name, columnNames());
                for (int w : which)
                    if (w == found) fail("column named twice", "column", name, "each column once");
                which.push_back(found);
            }
            const auto has = [&](const char* n) {
                for (int w : which)
                    if (std::string(columns()[std::size_t(w)].name) == n) return true;
                return false;
            };
            hasGlobal = has("global_radiation");
            hasPar = has("par");
            if (!has("time")) fail("no time column", "column", "", "a header naming time");
            if (!has("air_temperature"))
                fail("no air_temperature column", "column", "", "a header naming air_temperature");
            if (hasGlobal == hasPar)
                fail(hasGlobal ? "both par and global_radiation columns" : "no light column",
                     "column", "", "one of par (µmol m-2 s-1) or global_radiation (W m-2)");
            continue;
        }
        if (parts.size() != which.size())
            fail("expected " + std::to_string(which.size()) + " values, found " +
                     std::to_string(parts.size()),
                 "row", line, "one value per column of the header");
        WeatherHour h;
        for (std::size_t i = 0; i < parts.size(); ++i) {
            const Column& c = columns()[std::size_t(which[i])];
            const std::string& v = parts[i];
            if (std::string(c.name) == "time") {
                try {
                    h.time = parseUTCTime(v);
                } catch (const Error& e) {
                    fail(e.message(), "time", v, e.validRange());
                }
                continue;
            }
            double x = 0.0;
            const char* end = v.data() + v.size();
            const auto r = std::from_chars(v.data(), end, x);
            if (v.empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(x))
                fail("not a finite number", c.name, v, std::string("a number, ") + c.unit);
            if (x < c.min || x > c.max)
                fail("out of range", c.name, v,
                     text::formatFloat(float(c.min)) + " to " + text::formatFloat(float(c.max)) +
                         " " + c.unit);
            if (c.field)
                h.*c.field = x;
            else
                h.par = x * kParPerGlobal;  // global radiation
        }
        if (!hours.empty() && !(daysSince2000(h.time) > daysSince2000(hours.back().time)))
            fail("time does not increase", "time", formatUTCTime(h.time),
                 "after " + formatUTCTime(hours.back().time));
        hours.push_back(h);
    }
    if (which.empty())
        fail("no header", "column", "", "a header line naming the columns: " + columnNames());
    if (hours.empty()) fail("no rows", "row", "", "at least one row after the header");
    return hours;
}

std::vector<WeatherHour> clearSkyDay(const Location& where, int year, int month, int day,
                                     double clearness, double tMin, double tMax) {
    if (!(clearness >= 0.0 && clearness <= 1.0))
        throw Error("clearness out of range", {.parameter = "clearness",
                                               .value = text::formatFloat(float(clearness)),
                                               .validRange = "0 to 1"});
    if (!(std::isfinite(tMin) && std::isfinite(tMax) && tMin <= tMax && tMin >= -90 && tMax <= 70))
        throw Error(
            "air temperatures out of range",
            {.parameter = "temperature",
             .value = text::formatFloat(float(tMin)) + " to " + text::formatFloat(float(tMax)),
             .validRange = "-90 to 70 °C, the minimum at most the maximum"});
    std::vector<WeatherHour> hours;
    for (int h = 0; h < 24; ++h) {
        WeatherHour w;
        w.time = UTCTime{year, month, day, h + 0.5};
        const SunPosition sun = sunPosition(where, w.time);  // checks place and date
        w.par = clearness * extraterrestrialHorizontal(w.time, sun.elevation) * kParPerGlobal;
        w.diffuseFraction = erbsDiffuseFraction(clearness);
        // Solar time: a sine from tMin at 06:00 up to tMax at 14:00 and back.
        const double solar = std::fmod(w.time.hour + where.longitude / 15.0 + 48.0, 24.0);
        const double phase = solar >= 6.0 && solar <= 14.0
                                 ? (solar - 6.0) / 8.0
                                 : (solar < 6.0 ? solar + 10.0 : solar - 14.0) / 16.0 + 1.0;
        w.airTemperature = tMin + (tMax - tMin) * 0.5 * (1.0 - std::cos(std::numbers::pi * phase));
        hours.push_back(w);
    }
    return hours;
}

}  // namespace plantarch
