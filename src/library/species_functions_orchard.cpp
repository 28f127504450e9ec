// Named per-phytomer functions of the library species: trained fruit plants (olive, apple,
// eastern redbud, grapevine). Species files refer to them by name.

#include <cmath>
#include <cstdint>

#include "library/species_functions.h"
#include "model/architecture_impl.h"

namespace plantarch::species_functions {

namespace {

bool dormant(const PlantInstance& plant) {
    return plant.stage == PhenologyStage::Dormant;
}

// Olive (callback): while the tree is dormant, the floral buds of every node more than 8
// below the shoot's tip are removed, so only the ~8 most distal nodes of each shoot flower
// in the coming season.
void olivePhytomerCallback(PhytomerCallbackContext& c) {
    if (!dormant(c.plant)) return;
    if (std::size_t(c.nodeIndex) + 8 < c.shoot.phytomers.size()) killFloralBuds(c.phytomer);
}

// Apple (creation): a shoot whose full internode length is at its minimum (0.01 m) is a spur,
// a short shoot: its nodes make no branches and no axillary flowers (it flowers from its
// terminal bud), its leaves are 80 % of full size, and it makes at most 6 nodes a season.
// Internode girth is not capped at 5 mm here: a spur's leaves give it about 2.5 mm.
void applePhytomer(PhytomerCreationContext& c) {
    constexpr float kSpurInternode = 0.01f;
    if (c.phytomer.internode.length > kSpurInternode * 1.0001f) return;
    killVegetativeBuds(c.phytomer);
    killFloralBuds(c.phytomer);
    for (Petiole& p : c.phytomer.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= 0.8f;
    c.shoot.maxNodesPerSeason = std::min(c.shoot.maxNodesPerSeason, 6);
}

// The first whole day of plant age in the current dormant period: the day after the plant
// was made for its first winter (no callback runs on the day it is made), else the first
// whole day at or after the season's end.
bool firstDayOfWinter(const PlantInstance& plant, double age) {
    if (plant.nextDormancyBreak < 0.0) return false;
    const double start = plant.nextDormancyBreak - double(plant.phenology.time_to_dormancy_break);
    const double day = plant.season == 0 ? std::floor(start) + 1.0 : std::ceil(start - 1e-9);
    return std::abs(age - day) < 1e-6;
}

// Eastern redbud (callback): once each winter, every shoot draws N uniform in 2..4; its N
// most distal nodes lose their floral buds (they branch next spring) and the nodes below
// lose their vegetative buds (they flower on the old wood, as redbud does). N is drawn once
// per shoot and winter from the plant's random stream, at the callback of the shoot's base
// node, which applies the rule to the whole shoot.
void redbudPhytomerCallback(PhytomerCallbackContext& c) {
    if (!dormant(c.plant) || c.nodeIndex != 0 || !firstDayOfWinter(c.plant, c.plantAge)) return;
    const int n = int(c.shoot.phytomers.size());
    const int distal = c.plant.rng.uniformInt(2, 4);
    for (int k = 0; k < n; ++k) {
        if (k < n - distal)
            killVegetativeBuds(c.shoot.phytomers[std::size_t(k)]);
        else
            killFloralBuds(c.shoot.phytomers[std::size_t(k)]);
    }
}

// Grapevine (creation): clusters only at the first two nodes of a shoot; shoots of rank 1
// (growing from the trunk, canes or cordons) branch only from their first 8 nodes; shoots
// of rank 2 and above (laterals) neither branch nor flower.
void grapevinePhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex >= 2) killFloralBuds(c.phytomer);
    if (c.shoot.rank >= 2 || (c.shoot.rank >= 1 && c.nodeIndex >= 8)) {
        killVegetativeBuds(c.phytomer);
        killFloralBuds(c.phytomer);
    }
}

}  // namespace

void registerOrchard(PlantArchitecture& arch) {
    arch.registerPhytomerCallbackFunction("olive_phytomer_callback", olivePhytomerCallback);
    arch.registerPhytomerCreationFunction("apple_phytomer", applePhytomer);
    arch.registerPhytomerCallbackFunction("redbud_phytomer_callback", redbudPhytomerCallback);
    arch.registerPhytomerCreationFunction("grapevine_phytomer", grapevinePhytomer);
}

}  // namespace plantarch::species_functions
