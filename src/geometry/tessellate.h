#pragma once
// A plant's geometry in the Context, regenerated from its state (tessellate.cpp).

#include <algorithm>
#include <limits>
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
/// (At a vanishing fraction the rate is held to the largest float, not infinity.)
inline float petioleBendRate(const Petiole& pt, float fraction) {
    if (!(fraction > 0.0f)) return pt.curvature;
    constexpr double kMax = std::numeric_limits<float>::max();
    return float(std::clamp(double(pt.curvature) / double(fraction), -kMax, kMax));
}
/// World positions of the nodes of a shoot as its geometry stands (each internode turned by
/// its bend under load, if any): [0] its base, [i+1] the tip of internode i.
std::vector<vec3> shootNodePositions(const PlantInstance& plant, unsigned shootID);

}  // namespace plantarch
