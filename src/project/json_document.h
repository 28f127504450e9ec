#pragma once
// JSON text read as plantarch's JSON readers read it (projects, skeletons, fit targets): the
// text scanned first (json_scan.h: encoding, nesting, numbers beyond a double's range), then
// parsed with a key given twice in one object an error; every problem one plantarch::Error
// naming the file and, where it can, the line.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "project/json_scan.h"

namespace plantarch::project {

/// The document in `text` (`file` names it in errors), nested at most `maxDepth` deep.
/// Numbers beyond a double's range: with `overflows` null, the first is an error; else each is
/// read as 1e308 of its sign (out of every field's range) and listed in *overflows for the
/// caller to name. `key` is what errors call a key ("field", "key").
nlohmann::json parseJSONDocument(const std::string& text, const std::string& file,
                                 std::size_t maxDepth, std::vector<JSONScan::Overflow>* overflows,
                                 const std::string& key = "field");

}  // namespace plantarch::project
