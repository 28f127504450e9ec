// Named per-phytomer functions of the library species: Nut trees (almond and its training variants, pistachio, walnut).

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

void registerTrees(PlantArchitecture& arch) {
    (void)arch;
}

}  // namespace plantarch::species_functions
