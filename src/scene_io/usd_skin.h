#pragma once
// Skinned plants in USD (UsdOptions::skeletons): UsdSkel. A skinned plant's prim is a SkelRoot
// holding a Skeleton (its joints as paths, bind and rest transforms) and meshes bound to it
// (SkelBindingAPI, skel:skeleton, primvars:skel:jointIndices and jointWeights, four per
// vertex). docs/formats.md, "Skinned plants".

#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"

namespace plantarch::io {

/// Checks options.skeletons before a write: joints with an earlier parent (the root none)
/// and a finite place, objects bound to joints the skeleton has, one influence per vertex,
/// weights >= 0. Throws plantarch::Error naming `file`.
void checkUsdSkins(const UsdOptions& options, const Context& context, const std::string& file);

/// The skeleton of plant `plant` in options.skeletons, or null.
const GltfSkeleton* usdSkeletonOf(const UsdOptions& options, std::int32_t plant);

/// The Skeleton prim named "skeleton" of a plant whose prim is placed at `base` (its joints'
/// transforms relative to that), indented for a child of the plant's prim.
std::string usdSkeleton(const GltfSkeleton& skeleton, vec3 base);

/// The binding of a mesh of `objects` (its points in that order) to the skeleton at
/// `skeletonPath`: skel:skeleton and four joint indices and weights per vertex.
std::string usdSkinBinding(const GltfSkeleton& skeleton, const Context& context,
                           const std::vector<ObjectID>& objects, const std::string& skeletonPath);

}  // namespace plantarch::io
