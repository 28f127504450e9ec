#pragma once
// The plants of a PlantArchitecture as the glTF and USD writers describe them.

#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

/// Every plant of `arch`: its ID, species, base, age, and the scene's seed.
std::vector<GltfPlant> exportPlants(const PlantArchitecture& arch);

}  // namespace plantarch
