// The line of each value of a JSON text (json_lines.h).

#include "calibration/json_lines.h"

#include <vector>

namespace plantarch::fit {

namespace {

struct LineFrame {
    bool array = false;
    bool expectKey = true;  ///< objects: the next string is a key
    std::string key;
    std::size_t index = 0;
};

std::string pointerOf(const std::vector<LineFrame>& stack) {
    std::string out;
    for (std::size_t i = 0; i < stack.size(); ++i) {
        if (i) out += '/';
        out += stack[i].array ? std::to_string(stack[i].index) : stack[i].key;
    }
    return out;
}

}  // namespace

JSONLines::JSONLines(std::string_view t) {
    std::vector<LineFrame> stack;
    int line = 1;
    // Keys are kept whole up to this length (longer ones are not found: their values get the
    // line of the enclosing object).
    constexpr std::size_t kMaxKey = 200;
    constexpr std::size_t kMaxValues = 1000000;
    const auto record = [&] {
        if (lines_.size() < kMaxValues) lines_.emplace(pointerOf(stack), line);
    };
    for (std::size_t i = 0; i < t.size(); ++i) {
        const char c = t[i];
        if (c == '\n') {
            ++line;
        } else if (c == '"') {
            const int startLine = line;
            std::string s;
            std::size_t j = i + 1;
            for (; j < t.size() && t[j] != '"'; ++j) {
                if (t[j] == '\\' && j + 1 < t.size()) ++j;
                if (t[j] == '\n') ++line;
                if (s.size() <= kMaxKey) s += t[j];
            }
            i = j;
            if (!stack.empty() && !stack.back().array && stack.back().expectKey) {
                stack.back().key = s;
                stack.back().expectKey = false;
            } else {
                const int now = line;
                line = startLine;
                record();
                line = now;
            }
        } else if (c == '{' || c == '[') {
            record();
            if (stack.size() >= 1000) return;  // deeper than any reader goes
            stack.push_back({c == '[', c == '{', "", 0});
        } else if (c == '}' || c == ']') {
            if (!stack.empty()) stack.pop_back();
        } else if (c == ',') {
            if (!stack.empty() && stack.back().array) ++stack.back().index;
            if (!stack.empty() && !stack.back().array) stack.back().expectKey = true;
        } else if (c == '-' || (c >= '0' && c <= '9') || c == 't' || c == 'f' || c == 'n') {
            record();
            while (i + 1 < t.size() && t[i + 1] != ',' && t[i + 1] != '}' && t[i + 1] != ']' &&
                   t[i + 1] != '\n' && t[i + 1] != ' ' && t[i + 1] != '\t' && t[i + 1] != '"')
                ++i;
        }
    }
}

int JSONLines::line(std::string pointer) const {
    for (;;) {
        if (const auto it = lines_.find(pointer); it != lines_.end()) return it->second;
        if (pointer.empty()) return 1;
        const auto slash = pointer.rfind('/');
        pointer = slash == std::string::npos ? std::string() : pointer.substr(0, slash);
    }
}

}  // namespace plantarch::fit
