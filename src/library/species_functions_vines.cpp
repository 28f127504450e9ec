// Named per-phytomer functions of the library species: Grapevines.

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

void registerVines(PlantArchitecture& arch) {
    (void)arch;
}

}  // namespace plantarch::species_functions
