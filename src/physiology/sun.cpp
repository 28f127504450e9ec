// Time, the sun's position, and the split of sunlight into direct and diffuse light.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Light.h"

namespace plantarch {

namespace {

constexpr double kRad = std::numbers::pi / 180.0;

bool leapYear(int y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int daysInMonth(int y, int m) {
    static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && leapYear(y) ? 29 : days[m - 1];
}

void checkTime(const UTCTime& t, const std::string& text) {
    const auto bad = [&](const std::string& why, const std::string& valid) {
        throw Error(why, {.parameter = "time", .value = text, .validRange = valid});
    };
    if (t.year < 1900 || t.year > 2100) bad("year out of range", "years 1900 to 2100");
    if (t.month < 1 || t.month > 12) bad("month out of range", "months 1 to 12");
    if (t.day < 1 || t.day > daysInMonth(t.year, t.month))
        bad("day out of range", "days 1 to " + std::to_string(daysInMonth(t.year, t.month)));
    if (!(t.hour >= 0.0 && t.hour <= 24.0)) bad("hour out of range", "hours 0 to 24");
}

// Days from 2000-01-01 to the start of the given date (proleptic Gregorian calendar).
long daysFromCivil(int y, int m, int d) {
    y -= m <= 2 ? 1 : 0;
    const long era = (y >= 0 ? y : y - 399) / 400;
    const long yoe = y - era * 400;
    const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468 - 10957;  // 10957: 1970-01-01 to 2000-01-01
}

double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}

int digits(std::string_view s, std::size_t at, std::size_t n, bool& ok) {
    int v = 0;
    if (at + n > s.size()) {
        ok = false;
        return 0;
    }
    for (std::size_t i = at; i < at + n; ++i) {
        if (s[i] < '0' || s[i] > '9') ok = false;
        v = v * 10 + (s[i] - '0');
    }
    return v;
}

}  // namespace

UTCTime parseUTCTime(std::string_view text) {
    const std::string shown(text);
    std::string_view s = text;
    if (!s.empty() && (s.back() == 'Z' || s.back() == 'z')) s.remove_suffix(1);
    bool ok = s.size() == 10 || s.size() == 16 || s.size() == 19;
    UTCTime t;
    t.year = digits(s, 0, 4, ok);
    ok = ok && s[4] == '-' && s[7] == '-';
    t.month = digits(s, 5, 2, ok);
    t.day = digits(s, 8, 2, ok);
    if (ok && s.size() > 10) {
        ok = (s[10] == 'T' || s[10] == 't' || s[10] == ' ') && s[13] == ':';
        const int h = digits(s, 11, 2, ok);
        const int m = digits(s, 14, 2, ok);
        int sec = 0;
        if (s.size() == 19) {
            ok = ok && s[16] == ':';
            sec = digits(s, 17, 2, ok);
        }
        ok = ok && m < 60 && sec < 60 && (h < 24 || (h == 24 && m == 0 && sec == 0));
        t.hour = h + m / 60.0 + sec / 3600.0;
    }
    if (!ok)
        throw Error("not a date and time",
                    {.parameter = "time",
                     .value = shown,
                     .validRange = "YYYY-MM-DDTHH:MM[:SS][Z] in UTC, or YYYY-MM-DD"});
    checkTime(t, shown);
    return t;
}

std::string formatUTCTime(const UTCTime& t) {
    const long seconds = std::lround(t.hour * 3600.0);
    char text[40];
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02ld:%02ld:%02ldZ", t.year, t.month, t.day,
                  seconds / 3600, (seconds / 60) % 60, seconds % 60);
    return text;
}

double daysSince2000(const UTCTime& t) {
    return double(daysFromCivil(t.year, t.month, t.day)) + t.hour / 24.0;
}

vec3 SunPosition::direction() const {
    const double e = elevation * kRad, a = azimuth * kRad;
    return vec3(float(std::cos(e) * std::sin(a)), float(std::cos(e) * std::cos(a)),
                float(std::sin(e)));
}

SunPosition sunPosition(const Location& where, const UTCTime& when) {
    if (!(where.latitude >= -90.0 && where.latitude <= 90.0))
        throw Error("latitude out of range", {.parameter = "latitude",
                                              .value = text::formatFloat(float(where.latitude)),
                                              .validRange = "-90 to 90 degrees"});
    if (!(where.longitude >= -180.0 && where.longitude <= 180.0))
        throw Error("longitude out of range",
                    {.parameter = "longitude",
                     .value = text::formatFloat(float(where.longitude)),
                     .validRange = "-180 to 180 degrees (east positive)"});
    checkTime(when, formatUTCTime(when));
    // Julian centuries from J2000.0 (2000-01-01T12:00, Julian day 2451545).
    const double jc = (daysSince2000(when) - 0.5) / 36525.0;
    const double meanLong = wrap360(280.46646 + jc * (36000.76983 + jc * 0.0003032));
    const double meanAnom = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);
    const double ecc = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);
    const double m = meanAnom * kRad;
    const double center = std::sin(m) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +
                          std::sin(2 * m) * (0.019993 - 0.000101 * jc) + std::sin(3 * m) * 0.000289;
    const double trueLong = meanLong + center;
    const double omega = (125.04 - 1934.136 * jc) * kRad;
    const double apparentLong = trueLong - 0.00569 - 0.00478 * std::sin(omega);
    const double meanObliq =
        23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
    const double obliq = (meanObliq + 0.00256 * std::cos(omega)) * kRad;
    const double declination = std::asin(std::sin(obliq) * std::sin(apparentLong * kRad));
    const double y = std::tan(obliq / 2) * std::tan(obliq / 2);
    const double l0 = meanLong * kRad;
    // Equation of time, minutes.
    const double eqTime = 4.0 / kRad *
                          (y * std::sin(2 * l0) - 2 * ecc * std::sin(m) +
                           4 * ecc * y * std::sin(m) * std::cos(2 * l0) -
                           0.5 * y * y * std::sin(4 * l0) - 1.25 * ecc * ecc * std::sin(2 * m));
    const double trueSolarMinutes =
        std::fmod(when.hour * 60.0 + eqTime + 4.0 * where.longitude + 1440.0 * 2, 1440.0);
    const double hourAngle = (trueSolarMinutes / 4.0 - 180.0) * kRad;
    const double lat = where.latitude * kRad;
    const double cosZenith =
        std::clamp(std::sin(lat) * std::sin(declination) +
                       std::cos(lat) * std::cos(declination) * std::cos(hourAngle),
                   -1.0, 1.0);
    const double zenith = std::acos(cosZenith);
    SunPosition sun;
    sun.elevation = 90.0 - zenith / kRad;
    // Azimuth clockwise from north, from the local east and north components.
    const double east = -std::cos(declination) * std::sin(hourAngle);
    const double north = std::cos(lat) * std::sin(declination) -
                         std::sin(lat) * std::cos(declination) * std::cos(hourAngle);
    sun.azimuth = (std::abs(east) < 1e-12 && std::abs(north) < 1e-12)
                      ? 180.0
                      : wrap360(std::atan2(east, north) / kRad);
    return sun;
}

double extraterrestrialHorizontal(const UTCTime& when, double elevation) {
    if (!(elevation > 0.0)) return 0.0;
    const double dayOfYear = daysSince2000(when) - daysFromCivil(when.year, 1, 1);
    const double distance = 1.0 + 0.033 * std::cos(2.0 * std::numbers::pi * dayOfYear / 365.25);
    return 1361.0 * distance * std::sin(std::min(elevation, 90.0) * kRad);
}

double erbsDiffuseFraction(double kt) {
    if (!(kt > 0.22)) return 1.0 - 0.09 * std::max(kt, 0.0);
    if (kt <= 0.8)
        return 0.9511 - 0.1604 * kt + 4.388 * kt * kt - 16.638 * kt * kt * kt +
               12.336 * kt * kt * kt * kt;
    return 0.165;
}

SkyLight skyLight(const Location& where, const WeatherHour& hour) {
    SkyLight sky;
    sky.sun = sunPosition(where, hour.time);
    const double par = std::max(hour.par, 0.0);
    double fd = hour.diffuseFraction;
    if (fd < 0.0) {
        const double top = extraterrestrialHorizontal(hour.time, sky.sun.elevation) * kParPerGlobal;
        fd = top > 0.0 ? erbsDiffuseFraction(par / top) : 1.0;
    }
    if (sky.sun.elevation < 1.0) fd = 1.0;
    fd = std::clamp(fd, 0.0, 1.0);
    sky.diffuseHorizontal = par * fd;
    sky.directNormal = fd < 1.0 ? par * (1.0 - fd) / std::sin(sky.sun.elevation * kRad) : 0.0;
    return sky;
}

}  // namespace plantarch
