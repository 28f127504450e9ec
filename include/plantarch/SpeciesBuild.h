#pragma once
// From a species to a plant through the manual building API: its shoot types defined in a
// PlantArchitecture and its <build> steps run on a plant (docs/species-format.md).
// PlantArchitecture::buildPlantInstanceFromLibrary does both; these are the two halves for a
// caller that builds by hand around them.

#include <map>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/Species.h"

namespace plantarch {

/// Defines every shoot type of the species in `arch` (PlantArchitecture::defineShootType), so
/// plants added afterwards can use them, with the files they name resolved
/// (speciesShootTypes). Errors (e.g. an unregistered prototype function) name the species
/// file.
void defineSpeciesShootTypes(PlantArchitecture& arch, const SpeciesModel& species);

/// Builds the species' initial structure (its <build> steps, in order) on plant `plantID`,
/// which must have no shoots yet, through addBaseStemShoot / appendShoot / addChildShoot.
/// The species' shoot types must be defined in `arch` before the plant was added
/// (defineSpeciesShootTypes). Returns the IDs of the shoots created, in creation order.
///
/// Random expressions in the steps draw from their own stream,
/// Rng::forPlant(arch.seed(), 2^62 + arch.plantStream(plantID)): deterministic per (seed, plant)
/// and independent of the plant's own stream, which the shoots created draw from as usual.
std::vector<unsigned> buildInitialStructure(PlantArchitecture& arch, unsigned plantID,
                                            const SpeciesModel& species,
                                            const std::map<std::string, float>& overrides = {});

}  // namespace plantarch
