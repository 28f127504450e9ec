#pragma once
// Node rules (NodeRule in plantarch/Parameters.h): generic, data-driven changes of phytomers
// by position, rank, age and season, run as a phytomer is made and at every whole day of
// plant age. Species files list them; docs/species-format.md describes each one.

#include <functional>
#include <map>
#include <string>

#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"

namespace plantarch::rules {

/// Runs the creation rules of `pp` on the newest phytomer of `shoot`.
void applyAtCreation(PlantInstance& plant, Shoot& shoot, const PhytomerParameters& pp);

/// True when a shoot type has daily or winter rules (the plant then needs a daily event).
bool hasDailyRules(const std::map<std::string, ShootParameters>& types);

/// Runs the daily and winter rules of `pp` on phytomer `node` of `shoot` at plant age `age`.
/// `nodeBase` gives the world position of the base of that phytomer's internode (asked only
/// when a rule needs the node's height).
void applyDaily(PlantInstance& plant, Shoot& shoot, unsigned node, const PhytomerParameters& pp,
                double age, const std::function<vec3()>& nodeBase);

}  // namespace plantarch::rules
