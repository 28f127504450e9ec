// Named per-phytomer functions of the library species: Nut trees (almond and its training
// variants, pistachio, walnut).

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

namespace {

// Almond: a shoot whose internodes are shorter than 1 cm is a spur, a short fruiting shoot
// that grows only a few nodes a year from its tip. Its nodes do not branch and carry no
// axillary flowers (the spur flowers at its tip, from its terminal buds), its leaves are
// 80 % of the full size, and the shoot makes at most 7 nodes per season.
constexpr float kSpurInternodeLength = 0.01f;  // m
constexpr int kSpurNodesPerSeason = 7;
constexpr float kSpurLeafScale = 0.8f;

void almondPhytomer(PhytomerCreationContext& c) {
    if (c.phytomer.internode.length >= kSpurInternodeLength) return;
    killVegetativeBuds(c.phytomer);
    killFloralBuds(c.phytomer);
    for (Petiole& p : c.phytomer.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= kSpurLeafScale;
    c.shoot.maxNodesPerSeason = kSpurNodesPerSeason;
}

// Walnut: the first four nodes of every scaffold and branch are blind (no branch, no
// flower); shoots branch and bear only further out.
constexpr unsigned kWalnutBlindNodes = 4;

void walnutPhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex >= kWalnutBlindNodes) return;
    killVegetativeBuds(c.phytomer);
    killFloralBuds(c.phytomer);
}

// Pistachio: the first node of a shoot is blind.
void pistachioPhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex != 0) return;
    killVegetativeBuds(c.phytomer);
    killFloralBuds(c.phytomer);
}

// Pistachio bears its fruit clusters laterally on older wood: during dormancy the floral buds
// of every node except the three nearest the shoot tip are made ready again (dormant,
// unopened), so they can flower in the coming season even where they flowered, fruited or
// failed before. The previous inflorescence's geometry goes when the bud next flowers.
constexpr unsigned kPistachioDistalNodesSkipped = 3;

void pistachioDormantFloralBuds(PhytomerCallbackContext& c) {
    if (c.plant.stage != PhenologyStage::Dormant) return;
    if (c.nodeIndex + kPistachioDistalNodesSkipped >= c.shoot.phytomers.size()) return;
    for (Petiole& p : c.phytomer.petioles)
        for (FloralBud& b : p.floralBuds) {
            if (b.stage == FloralStage::Bud && b.state == BudState::Dormant) continue;
            b.stage = FloralStage::Bud;
            b.state = BudState::Dormant;
            b.nextTime = -1.0;  // scheduled when dormancy breaks
            b.fruitAge = 0.0f;
            b.fruitGrowth = 1.0f;
        }
}

}  // namespace

void registerTrees(PlantArchitecture& arch) {
    arch.registerPhytomerCreationFunction("almond_phytomer", almondPhytomer);
    arch.registerPhytomerCreationFunction("walnut_phytomer", walnutPhytomer);
    arch.registerPhytomerCreationFunction("pistachio_phytomer", pistachioPhytomer);
    arch.registerPhytomerCallbackFunction("pistachio_dormant_floral_buds",
                                          pistachioDormantFloralBuds);
}

}  // namespace plantarch::species_functions
