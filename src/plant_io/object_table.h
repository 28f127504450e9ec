#pragma once
// The object table (docs/formats.md, "Object table"): a JSON file that maps each object ID of
// a mesh to its labels and, for plant organs, to the element of the plant structure file
// that describes the organ.

#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/PlantState.h"

namespace plantarch::io {

/// The table of the objects an export of `context` writes (hidden ones too with
/// `includeHidden`), in increasing ID order; objects of `plants` also get their place in the
/// plant structure file.
std::string objectTableJSON(const Context& context, const std::vector<const PlantInstance*>& plants,
                            bool includeHidden);

}  // namespace plantarch::io
