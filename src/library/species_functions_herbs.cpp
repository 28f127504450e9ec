// Named per-phytomer functions of the library species: vegetable and cereal crops (tomato,
// cherry tomato, capsicum, maize, sorghum, wheat, asparagus, butter lettuce).

#include <algorithm>

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

namespace {

void scaleLeaves(Phytomer& ph, float factor) {
    for (Petiole& p : ph.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= factor;
}

// Tomato: no flowers on the main stem's first 8 nodes; shoots of rank 2 and up neither branch
// nor flower. Leaves made early start smaller (50 % at emergence, full size from day 10), and
// so do internodes (70 %, full length from day 10).
void tomatoPhytomer(PhytomerCreationContext& c) {
    if (c.shoot.rank == 0 && c.nodeIndex < 8) killFloralBuds(c.phytomer);
    if (c.shoot.rank > 1) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    const float age = float(c.plantAge);
    scaleLeaves(c.phytomer, std::min(1.0f, 0.5f + 0.5f * age / 10.0f));
    c.phytomer.internode.length *= std::min(1.0f, 0.7f + 0.3f * age / 10.0f);
}

}  // namespace

void registerHerbs(PlantArchitecture& arch) {
    arch.registerPhytomerCreationFunction("tomato_phytomer", tomatoPhytomer);
}

}  // namespace plantarch::species_functions
