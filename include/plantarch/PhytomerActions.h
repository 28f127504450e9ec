#pragma once
// What a species node rule does to one phytomer, offered to phytomer creation functions in
// C++ and Python so that a hand-written rule does exactly what the same rule in a species
// file does.

#include "plantarch/PlantState.h"

namespace plantarch {

/// Marks the phytomer's dormant axillary vegetative buds dead: no branch grows from this node
/// (a bud that is already active or broken keeps growing). The `remove_vegetative_buds` rule.
void killVegetativeBuds(Phytomer& phytomer);
/// Marks the phytomer's unopened floral buds dead and removed: no flowers from this node
/// (open flowers and fruit stay). The `remove_floral_buds` rule.
void killFloralBuds(Phytomer& phytomer);
/// Removes the phytomer's leaves, with their petioles' length and radius. The
/// `remove_leaves` rule.
void removeLeaves(Phytomer& phytomer);
/// Multiplies the full-grown size of the phytomer's leaves, and the length and radius of
/// their petioles, by `factor` (a petiole's curvature is divided by it, so it bends by the
/// same angle). The `leaf_scale` rule. Throws plantarch::Error, changing nothing, for a
/// factor that is not finite or that would take a leaf's size or a petiole's length or radius
/// out of its declared range (a negative one, with any leaf).
void scaleLeaves(Phytomer& phytomer, float factor);

}  // namespace plantarch
