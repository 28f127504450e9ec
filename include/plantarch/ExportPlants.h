#pragma once
// Exports that need the plants, not only their geometry: the plants as the glTF and USD
// writers describe them, and the internodes as QSM cylinders.

#include <string>
#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

/// Every plant of `arch`: its ID, species, base, age, and the scene's seed.
std::vector<GltfPlant> exportPlants(const PlantArchitecture& arch);

/// Writes the plants' internodes as cylinders, the table a quantitative structure model
/// (QSM, as TreeQSM makes from scans of trees) holds, as CSV with a header: one row per
/// internode with its id, parent cylinder, plant, start point, unit axis, length, radius,
/// branch (shoot ID), branch order (shoot rank), position in the branch and shoot type.
/// Written atomically; throws plantarch::Error naming the file.
void writeQSM(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
              const std::string& path);

}  // namespace plantarch
