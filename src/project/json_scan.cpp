// The scan of JSON text before it is parsed (json_scan.h): nesting depth, numbers beyond a
// double's range, UTF-16 and UTF-32 text.

#include "project/json_scan.h"

#include <charconv>
#include <cstdint>

namespace plantarch::project {

namespace {

// The length of the valid UTF-8 sequence at `s[i]` (printable characters only: no control
// characters), or 0 when there is none.
std::size_t utf8Length(std::string_view s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = byte(i);
    if (c >= 0x20 && c < 0x7F) return 1;
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the valid range of the second byte
    if (c >= 0xC2 && c <= 0xDF)
        n = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0) lo = 0xA0;  // no overlong forms
        if (c == 0xED) hi = 0x9F;  // no surrogates
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;  // at most U+10FFFF
    } else
        return 0;
    if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    return n;
}

// Whether a number's text whose conversion is out of range is too large (not too small): the
// decimal exponent of its first significant digit is positive.
bool tooLarge(std::string_view number) {
    std::size_t i = number.starts_with('-') ? 1 : 0;
    long long lead = 0;  // decimal places of the first significant digit before the point
    bool point = false, significant = false;
    for (; i < number.size() && number[i] != 'e' && number[i] != 'E'; ++i) {
        if (number[i] == '.') {
            point = true;
            continue;
        }
        if (number[i] != '0') significant = true;
        if (!point && significant) ++lead;
        if (point && !significant) --lead;
    }
    long long exponent = 0;
    bool negative = false;
    if (i < number.size()) ++i;
    if (i < number.size() && (number[i] == '+' || number[i] == '-')) negative = number[i++] == '-';
    for (; i < number.size() && exponent < 1000000000; ++i)
        if (number[i] >= '0' && number[i] <= '9') exponent = exponent * 10 + (number[i] - '0');
    return (negative ? -exponent : exponent) + lead > 0;
}

std::string encodingOf(std::string_view t) {
    if (t.size() >= 4 &&
        ((t[0] == 0 && t[1] == 0 && t[2] == 0) || (t[1] == 0 && t[2] == 0 && t[3] == 0)))
        return "UTF-32";
    if (t.size() >= 4 && ((t.substr(0, 4) == std::string_view("\xFF\xFE\0\0", 4)) ||
                          t.substr(0, 4) == std::string_view("\0\0\xFE\xFF", 4)))
        return "UTF-32";
    if (t.size() >= 2 &&
        (t[0] == 0 || t[1] == 0 || t.starts_with("\xFF\xFE") || t.starts_with("\xFE\xFF")))
        return "UTF-16";
    return "";
}

struct Frame {
    bool array = false;
    std::string key;  ///< objects: the key of the value being read (cut short)
    std::size_t index = 0;
};

// The JSON pointer of the value being read at the top of `stack`, at most `maxParts` parts.
std::string pointer(const std::vector<Frame>& stack, std::size_t maxParts) {
    std::string out;
    for (std::size_t i = 0; i < stack.size(); ++i) {
        if (i == maxParts) return out + "/...";
        if (i) out += '/';
        out += stack[i].array ? std::to_string(stack[i].index) : printable(stack[i].key, 40);
    }
    return out;
}

bool isNumberChar(char c) {
    return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' || c == 'E';
}

}  // namespace

std::string printable(std::string_view text, std::size_t max) {
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = utf8Length(text, i);
        if (out.size() + std::max<std::size_t>(n, 1) > max) return out + "...";
        if (n == 0) {
            out += '?';
            ++i;
        } else {
            out.append(text.substr(i, n));
            i += n;
        }
    }
    return out;
}

JSONScan scanJSON(std::string_view t, std::size_t maxDepth) {
    JSONScan s;
    s.encoding = encodingOf(t);
    if (!s.encoding.empty()) return s;
    std::vector<Frame> stack;
    std::string last;  // the last string read: a key once a ':' follows
    int line = 1;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const char c = t[i];
        if (c == '\n') {
            ++line;
        } else if (c == '"') {
            last.clear();
            std::size_t j = i + 1;
            for (; j < t.size() && t[j] != '"'; ++j) {
                if (t[j] == '\\' && j + 1 < t.size()) {
                    if (last.size() < 200) last += t[j];
                    ++j;
                }
                if (t[j] == '\n') ++line;
                if (last.size() < 200) last += t[j];
            }
            i = j;
        } else if (c == '{' || c == '[') {
            if (stack.size() >= maxDepth) {
                s.tooDeep = true;
                s.deepField = pointer(stack, 8);
                s.deepLine = line;
                return s;
            }
            stack.push_back({c == '[', "", 0});
        } else if (c == '}' || c == ']') {
            if (!stack.empty()) stack.pop_back();
        } else if (c == ',') {
            if (!stack.empty() && stack.back().array) ++stack.back().index;
            if (!stack.empty() && !stack.back().array) stack.back().key.clear();
        } else if (c == ':') {
            if (!stack.empty() && !stack.back().array) stack.back().key = last;
        } else if (c == '-' || (c >= '0' && c <= '9')) {
            std::size_t j = i;
            while (j < t.size() && isNumberChar(t[j])) ++j;
            const std::string_view number = t.substr(i, j - i);
            // Short numbers without an exponent are always in range.
            if (number.size() > 15 || number.find_first_of("eE") != std::string_view::npos) {
                double v = 0.0;
                const auto r = std::from_chars(number.data() + (number[0] == '-' ? 1 : 0),
                                               number.data() + number.size(), v);
                if (r.ec == std::errc::result_out_of_range && tooLarge(number))
                    s.overflows.push_back({pointer(stack, 64), line, printable(number, 40), i,
                                           number.size(), number[0] == '-'});
            }
            i = j - 1;
        }
    }
    return s;
}

}  // namespace plantarch::project
