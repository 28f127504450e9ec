#pragma once
// Counting organs that cross each other, to measure what soft avoidance achieves.

#include <cstddef>
#include <vector>

#include "plantarch/Context.h"

namespace plantarch::collision {

/// Number of pairs of the given objects whose triangles cross (touching does not count).
/// Pairs are found by a sweep over the objects' bounding boxes, then tested triangle by
/// triangle. Objects with the same non-negative group number are never counted as a pair
/// (leaflets of one leaf, which meet at their bases).
std::size_t countIntersectingPairs(const Context& ctx, const std::vector<ObjectID>& objects,
                                   const std::vector<long long>& groups = {});

/// Group numbers for leaves: one per petiole (plant, shoot, node), from the objects' data.
std::vector<long long> petioleGroups(const Context& ctx, const std::vector<ObjectID>& objects);

}  // namespace plantarch::collision
