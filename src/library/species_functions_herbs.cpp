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

// Removes a phytomer's leaves together with their petioles (a petiole of zero size is not
// drawn); the node keeps its buds.
void removeLeaves(Phytomer& ph) {
    for (Petiole& p : ph.petioles) {
        for (LeafOrgan& l : p.leaves) l.removed = true;
        p.length = 0.0f;
        p.radius = 0.0f;
    }
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

// Cherry tomato (trained on a string, indeterminate): the first 8 nodes of every shoot, and
// all of shoots of rank 2 and up, neither branch nor flower. Leaves made early start smaller
// (70 %, full size from day 15), and so do internodes (70 %, full length from day 10).
void cherryTomatoPhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex < 8 || c.shoot.rank > 1) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    const float age = float(c.plantAge);
    scaleLeaves(c.phytomer, std::min(1.0f, 0.7f + 0.3f * age / 15.0f));
    c.phytomer.internode.length *= std::min(1.0f, 0.7f + 0.3f * age / 10.0f);
}

// Cherry tomato pruning: from day 101 on, the leaves (with their petioles) of every node
// whose internode starts below 1 m are stripped, as growers clear the lower canopy.
constexpr double kCherryTomatoPruningAge = 101.0;
constexpr float kCherryTomatoPruningHeight = 1.0f;

void cherryTomatoPruning(PhytomerCallbackContext& c) {
    if (c.plantAge < kCherryTomatoPruningAge) return;
    if (c.nodeBase.z - c.plant.base.z < kCherryTomatoPruningHeight) removeLeaves(c.phytomer);
}

// Capsicum: the main stem's first 6 nodes are bare (no leaf, petiole, branch or flower);
// shoots of rank 2 and up neither branch nor flower. Leaves grow with the node, from 60 % of
// full size at node 0 to full size at node 5; main-stem internodes made at emergence are 5 %
// of full length, full length from day 15.
void capsicumPhytomer(PhytomerCreationContext& c) {
    if (c.shoot.rank == 0 && c.nodeIndex < 6) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
        removeLeaves(c.phytomer);
    }
    if (c.shoot.rank >= 2) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    scaleLeaves(c.phytomer, std::min(1.0f, 0.6f + 0.4f * float(c.nodeIndex) / 5.0f));
    if (c.shoot.rank == 0)
        c.phytomer.internode.length *= std::min(1.0f, 0.05f + 0.95f * float(c.plantAge) / 15.0f);
}

}  // namespace

void registerHerbs(PlantArchitecture& arch) {
    arch.registerPhytomerCreationFunction("tomato_phytomer", tomatoPhytomer);
    arch.registerPhytomerCreationFunction("cherrytomato_phytomer", cherryTomatoPhytomer);
    arch.registerPhytomerCallbackFunction("cherrytomato_pruning", cherryTomatoPruning);
    arch.registerPhytomerCreationFunction("capsicum_phytomer", capsicumPhytomer);
}

}  // namespace plantarch::species_functions
