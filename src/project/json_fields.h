#pragma once
// Reading the fields of a JSON document strictly, as the project and dataset files are read:
// each error one plantarch::Error naming the file, the field as a JSON pointer without its
// leading slash ("blocks/1/count"), the value as written (cut short) and the valid range.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "project/json_scan.h"
#include "project/project_fields.h"

namespace plantarch::project {

/// The value as a person reads it in an error: JSON text, cut short.
std::string shownJSON(const nlohmann::json& v);

class JSONFields {
public:
    explicit JSONFields(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& field, const std::string& message,
                           const nlohmann::json* value = nullptr,
                           const std::string& range = "") const {
        throw Error(message, {.file = file_,
                              .parameter = project::printable(field, 160),
                              .value = value ? shownJSON(*value) : "",
                              .validRange = range});
    }

    // Checks that `j` is an object whose keys are all in `known`; a key valid elsewhere
    // (`elsewhere`, with why) gets that reason, another the nearest known name.
    void object(const nlohmann::json& j, const std::string& field,
                const std::vector<std::string>& known,
                const std::map<std::string, std::string>& elsewhere = {},
                const std::string& elsewhereMessage = "") const {
        if (!j.is_object()) fail(field, "expected an object {...}", &j);
        for (const auto& [key, value] : j.items()) {
            if (std::find(known.begin(), known.end(), key) != known.end()) continue;
            const std::string at = join(field, key);
            if (const auto e = elsewhere.find(key); e != elsewhere.end())
                fail(at, elsewhereMessage, nullptr, e->second);
            const std::string near = text::closestMatch(key, known);
            fail(at, "unknown field" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                 nullptr, near.empty() ? text::oneOf(known) : "");
        }
    }

    double number(const nlohmann::json& j, const std::string& field, double lo, double hi,
                  const std::string& range, bool loOpen = false, bool whole = false,
                  bool hiOpen = false) const {
        if (!j.is_number())
            fail(field, whole ? "expected a whole number" : "expected a number", &j, range);
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(field, "expected a finite number", &j, range);
        if (whole && v != std::floor(v)) fail(field, "expected a whole number", &j, range);
        if (v < lo || v > hi || (loOpen && v == lo) || (hiOpen && v == hi))
            fail(field, "out of range", &j, range);
        return v;
    }
    // A number kept as a float: the float too is in range (1e-50 is > 0, but as a float 0),
    // so that the project written reads back.
    float number(const nlohmann::json& j, const std::string& field, const Range& r) const {
        const float v = float(number(j, field, r.lo, r.hi, r.text, r.loOpen, r.whole, r.hiOpen));
        if (v < r.lo || v > r.hi || (r.loOpen && v == float(r.lo)) ||
            (r.hiOpen && v == float(r.hi)))
            fail(field, "out of range (as a 32-bit float)", &j, r.text);
        return v;
    }
    // A file or species name: text without control characters.
    std::string name(const nlohmann::json& j, const std::string& field,
                     const std::string& range) const {
        std::string s = string(j, field);
        if (s.empty()) fail(field, "empty", &j, range);
        if (std::any_of(s.begin(), s.end(), [](char c) { return (unsigned char)c < 0x20; }))
            fail(field, "a control character in a name", &j, range);
        return s;
    }
    bool flag(const nlohmann::json& j, const std::string& field) const {
        if (!j.is_boolean()) fail(field, "expected true or false", &j, "true, false");
        return j.get<bool>();
    }
    std::string string(const nlohmann::json& j, const std::string& field) const {
        if (!j.is_string()) fail(field, "expected a text in quotes", &j);
        return j.get<std::string>();
    }
    std::uint64_t seed(const nlohmann::json& j, const std::string& field) const {
        const char* range = "a whole number 0 to 18446744073709551615";
        if (j.is_number_unsigned()) return j.get<std::uint64_t>();
        if (j.is_number_integer() && j.get<std::int64_t>() >= 0) return j.get<std::uint64_t>();
        if (j.is_number_float()) {
            const double v = j.get<double>();
            if (v >= 0 && v == std::floor(v) && v < 9007199254740992.0) return std::uint64_t(v);
        }
        fail(field, "expected a seed", &j, range);
    }
    // `n` numbers [a, b, ...], each in `r`.
    std::vector<float> numbers(const nlohmann::json& j, const std::string& field, std::size_t n,
                               const std::vector<Range>& ranges, const std::string& form) const {
        if (!j.is_array() || j.size() != n)
            fail(field, "expected " + std::to_string(n) + " numbers " + form, &j);
        std::vector<float> out;
        for (std::size_t i = 0; i < n; ++i)
            out.push_back(number(j[i], join(field, std::to_string(i)), ranges[i]));
        return out;
    }
    vec3 point(const nlohmann::json& j, const std::string& field) const {
        const Range any = anyNumber();
        const auto v = numbers(j, field, 3, {any, any, any}, "[x, y, z]");
        return vec3(v[0], v[1], v[2]);
    }
    vec2 pair(const nlohmann::json& j, const std::string& field, const Range& r) const {
        const auto v = numbers(j, field, 2, {r, r}, "[x, y]");
        return vec2(v[0], v[1]);
    }

    static std::string join(const std::string& field, const std::string& key) {
        return field.empty() ? key : field + "/" + key;
    }
    const std::string& file() const { return file_; }

private:
    std::string file_;
};

}  // namespace plantarch::project
