#pragma once
// Turning side organs out of solid obstacles (see clearance.cpp).

#include "collision/collision_state.h"

namespace plantarch::collision {

class World;

/// Sets the clearance turns of the plant's petioles, peduncles and (with fruit adjustment)
/// fruit from its current shape; organs clear of every obstacle get no turn.
void clearOrgans(const Worker& worker, const World& world, PlantInstance& plant);

}  // namespace plantarch::collision
