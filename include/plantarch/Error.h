#pragma once
// plantarch::Error: the one exception type for bad input and failed I/O.
//
// Every error a user can act on names where it happened (file, line), what was wrong
// (parameter path, value) and what would have been right (valid range). what() joins
// these into a single line such as
//   species/bean.xml:42: trifoliate.phytomer.petiole.pitch = 200: out of range (valid: -180 to 180)

#include <cstddef>
#include <stdexcept>
#include <string>

namespace plantarch {

/// Where and why an input was rejected. Every field is optional.
struct ErrorContext {
    std::string file;        ///< file being read or written
    int line = 0;            ///< 1-based line in that file, 0 if unknown
    std::string parameter;   ///< dotted parameter path, e.g. "trifoliate.max_nodes"
    std::string value;       ///< the offending value as text
    std::string validRange;  ///< what would be accepted, e.g. "0 to 1" or "one of: obj, ply"
};

/// Bad input or failed I/O. The message is one line; the CLI prints it and exits 2.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message, ErrorContext context = {});

    const std::string& message() const noexcept { return message_; }
    const ErrorContext& context() const noexcept { return context_; }
    const std::string& file() const noexcept { return context_.file; }
    int line() const noexcept { return context_.line; }
    const std::string& parameter() const noexcept { return context_.parameter; }
    const std::string& value() const noexcept { return context_.value; }
    const std::string& validRange() const noexcept { return context_.validRange; }

    /// The same error with a file (and line) filled in where it had none.
    Error withFile(const std::string& file, int line = 0) const;
    /// The same error with `prefix.` put in front of the parameter path.
    Error withParameterPrefix(const std::string& prefix) const;

private:
    std::string message_;
    ErrorContext context_;
};

/// A job stopped (or refused) because it needs more triangles than the triangle limit allows
/// (Context::setTriangleLimit, PlantArchitecture::setTriangleLimit; the CLI's
/// --max-triangles). Thrown before the work when it can be estimated (a canopy), else as soon
/// as the limit is passed (while growing or tessellating); the scene is left as it was.
class TriangleBudgetError : public Error {
public:
    /// `what` names the job ("canopy of 400 plants"); the message adds the estimate and limit.
    TriangleBudgetError(const std::string& what, std::size_t estimate, std::size_t limit,
                        const std::string& how = "");

    /// The triangles the job needs (or would have reached), as estimated.
    std::size_t estimate() const noexcept { return estimate_; }
    /// The limit it was held to.
    std::size_t limit() const noexcept { return limit_; }

private:
    std::size_t estimate_;
    std::size_t limit_;
};

/// Formats the one-line description used as what().
std::string formatError(const std::string& message, const ErrorContext& context);

}  // namespace plantarch
