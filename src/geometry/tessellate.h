#pragma once
// A plant's geometry in the Context, regenerated from its state (tessellate.cpp).

#include <vector>

#include "geometry/prototype_cache.h"
#include "model/plant_store.h"
#include "plantarch/Context.h"

namespace plantarch {

/// Regenerates the plant's objects in `ctx` from its state: organs keep their object IDs,
/// organs with no geometry now lose theirs.
void tessellatePlant(const PlantStore& store, PrototypeCache& prototypes, Context& ctx,
                     PlantInstance& plant);
/// Deletes the objects of every organ of a shoot from the Context (before pruning it).
void deleteShootObjects(Context& ctx, Shoot& shoot);
void deletePhytomerObjects(Context& ctx, Phytomer& phytomer);
/// Degrees per metre of a petiole at `fraction` of its full length: a growing petiole keeps the
/// shape it has full grown (a bend of curvature x full length in all), as its leaves do.
inline float petioleBendRate(const Petiole& pt, float fraction) {
    return fraction > 0.0f ? pt.curvature / fraction : pt.curvature;
}
/// World positions of the nodes of a shoot: [0] its base, [i+1] the tip of internode i.
std::vector<vec3> shootNodePositions(const PlantInstance& plant, unsigned shootID);

}  // namespace plantarch
