// JSON documents as plantarch's JSON readers read them (json_document.h).

#include "project/json_document.h"

#include <algorithm>
#include <set>

#include "plantarch/Error.h"

namespace plantarch::project {

namespace {

using json = nlohmann::json;

int lineAt(const std::string& text, std::size_t offset) {
    const auto end = text.begin() + std::ptrdiff_t(std::min(offset, text.size()));
    return 1 + int(std::count(text.begin(), end, '\n'));
}

// The library's message without its "[json.exception...] ... : " prefix.
std::string reason(const char* what, const char* after) {
    std::string why = what;
    if (const auto at = why.find(after); at != std::string::npos)
        why = why.substr(at + std::char_traits<char>::length(after));
    return printable(why, 160);
}

}  // namespace

json parseJSONDocument(const std::string& text, const std::string& file, std::size_t maxDepth,
                       std::vector<JSONScan::Overflow>* overflows, const std::string& key) {
    JSONScan scan = scanJSON(text, maxDepth);
    if (!scan.encoding.empty())
        throw Error("not a JSON document: the text is " + scan.encoding,
                    {.file = file, .line = 1, .validRange = "UTF-8 text"});
    if (scan.tooDeep)
        throw Error("nested too deep", {.file = file,
                                        .line = scan.deepLine,
                                        .parameter = scan.deepField,
                                        .validRange = "arrays and objects nested at most " +
                                                      std::to_string(maxDepth) + " deep"});
    if (!scan.overflows.empty() && !overflows) {
        const JSONScan::Overflow& o = scan.overflows.front();
        throw Error("a number beyond a double's range", {.file = file,
                                                         .line = o.line,
                                                         .parameter = o.field,
                                                         .value = o.token,
                                                         .validRange = "a finite number"});
    }
    std::string substituted;
    if (!scan.overflows.empty()) {
        substituted = text;
        for (auto o = scan.overflows.rbegin(); o != scan.overflows.rend(); ++o)
            substituted.replace(o->offset, o->length, o->negative ? "-1e308" : "1e308");
    }
    const std::string& input = scan.overflows.empty() ? text : substituted;
    std::vector<std::set<std::string>> keys;
    std::string duplicate;
    const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::object_start) keys.emplace_back();
        if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
        if (event == json::parse_event_t::key && !keys.empty() && duplicate.empty() &&
            !keys.back().insert(parsed.get<std::string>()).second)
            duplicate = parsed.get<std::string>();
        return true;
    };
    json j;
    try {
        j = json::parse(input, callback);
    } catch (const json::parse_error& e) {
        throw Error("not a JSON document: " + reason(e.what(), ": "),
                    {.file = file, .line = lineAt(input, e.byte ? e.byte - 1 : 0)});
    } catch (const json::exception& e) {
        // Not expected after the scan (a number out of range is read as 1e308); one line.
        throw Error("not a JSON document: " + reason(e.what(), "] "), {.file = file});
    }
    if (!duplicate.empty()) {
        // The line of its second appearance in quotes.
        const std::string quoted =
            json(duplicate).dump(-1, ' ', false, json::error_handler_t::replace);
        const std::size_t first = input.find(quoted);
        const std::size_t second =
            first == std::string::npos ? first : input.find(quoted, first + quoted.size());
        throw Error("a " + key + " given twice",
                    {.file = file,
                     .line = second == std::string::npos ? 0 : lineAt(input, second),
                     .parameter = printable(duplicate, 160),
                     .validRange = "each " + key + " once per object"});
    }
    if (overflows) *overflows = std::move(scan.overflows);
    return j;
}

}  // namespace plantarch::project
