#pragma once
// The daily carbohydrate and nitrogen steps of one plant (docs/physiology.md). They change the
// plant's state only (pools, phyllochrons, bud break factors, aborted floral buds, leaf
// nitrogen); the caller measures the organs beforehand, then removes what they condemn
// (pruned shoots, aborted flowers' objects) and redraws.

#include <vector>

#include "plantarch/Physiology.h"
#include "plantarch/PlantState.h"

namespace plantarch::physiology {

/// What the caller measured of one shoot now (the wood from the state, the rest from the
/// drawn organs).
struct ShootMeasure {
    double woodVolume = 0.0;   ///< m³ of its internodes as they are now
    double woodCarbon = 0.0;   ///< mol C of structure in them
    double leafArea = 0.0;     ///< m² of its leaves (one side)
    double fruitVolume = 0.0;  ///< m³ of its fruit
    unsigned flowers = 0;      ///< flowers it has formed (open, closed or set as fruit)
    double input = 0.0;        ///< mol C its leaves fixed (net) since the last step
};

/// A floral bud the budget aborted: where it was and the objects to delete.
struct AbortedBud {
    unsigned shoot = 0, node = 0, petiole = 0, index = 0;
    bool terminal = false;
};

/// What one carbon step decided besides the pools.
struct CarbonActions {
    std::vector<unsigned> prune;  ///< shoots that die (with everything growing from them)
    std::vector<AbortedBud> aborted;
};

/// The structural carbon of `volume` m³ of wood, mol C (stem density times its carbon share
/// less the non-structural share).
double woodCarbon(const CarbohydrateParameters& p, double volume);

/// Gives every live shoot without pools its starting pools: the species' initial
/// concentration of its wood, with its organs as now counted as already paid for. Returns
/// the carbon added (mol C).
double startCarbon(PlantInstance& plant, const std::vector<ShootMeasure>& measures);

/// One step of `days` (> 0, at most 1) at mean air temperature `temperature` (°C): input,
/// maintenance, growth costs, starch, transfer, phyllochron, bud break, abortion and death.
/// `measures` is indexed by shoot ID. Adds the step's fluxes to `record` (its pools are set
/// to the totals after the step). Shoots already removed lose their pools (as losses).
CarbonActions stepCarbon(PlantInstance& plant, const std::vector<ShootMeasure>& measures,
                         double temperature, double days, PhysiologyRecord& record);

/// One leaf as the nitrogen step sees it.
struct LeafMeasure {
    LeafOrgan* leaf = nullptr;
    double area = 0.0;  ///< m² (one side), 0 for a leaf without geometry yet
};

/// Starts the plant's nitrogen: the available pool from the species' initial value, each leaf
/// at the initial content per area.
void startNitrogen(PlantInstance& plant, const std::vector<LeafMeasure>& leaves);

/// One nitrogen step of `days`: uptake by leaves, remobilisation from old leaves to young
/// ones, the fruit's demand (`fruitArea`: the plant's fruit surface now, m²), the stress
/// factor. Adds its fluxes to `record`.
void stepNitrogen(PlantInstance& plant, const std::vector<LeafMeasure>& leaves, double fruitArea,
                  double days, PhysiologyRecord& record);

/// Adds fertiliser nitrogen (g N): the roots keep root_allocation of it, the rest becomes
/// available.
void addNitrogen(PlantInstance& plant, double grams);

}  // namespace plantarch::physiology
