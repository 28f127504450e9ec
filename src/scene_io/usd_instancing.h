#pragma once
// USD with Instancing::Gpu (usd_instancing.cpp): the organs of a plant that share a shape are
// the instances of one UsdGeomPointInstancer.

#include <map>
#include <string>
#include <vector>

#include "scene_io/organ_tracks.h"
#include "scene_io/usd_text.h"

namespace plantarch::io {

/// A PointInstancer "instances" under the plant prim at `plantPath` (its base at `base`), at 8
/// spaces, for the organs `tracks` of that plant whose shape (written at shapePaths) two or more
/// of them place: a prototype per shape (a Mesh referencing the shared one), and per instance
/// protoIndices, ids (object IDs), positions, orientations (quath) and orientationsf (quatf),
/// scales and the organ's labels as primvars (interpolation "vertex": one value per instance);
/// the instances' names in order in customData. Writes nothing when none is shared.
void writePointInstancer(Text& out, const OrganTracks& organs,
                         const std::vector<std::size_t>& tracks, vec3 base,
                         const std::string& plantPath,
                         const std::map<std::size_t, std::string>& shapePaths);

}  // namespace plantarch::io
