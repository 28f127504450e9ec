#pragma once
// The line of every value of a JSON text, by its JSON pointer (without the leading '/',
// "ages/0/height/sd"), so that a reader of the parsed value can name the line of a bad one.
// Like project/json_scan.h it does not check the syntax (the parser does); it is linear and
// iterative.

#include <map>
#include <string>
#include <string_view>

namespace plantarch::fit {

class JSONLines {
public:
    explicit JSONLines(std::string_view text);
    /// The line of the value at `pointer`, or of the nearest enclosing value that has one
    /// (1 when none has).
    int line(std::string pointer) const;

private:
    std::map<std::string, int> lines_;
};

}  // namespace plantarch::fit
