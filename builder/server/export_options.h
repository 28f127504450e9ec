#pragma once
// The variants of an export (docs/formats.md): materials and texture size, nodes and
// instancing, levels of detail, meshopt compression and skin, as a request names them,
// checked one field at a time with the command line's own checks and messages, and turned into
// the PlantFileOptions the writers take.

#include <string>
#include <vector>

#include "builder/server/server_impl.h"
#include "plantarch/PlantFiles.h"

namespace plantarch::builder {

/// The fields of an export's variant, in the order the API lists them: materials,
/// texture_size, atlas, nodes, instancing, lod, meshopt, skin.
const std::vector<std::string>& exportVariantFields();

/// The options of an export of `format` (an export format, "glb" ...) from the variant fields
/// of a JSON body (text for materials, nodes, instancing and lod; a whole number for
/// texture_size; true or false for atlas, meshopt and skin; other fields ignored). Throws
/// plantarch::Error (400) naming the first bad field, its value and what is valid, or a variant
/// `format` cannot hold.
PlantFileOptions exportVariant(const json& body, const std::string& format);

/// The same from a request's query parameters (all text; true, false, 1 or 0 for the flags).
PlantFileOptions exportVariant(const httplib::Request& req, const std::string& format);

}  // namespace plantarch::builder
