// Named per-phytomer functions of the library species: Trained fruit plants (olive, apple, eastern redbud, grapevine).

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

void registerOrchard(PlantArchitecture& arch) {
    (void)arch;
}

}  // namespace plantarch::species_functions
