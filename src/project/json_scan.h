#pragma once
// A scan of JSON text before it is parsed, for what nlohmann's parser handles badly: nesting so
// deep that anything recursive on the parsed value (dump, copy, compare) overflows the stack,
// numbers beyond a double's range (the parser throws out_of_range without saying where), and
// text that is not UTF-8 at all (UTF-16 or UTF-32). The scan is iterative and linear; it does
// not check the syntax (the parser does).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace plantarch::project {

/// Arrays and objects nested deeper than this are refused (a project needs 4).
inline constexpr std::size_t kMaxJSONDepth = 64;

struct JSONScan {
    /// The encoding when the text is UTF-16 or UTF-32 ("UTF-16"), else "".
    std::string encoding;
    /// Set when an array or object is nested deeper than the limit: where it starts.
    bool tooDeep = false;
    std::string deepField;  ///< JSON pointer without its leading '/', cut after a few parts
    int deepLine = 0;
    /// A number beyond a double's range (1e400).
    struct Overflow {
        std::string field;  ///< JSON pointer without its leading '/'
        int line = 0;
        std::string token;       ///< the number as written (cut short)
        std::size_t offset = 0;  ///< of the number in the text
        std::size_t length = 0;  ///< of the number in the text
        bool negative = false;
    };
    std::vector<Overflow> overflows;
};

/// Scans `text` (stops at the first nesting deeper than `maxDepth`).
JSONScan scanJSON(std::string_view text, std::size_t maxDepth = kMaxJSONDepth);

/// `text` as valid UTF-8 (each byte of an invalid sequence shown as '?') of at most `max`
/// bytes, "..." added when cut; for quoting user text in one-line messages.
std::string printable(std::string_view text, std::size_t max);

}  // namespace plantarch::project
