#pragma once
// What the skeleton readers share (src/project/skeleton_files.cpp, mtg_files.cpp).

#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Error.h"
#include "plantarch/Skeleton.h"

namespace plantarch::skeleton {

/// The organ tags a node may carry: bare, flower, fruit.
const std::vector<std::string>& organTags();
/// "<"/"continue", "+"/"branch" or empty; anything else throws with `at`.
SkeletonLink parseLink(std::string_view text, const ErrorContext& at);
/// A shoot type label (letters, digits, '_', '-'; at most 64) or empty.
std::string checkedShootType(std::string_view text, const ErrorContext& at);
/// Tags separated by ';' or spaces, each one of organTags().
std::vector<std::string> parseOrgans(std::string_view text, const ErrorContext& at);
/// An MTG file (FORM-A) as a skeleton (mtg_files.cpp); not yet checked as a tree.
Skeleton readMTG(const std::string& text, const std::string& name);

}  // namespace plantarch::skeleton
