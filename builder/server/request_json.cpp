// Request bodies as JSON: a first pass over the text (nlohmann's SAX parser, which does not
// recurse) refuses nesting deeper than kMaxRequestDepth, so that nothing done with the parsed
// value afterwards (dump, copy, compare: all recursive) can overflow the stack, and names the
// field of a number beyond a double's range; then the text is parsed. Values quoted in
// messages are cut short.

#include <algorithm>

#include "builder/server/server_impl.h"

namespace plantarch::builder {

namespace {

// Follows where the parser is (a JSON pointer) and stops it at the first container nested
// deeper than the limit or at the first error, keeping a one-line reason.
class Scan : public nlohmann::json_sax<json> {
public:
    explicit Scan(const std::string& text) : text_(text) {}

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(false); }
    bool start_array(std::size_t) override { return open(true); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }
    bool key(string_t& k) override {
        if (!stack_.empty()) stack_.back().key = clip(k, 40);
        return true;
    }
    bool parse_error(std::size_t position, const std::string& token,
                     const nlohmann::detail::exception& e) override {
        const std::string at = where();
        if (e.id == 406)  // out_of_range: a number beyond a double's range
            problem_ = (at.empty() ? "" : at + " = ") + clip(token, 40) +
                       ": a number beyond the range of numbers (valid: numbers of at most about "
                       "1.8e308 in size; each field's own range is smaller)";
        else {
            std::string why = e.what();
            if (const auto colon = why.find(": "); colon != std::string::npos)
                why = why.substr(colon + 2);
            problem_ = "the request body is not JSON: " + clip(why, 160) + " (line " +
                       std::to_string(lineAt(position)) + ")";
        }
        return false;
    }

    const std::string& problem() const { return problem_; }

private:
    struct Frame {
        bool array = false;
        std::string key;
        std::size_t index = 0;  ///< arrays: the index of the next value
    };

    bool value() {
        if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
        return true;
    }
    bool open(bool array) {
        if (stack_.size() >= kMaxRequestDepth) {
            const std::string at = where();
            problem_ = (at.empty() ? "the request body" : at) +
                       ": JSON nested too deep (valid: arrays and objects nested at most " +
                       std::to_string(kMaxRequestDepth) + " deep)";
            return false;
        }
        stack_.push_back({array, "", 0});
        return true;
    }
    bool close() {
        if (!stack_.empty()) stack_.pop_back();
        return value();  // the container was a value of its parent
    }
    // The pointer of the value being read, at most 8 parts.
    std::string where() const {
        std::string out;
        for (std::size_t i = 0; i < stack_.size(); ++i) {
            if (i == 8) return out + "/...";
            if (i) out += '/';
            out += stack_[i].array ? std::to_string(stack_[i].index) : stack_[i].key;
        }
        return out;
    }
    int lineAt(std::size_t position) const {
        const auto end = text_.begin() + std::ptrdiff_t(std::min(position, text_.size()));
        return 1 + int(std::count(text_.begin(), end, '\n'));
    }

    const std::string& text_;
    std::vector<Frame> stack_;
    std::string problem_;
};

}  // namespace

std::string clip(const std::string& text, std::size_t max) {
    // Line breaks as \n, other control characters as '?': one line whatever the request holds
    // (its path too: cpp-httplib decodes %0a).
    std::string out;
    for (const char c : text.size() <= max ? text : text.substr(0, max)) {
        if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else
            out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
    }
    return text.size() <= max ? out : out + "...";
}

std::string shownJSON(const json& value) {
    // Within kMaxRequestDepth, so dump() recurses no deeper; a long value is cut.
    std::string text;
    if (value.is_structured() && value.size() > 8) {
        json head = value.is_array() ? json::array() : json::object();
        std::size_t n = 0;
        for (auto it = value.begin(); it != value.end() && n < 8; ++it, ++n) {
            if (value.is_array())
                head.push_back(*it);
            else
                head[it.key()] = *it;
        }
        text = head.dump(-1, ' ', false, json::error_handler_t::replace);
        if (text.size() <= 60) text += " ...";
    } else {
        text = value.dump(-1, ' ', false, json::error_handler_t::replace);
    }
    return clip(text, 60);
}

json bodyJSON(const httplib::Request& req) {
    Scan scan(req.body);
    if (!json::sax_parse(req.body, &scan)) throw HttpError{400, scan.problem()};
    json j = json::parse(req.body);
    if (!j.is_object()) throw HttpError{400, "the request body is not a JSON object {...}"};
    return j;
}

}  // namespace plantarch::builder
