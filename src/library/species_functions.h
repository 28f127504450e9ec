// Named per-phytomer functions of the library species, grouped by plant family; each group
// registers its own functions. Species files refer to them by name.
#pragma once

namespace plantarch {

class PlantArchitecture;
struct Phytomer;

namespace species_functions {

/// Marks the dormant axillary vegetative buds of a phytomer dead (no branch from this node).
void killVegetativeBuds(Phytomer& ph);
/// Marks the unopened floral buds of a phytomer dead (no flowers from this node).
void killFloralBuds(Phytomer& ph);

void registerLegumes(PlantArchitecture& arch);  // species_functions.cpp
void registerTrees(PlantArchitecture& arch);    // species_functions_trees.cpp
void registerOrchard(PlantArchitecture& arch);  // species_functions_orchard.cpp
void registerHerbs(PlantArchitecture& arch);    // species_functions_herbs.cpp

}  // namespace species_functions

/// Registers every group's functions with `arch` (species_functions.cpp).
void registerSpeciesFunctions(PlantArchitecture& arch);

}  // namespace plantarch
