#pragma once
// Leaf photosynthesis from the light a leaf absorbs, its temperature and the air's CO2: the
// C3 model of Farquhar, von Caemmerer and Berry (1980) with the temperature responses of
// Bernacchi et al. (2001) and a peaked Arrhenius response for electron transport (Medlyn et
// al. 2002), or a non-rectangular light-response hyperbola. Rates in µmol CO2 m⁻² s⁻¹ per
// square metre of leaf (one side); light in µmol photons m⁻² s⁻¹ of absorbed PAR.
// docs/physiology.md gives the equations and the sources of every default.

namespace plantarch {

/// The Farquhar–von Caemmerer–Berry model's parameters at 25 °C and their temperature
/// responses. Defaults: a well-fed C3 crop leaf (Vcmax 100 as measured on crop leaves,
/// Wullschleger 1993; Jmax 1.75 × Vcmax, Medlyn et al. 2002; Rd 0.015 × Vcmax, Collatz et
/// al. 1991).
struct FarquharParameters {
    double vcmax25 = 100.0;  ///< maximum carboxylation rate, µmol m⁻² s⁻¹
    double jmax25 = 175.0;   ///< maximum electron transport rate, µmol m⁻² s⁻¹
    double rd25 = 1.5;       ///< day respiration, µmol m⁻² s⁻¹
    /// Electrons per absorbed photon (0.5 × 0.85 of the photons reach photosystem II).
    double quantumYield = 0.425;
    double curvature = 0.7;  ///< θ of the electron transport's light response
    /// Intercellular over ambient CO2 (stomata not modelled: a C3 leaf's usual 0.7).
    double ciOverCa = 0.7;
    double oxygen = 210.0;  ///< mmol mol⁻¹
    // Bernacchi et al. (2001): values at 25 °C and activation energies (kJ mol⁻¹).
    double kc25 = 404.9, kcEnergy = 79.43;            ///< Rubisco's Km for CO2, µmol mol⁻¹
    double ko25 = 278.4, koEnergy = 36.38;            ///< Rubisco's Km for O2, mmol mol⁻¹
    double gammaStar25 = 42.75, gammaEnergy = 37.83;  ///< CO2 compensation point without Rd
    double vcmaxEnergy = 65.33;                       ///< Vcmax's activation energy
    double rdEnergy = 46.39;                          ///< day respiration's activation energy
    // Medlyn et al. (2002): Jmax's peaked response.
    double jmaxEnergy = 50.0;         ///< activation, kJ mol⁻¹
    double jmaxDeactivation = 200.0;  ///< kJ mol⁻¹
    double jmaxEntropy = 0.65;        ///< kJ mol⁻¹ K⁻¹
};

/// One leaf's rates (µmol m⁻² s⁻¹).
struct LeafPhotosynthesis {
    double gross = 0.0;  ///< min(Rubisco-limited, electron-transport-limited) carboxylation
    double net = 0.0;    ///< gross - day respiration (negative in the dark)
    double respiration = 0.0;
    bool lightLimited = false;  ///< electron transport, not Rubisco, sets the rate
};

/// Net photosynthesis of a C3 leaf absorbing `absorbedPar` (µmol m⁻² s⁻¹) at
/// `leafTemperature` (°C) in air of `co2` (µmol mol⁻¹). Throws plantarch::Error for values
/// out of range (light under 0 or not finite, temperature outside -50 to 70 °C, CO2 outside 0
/// to 100000, parameters not positive where they must be).
LeafPhotosynthesis farquhar(const FarquharParameters& p, double absorbedPar, double leafTemperature,
                            double co2 = 420.0);

/// The mean net photosynthesis of a surface partly in the sun (the light model's triangle,
/// LightResult): its shaded part absorbs `absorbed - absorbedDirect`, its sunlit share
/// `sunlitFraction` that and `absorbedDirect / sunlitFraction` more. Averaging the rates of
/// the two parts, not the light, matters: the response saturates.
LeafPhotosynthesis farquharSunlitShaded(const FarquharParameters& p, double absorbed,
                                        double absorbedDirect, double sunlitFraction,
                                        double leafTemperature, double co2 = 420.0);

/// A fitted light-response curve's parameters (lightResponse).
struct LightResponseParameters {
    double alpha = 0.05;       ///< initial slope, mol CO2 per mol of absorbed photons
    double pmax = 25.0;        ///< light-saturated gross rate, µmol m⁻² s⁻¹
    double curvature = 0.7;    ///< θ, 0 to 1
    double respiration = 1.0;  ///< µmol m⁻² s⁻¹
};
/// A non-rectangular hyperbola: gross = (αI + Pmax - sqrt((αI + Pmax)² - 4θαI Pmax)) / 2θ,
/// net = gross - respiration, for users with fitted light-response curves. Throws
/// plantarch::Error for values out of range.
LeafPhotosynthesis lightResponse(const LightResponseParameters& p, double absorbedPar);

}  // namespace plantarch
