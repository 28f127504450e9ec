// Named per-phytomer functions of the library species: Orchard and ornamental trees (almond, apple, olive, pistachio, walnut, eastern redbud).

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

void registerTrees(PlantArchitecture& arch) {
    (void)arch;
}

}  // namespace plantarch::species_functions
