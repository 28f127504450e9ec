#include "plantarch/Error.h"

namespace plantarch {

namespace {

// A value longer than this is shown by its start and its length, so that a hostile or
// generated input cannot turn one error line into pages.
constexpr std::size_t kMaxShownValue = 120;

std::string shownValue(const std::string& value) {
    if (value.size() <= kMaxShownValue) return value;
    std::size_t cut = kMaxShownValue;
    // Never cut a UTF-8 character in two: back off over continuation bytes.
    while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xC0) == 0x80) --cut;
    return value.substr(0, cut) + "... (" + std::to_string(value.size()) + " characters)";
}

}  // namespace

std::string formatError(const std::string& message, const ErrorContext& c) {
    std::string out;
    if (!c.file.empty()) {
        out.append(c.file);
        if (c.line > 0) out.append(":").append(std::to_string(c.line));
        out.append(": ");
    }
    if (!c.parameter.empty()) {
        out.append(c.parameter);
        if (!c.value.empty()) out.append(" = ").append(shownValue(c.value));
        out.append(": ");
    } else if (!c.value.empty()) {
        out.append("'").append(shownValue(c.value)).append("': ");
    }
    out.append(message);
    if (!c.validRange.empty()) out.append(" (valid: ").append(c.validRange).append(")");
    // Keep it to one line whatever the pieces held.
    for (char& ch : out)
        if (ch == '\n' || ch == '\r') ch = ' ';
    return out;
}

Error::Error(const std::string& message, ErrorContext context)
    : std::runtime_error(formatError(message, context)),
      message_(message),
      context_(std::move(context)) {}

Error Error::withFile(const std::string& file, int line) const {
    if (!context_.file.empty()) return *this;
    ErrorContext c = context_;
    c.file = file;
    if (c.line == 0) c.line = line;
    return Error(message_, c);
}

Error Error::withParameterPrefix(const std::string& prefix) const {
    ErrorContext c = context_;
    c.parameter = c.parameter.empty() ? prefix : prefix + "." + c.parameter;
    return Error(message_, c);
}

namespace {

std::string budgetMessage(const std::string& what, std::size_t estimate, std::size_t limit,
                          const std::string& how) {
    return what + " needs about " + std::to_string(estimate) + " triangles" +
           (how.empty() ? "" : " (" + how + ")") + ", over the triangle limit of " +
           std::to_string(limit);
}

}  // namespace

TriangleBudgetError::TriangleBudgetError(const std::string& what, std::size_t estimate,
                                         std::size_t limit, const std::string& how)
    : Error(budgetMessage(what, estimate, limit, how)), estimate_(estimate), limit_(limit) {}

}  // namespace plantarch
