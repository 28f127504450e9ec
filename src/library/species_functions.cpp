// Named per-phytomer functions used by the library species, registered in every
// PlantArchitecture. Species files refer to them by name.

#include "library/species_functions.h"

#include <algorithm>

#include "model/architecture_impl.h"

namespace plantarch {
namespace species_functions {

void killVegetativeBuds(Phytomer& ph) {
    for (Petiole& p : ph.petioles)
        for (VegetativeBud& b : p.vegetativeBuds)
            if (b.state == BudState::Dormant) b.state = BudState::Dead;
}

void killFloralBuds(Phytomer& ph) {
    for (Petiole& p : ph.petioles)
        for (FloralBud& b : p.floralBuds)
            if (b.stage == FloralStage::Bud) {
                b.state = BudState::Dead;
                b.stage = FloralStage::Removed;
            }
}

namespace {

// Legumes (bean, cowpea, soybean): the six lowest nodes of the main stem and its branches
// branch but do not flower, higher nodes and higher-order shoots flower but do not branch.
// Early leaves are smaller (60 % at emergence, full size by day 8) and the main stem's
// first internodes shorter (20 % at emergence, full length by day 10).
void legumePhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex > 5 || c.shoot.rank > 1)
        killVegetativeBuds(c.phytomer);
    else
        killFloralBuds(c.phytomer);
    const float leafScale = std::min(1.0f, 0.6f + 0.4f * float(c.plantAge) / 8.0f);
    for (Petiole& p : c.phytomer.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= leafScale;
    if (c.shoot.rank == 0)
        c.phytomer.internode.length *= std::min(1.0f, 0.2f + 0.8f * float(c.plantAge) / 10.0f);
}

}  // namespace

void registerLegumes(PlantArchitecture& arch) {
    arch.registerPhytomerCreationFunction("legume_phytomer", legumePhytomer);
}

}  // namespace species_functions

void registerSpeciesFunctions(PlantArchitecture& arch) {
    species_functions::registerLegumes(arch);
    species_functions::registerTrees(arch);
    species_functions::registerOrchard(arch);
    species_functions::registerHerbs(arch);
}

}  // namespace plantarch
