// Named per-phytomer functions of the library species: Vegetable and cereal crops (tomato, capsicum, maize, sorghum, wheat, asparagus, lettuce).

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

void registerHerbs(PlantArchitecture& arch) {
    (void)arch;
}

}  // namespace plantarch::species_functions
