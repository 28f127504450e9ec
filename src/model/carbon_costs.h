#pragma once
// The carbon of wood and what building it costs (docs/physiology.md), shared by the budget,
// which charges growth, and growth, which limits thickening by what a shoot can pay.

#include <algorithm>

#include "plantarch/Parameters.h"

namespace plantarch::carbon {

inline constexpr double kCarbonMolarMass = 12.01;  // g mol⁻¹
inline constexpr double kMinVolume = 1e-9;         // m³: a concentration for shoots of no wood

/// The structural carbon of `volume` m³ of wood, mol C (stem density times its carbon share
/// less the non-structural share).
inline double woodCarbon(const CarbohydrateParameters& p, double volume) {
    return p.stem_density *
           std::max(0.0, double(p.stem_carbon_fraction) - p.nonstructural_fraction) /
           kCarbonMolarMass * volume;
}

/// What building wood of `carbon` mol C costs the shoot: the wood, the roots grown with it
/// (shoot:root ratio) and the growth respiration of both, mol C.
inline double woodCost(const CarbohydrateParameters& p, double carbon) {
    return carbon * (1.0 + 1.0 / double(p.shoot_root_ratio)) *
           (1.0 + double(p.growth_respiration_fraction));
}

/// Pool amount (mol C) of a concentration (g C per g dry stem) in `volume` m³ of wood.
inline double amount(const CarbohydrateParameters& p, double concentration, double volume) {
    return concentration * p.stem_density * std::max(volume, kMinVolume) / kCarbonMolarMass;
}

}  // namespace plantarch::carbon
