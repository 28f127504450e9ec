#pragma once
// The XML text a reader is reading (species files, plant structure files): its name for error
// messages, the line of any node, and errors located there.

#include <algorithm>
#include <cstddef>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Error.h"

namespace plantarch {

/// Reads nothing itself; `text` must outlive it. Not thread-safe (line starts are found on
/// first use).
class XmlSource {
public:
    XmlSource(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

    const std::string& file() const { return file_; }

    /// Line (from 1) of a byte offset into the text.
    int lineAt(std::ptrdiff_t offset) const {
        if (offset < 0) return 1;
        if (lineStarts_.empty()) {
            lineStarts_.push_back(0);
            for (std::size_t i = 0; i < text_.size(); ++i)
                if (text_[i] == '\n') lineStarts_.push_back(std::ptrdiff_t(i + 1));
        }
        auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
        return int(it - lineStarts_.begin());
    }
    int line(pugi::xml_node n) const { return lineAt(n.offset_debug()); }

    /// An error at node `n` about the value at `path`.
    [[noreturn]] void fail(pugi::xml_node n, const std::string& path, const std::string& message,
                           std::string value = "", std::string validRange = "") const {
        throw Error(message, {.file = file_,
                              .line = line(n),
                              .parameter = path,
                              .value = std::move(value),
                              .validRange = std::move(validRange)});
    }

    /// An Error raised while converting a value, located at node `n` and, unless `path` is
    /// empty, the parameter path.
    [[noreturn]] void relocate(const Error& e, pugi::xml_node n, const std::string& path) const {
        ErrorContext c = e.context();
        c.file = file_;
        c.line = line(n);
        if (!path.empty()) c.parameter = path;
        throw Error(e.message(), c);
    }

private:
    std::string_view text_;
    std::string file_;
    mutable std::vector<std::ptrdiff_t> lineStarts_;
};

}  // namespace plantarch
