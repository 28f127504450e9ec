// The value text of JSON fields' errors (json_fields.h).

#include "project/json_fields.h"

#include <cmath>

#include "project/json_scan.h"

namespace plantarch::project {

namespace {

using json = nlohmann::json;

// JSON text of `v` (compact, as dump() writes it), stopping once `out` holds more than `max`
// bytes. The text was parsed within project::kMaxJSONDepth, so this recurses no deeper.
void dumpShort(const json& v, std::string& out, std::size_t max) {
    if (!v.is_structured()) {
        out += v.dump(-1, ' ', false, json::error_handler_t::replace);
        return;
    }
    out += v.is_array() ? '[' : '{';
    for (auto it = v.begin(); it != v.end() && out.size() <= max; ++it) {
        if (it != v.begin()) out += ',';
        if (v.is_object())
            out += json(it.key()).dump(-1, ' ', false, json::error_handler_t::replace) + ":";
        dumpShort(*it, out, max);
    }
    out += v.is_array() ? ']' : '}';
}

}  // namespace

std::string shownJSON(const json& v) {
    // A whole number written with a fraction or exponent (1e6) shown as a whole number.
    if (v.is_number_float() && std::isfinite(v.get<double>()) &&
        v.get<double>() == std::floor(v.get<double>()) && std::fabs(v.get<double>()) < 1e15)
        return std::to_string(std::int64_t(v.get<double>()));
    std::string text;
    dumpShort(v, text, 80);
    return project::printable(text, text.size() > 60 ? 57 : 60);
}

}  // namespace plantarch::project
