#pragma once
// Carrying a plant's state to another place, orientation and clock, driven by the state table
// (plantarch/PlantStateTable.h): every direction it declares turns, every plant age it declares
// moves, so a field added there is carried too (PlantArchitecture::duplicatePlantInstance).

#include "core/math.h"
#include "plantarch/PlantState.h"

namespace plantarch {

struct PlantMove {
    glm::mat3 rotation{1.0f};  ///< about the plant's base
    vec3 base{0.0f};           ///< where the base stands afterwards
    double age = 0.0;          ///< plant age afterwards, days
};

/// Turns every direction of the plant's state (the unit-vector fields) by `move.rotation`,
/// moves its own attraction points with its base and turns them about it, and sets its age,
/// moving every plant age it holds by the same amount: scheduled times stay unscheduled
/// (negative) and never move before age 0; times past move freely. Object IDs, ID, stream
/// and random generator are left to the caller.
void movePlant(PlantInstance& plant, const PlantMove& move);

}  // namespace plantarch
