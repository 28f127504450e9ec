// Text forms of parameter values: strict parsers and shortest round-trip formatting.

#include "core/value_text.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"

namespace plantarch::text {

namespace {

constexpr const char* kFloatForms =
    "a number, or uniform(min, max), normal(mean, stddev), weibull(shape, scale)";
constexpr const char* kIntForms =
    "a whole number, or uniform(min, max), discrete(a, b, ...) of whole numbers";

[[noreturn]] void fail(const std::string& message, std::string_view value,
                       std::string validRange = "") {
    throw Error(message, {.value = std::string(value), .validRange = std::move(validRange)});
}

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// The one number reader: std::from_chars (locale-independent, exact) over the whole text.
template <class T>
bool readWhole(std::string_view s, T& out) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    if (s.empty()) return false;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return false;
    if constexpr (std::is_floating_point_v<T>) return std::isfinite(out);
    return true;
}

template <class T>
T parseReal(std::string_view raw) {
    const std::string_view s = trim(raw);
    T v = 0;
    if (!readWhole(s, v)) fail("expected a number", s, "a finite number");
    return v;
}

// "name(a, b, ...)" split into its name and trimmed arguments.
struct Call {
    std::string_view name;
    std::vector<std::string_view> args;
};

bool splitCall(std::string_view s, Call& call) {
    const auto open = s.find('(');
    if (open == std::string_view::npos) return false;
    if (s.back() != ')') fail("missing ')' at the end", s);
    call.name = trim(s.substr(0, open));
    std::string_view inner = s.substr(open + 1, s.size() - open - 2);
    if (inner.find_first_of("()") != std::string_view::npos) fail("unexpected parenthesis", s);
    if (!trim(inner).empty()) {
        std::size_t start = 0;
        while (true) {
            const auto comma = inner.find(',', start);
            call.args.push_back(trim(inner.substr(start, comma - start)));
            if (comma == std::string_view::npos) break;
            start = comma + 1;
        }
    }
    return true;
}

// Argument i of a distribution: a number (whole for the integer distributions).
template <class T>
T numberArg(const Call& c, std::size_t i, std::string_view whole) {
    constexpr bool real = std::is_floating_point_v<T>;
    T v = 0;
    if (!readNumber(c.args[i], v))
        fail("argument " + std::to_string(i + 1) + " of " + std::string(c.name) + " is not a " +
                 (real ? "number" : "whole number") + " ('" + std::string(c.args[i]) + "')",
             whole, real ? kFloatForms : kIntForms);
    return v;
}

void requireArgs(const Call& c, std::size_t n, const char* names, std::string_view whole) {
    if (c.args.size() != n)
        fail(std::string(c.name) + " takes " + std::to_string(n) + " arguments (" + names +
                 "), got " + std::to_string(c.args.size()),
             whole);
}

}  // namespace

std::string_view trim(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

std::string collapseSpaces(std::string_view s) {
    std::string out;
    bool space = false;
    for (char c : trim(s)) {
        if (isSpace(c)) {
            space = true;
            continue;
        }
        if (space) out += ' ';
        space = false;
        out += c;
    }
    return out;
}

bool readNumber(std::string_view s, float& out) {
    return readWhole(s, out);
}
bool readNumber(std::string_view s, double& out) {
    return readWhole(s, out);
}
bool readNumber(std::string_view s, int& out) {
    return readWhole(s, out);
}
bool readNumber(std::string_view s, unsigned& out) {
    return readWhole(s, out);
}
bool readNumber(std::string_view s, std::uint64_t& out) {
    return readWhole(s, out);
}

float parseFloat(std::string_view raw) {
    return parseReal<float>(raw);
}

double parseDouble(std::string_view raw) {
    return parseReal<double>(raw);
}

int parseInt(std::string_view raw) {
    const std::string_view s = trim(raw);
    int v = 0;
    if (!readNumber(s, v)) fail("expected a whole number", s, "a whole number");
    return v;
}

unsigned parseUnsigned(std::string_view raw) {
    const std::string_view s = trim(raw);
    unsigned v = 0;
    if (!readNumber(s, v)) fail("expected a whole number >= 0", s, "a whole number >= 0");
    return v;
}

bool parseBool(std::string_view raw) {
    const std::string_view s = trim(raw);
    if (s == "true") return true;
    if (s == "false") return false;
    fail("expected true or false", s, "true, false");
}

vec3 parseVec3(std::string_view raw) {
    const std::string_view s = trim(raw);
    std::vector<std::string_view> parts;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (isSpace(s[i]) || s[i] == ',')) ++i;
        std::size_t j = i;
        while (j < s.size() && !isSpace(s[j]) && s[j] != ',') ++j;
        if (j > i) parts.push_back(s.substr(i, j - i));
        i = j;
    }
    vec3 v{0.0f};
    bool ok = parts.size() == 3;
    for (std::size_t k = 0; ok && k < 3; ++k) ok = readNumber(parts[k], v[int(k)]);
    if (!ok) fail("expected three numbers", s, "three numbers such as '0.2 0.25 0.05'");
    return v;
}

RandomFloat parseRandomFloat(std::string_view raw) {
    const std::string_view s = trim(raw);
    float constant = 0.0f;
    if (readNumber(s, constant)) return RandomFloat(constant);
    Call c;
    if (s.empty() || !splitCall(s, c)) fail("expected a number or a distribution", s, kFloatForms);
    if (c.name == "uniform") {
        requireArgs(c, 2, "min, max", s);
        return RandomFloat::uniform(numberArg<float>(c, 0, s), numberArg<float>(c, 1, s));
    }
    if (c.name == "normal") {
        requireArgs(c, 2, "mean, stddev", s);
        return RandomFloat::normal(numberArg<float>(c, 0, s), numberArg<float>(c, 1, s));
    }
    if (c.name == "weibull") {
        requireArgs(c, 2, "shape, scale", s);
        return RandomFloat::weibull(numberArg<float>(c, 0, s), numberArg<float>(c, 1, s));
    }
    const std::string near = closestMatch(c.name, {"uniform", "normal", "weibull"});
    fail("unknown distribution '" + std::string(c.name) + "'" +
             (near.empty() ? "" : ", did you mean '" + near + "'?"),
         s, kFloatForms);
}

RandomInt parseRandomInt(std::string_view raw) {
    const std::string_view s = trim(raw);
    int constant = 0;
    if (readNumber(s, constant)) return RandomInt(constant);
    Call c;
    if (s.empty() || !splitCall(s, c))
        fail("expected a whole number or a distribution", s, kIntForms);
    if (c.name == "uniform") {
        requireArgs(c, 2, "min, max", s);
        return RandomInt::uniform(numberArg<int>(c, 0, s), numberArg<int>(c, 1, s));
    }
    if (c.name == "discrete") {
        if (c.args.empty()) fail("discrete needs at least one value", s, kIntForms);
        std::vector<int> values;
        for (std::size_t i = 0; i < c.args.size(); ++i) values.push_back(numberArg<int>(c, i, s));
        return RandomInt::discrete(std::move(values));
    }
    const std::string near = closestMatch(c.name, {"uniform", "discrete"});
    fail("unknown integer distribution '" + std::string(c.name) + "'" +
             (near.empty() ? "" : ", did you mean '" + near + "'?"),
         s, kIntForms);
}

namespace {

// Shortest round-trip text, in plain notation unless that is more than two characters
// longer than with an exponent: "0.0001", "1000000", but "1e-09", "3.4028235e+38".
template <class T>
std::string shortest(T v) {
    char general[64];
    char fixed[64];
    const auto g = std::to_chars(general, general + sizeof general, v);
    const auto f = std::to_chars(fixed, fixed + sizeof fixed, v, std::chars_format::fixed);
    if (f.ec == std::errc() && f.ptr - fixed <= g.ptr - general + 2)
        return std::string(fixed, f.ptr);
    return std::string(general, g.ptr);
}

}  // namespace

std::string formatFloat(float v) {
    return shortest(v);
}

std::string formatDouble(double v) {
    return shortest(v);
}

std::string formatRandomFloat(const RandomFloat& v) {
    auto call = [&](const char* name) {
        return std::string(name) + "(" + formatFloat(v.a()) + ", " + formatFloat(v.b()) + ")";
    };
    switch (v.kind()) {
        case RandomFloat::Kind::Constant:
            return formatFloat(v.a());
        case RandomFloat::Kind::Uniform:
            return call("uniform");
        case RandomFloat::Kind::Normal:
            return call("normal");
        case RandomFloat::Kind::Weibull:
            return call("weibull");
    }
    return formatFloat(v.a());
}

std::string formatVec3(const vec3& v) {
    return formatFloat(v.x) + " " + formatFloat(v.y) + " " + formatFloat(v.z);
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    // Optimal string alignment: insertions, deletions, substitutions and transpositions of
    // neighbours ("lable" -> "label") each cost 1.
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::size_t> d((n + 1) * (m + 1));
    auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * (m + 1) + j]; };
    for (std::size_t i = 0; i <= n; ++i) at(i, 0) = i;
    for (std::size_t j = 0; j <= m; ++j) at(0, j) = j;
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
        }
    return at(n, m);
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
    const std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
    std::string best;
    std::size_t bestDistance = limit + 1;
    for (const std::string& c : candidates) {
        const std::size_t d = editDistance(word, c);
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

std::string joinNames(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) {
        if (!out.empty()) out += ", ";
        out += n;
    }
    return out;
}

std::string oneOf(const std::vector<std::string>& names) {
    return names.empty() ? "none" : "one of: " + joinNames(names);
}

std::string unknownMessage(std::string_view what, std::string_view name,
                           const std::vector<std::string>& candidates, std::string_view where) {
    const std::string near = closestMatch(name, candidates);
    std::string out = "unknown ";
    out.append(what).append(" '").append(name).append("'").append(where);
    if (!near.empty()) out += ", did you mean '" + near + "'?";
    return out;
}

bool isLabel(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
}

std::size_t parseChoice(std::string_view raw, const std::vector<std::string>& choices) {
    const std::string_view s = trim(raw);
    for (std::size_t i = 0; i < choices.size(); ++i)
        if (s == choices[i]) return i;
    fail(unknownMessage("value", s, choices), s, oneOf(choices));
}

void appendXmlEscaped(std::string& out, std::string_view s) {
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            case '\r':
                out += "&#13;";
                break;
            case '\n':
                out += "&#10;";
                break;
            case '\t':
                out += "&#9;";
                break;
            default:
                out += c;
        }
    }
}

}  // namespace plantarch::text

namespace plantarch {

std::string rangeText(const NumberRange& r) {
    const auto number = [&](double v) {
        if (r.whole && std::abs(v) < 9.0e15) return std::to_string(static_cast<long long>(v));
        return r.single ? text::formatFloat(float(v)) : text::formatDouble(v);
    };
    const bool low = std::isfinite(r.min), high = std::isfinite(r.max);
    const std::string from = (r.openMin ? "> " : ">= ") + (low ? number(r.min) : "");
    const std::string to = (r.openMax ? "< " : "<= ") + (high ? number(r.max) : "");
    if (low && high)
        return r.openMin || r.openMax ? from + " and " + to
                                      : number(r.min) + " to " + number(r.max);
    if (low) return from;
    if (high) return to;
    return r.whole ? "any whole number" : "any finite number";
}

}  // namespace plantarch
