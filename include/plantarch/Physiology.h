#pragma once
// A plant's physiology over time (docs/physiology.md): its leaves' photosynthesis from the
// light they absorb, a carbohydrate budget per shoot that pays for respiration and growth and
// slows, thins and kills what it cannot pay for, and a nitrogen model whose stress shrinks new
// leaves and lowers photosynthetic capacity. Switched on per plant
// (PlantArchitecture::enableCarbohydrateModel / enableNitrogenModel, or by growPhysiology for
// the plants of a species with `enabled` set); a plant with both off grows exactly as without
// them.

#include <cstdint>
#include <string>
#include <vector>

#include "plantarch/Light.h"
#include "plantarch/Progress.h"

namespace plantarch {

class PlantArchitecture;

/// One step of one plant (a day, or less), its fluxes over the step and its pools after it.
/// Carbon in mol C, nitrogen in g N. The carbon balance closes: the change in sugar + starch
/// over a step is input - maintenance - growth - growthRespiration - losses.
struct PhysiologyRecord {
    unsigned plant = 0;
    double age = 0.0;           ///< plant age at the end of the step, days
    double days = 0.0;          ///< the step's length
    double leafArea = 0.0;      ///< m² (one side) at the step's start
    double absorbedPar = 0.0;   ///< mol photons its leaves absorbed over the step
    double temperature = 20.0;  ///< mean air temperature of the step, °C
    // Carbon (zero while the budget is off).
    double input = 0.0;              ///< net photosynthesis of its leaves
    double maintenance = 0.0;        ///< maintenance respiration of wood and roots
    double growth = 0.0;             ///< carbon built into new wood, roots, leaves, flowers, fruit
    double growthRespiration = 0.0;  ///< respired building it
    double rootGrowth = 0.0;         ///< the part of growth that went to roots beyond their share
    double losses = 0.0;             ///< pools of shoots that died or were removed
    double sugar = 0.0;
    double starch = 0.0;
    unsigned shootsPruned = 0;  ///< shoots that died of starvation (with what grew from them)
    unsigned budsAborted = 0;   ///< floral buds (flowers, fruit) aborted
    // Nitrogen (zero while the model is off).
    double nitrogenAvailable = 0.0;    ///< the pool leaves draw from, after the step
    double nitrogenInLeaves = 0.0;     ///< after the step
    double nitrogenUptake = 0.0;       ///< taken by leaves from the pool over the step
    double nitrogenRemobilised = 0.0;  ///< moved from old leaves to young ones
    double nitrogenLost = 0.0;         ///< released by old leaves and not recovered
    double nitrogenToFruit = 0.0;
    double nitrogenShed = 0.0;    ///< in leaves shed or removed since the last step
    double nitrogenStress = 1.0;  ///< leaf N over its target, at most 1 (1: none)
};

/// The names of PhysiologyRecord's columns, in the order writePhysiologyCSV writes them.
std::vector<std::string> physiologyColumns();
/// One record's values in the columns' order.
std::vector<double> physiologyValues(const PhysiologyRecord& record);
/// Writes records as CSV (a header line, one line per record), atomically. Throws
/// plantarch::Error when the file cannot be written.
void writePhysiologyCSV(const std::string& path, const std::vector<PhysiologyRecord>& records);

/// How growPhysiology lights the scene and turns light into carbon.
struct PhysiologyOptions {
    Location location;
    /// Rays and optics; the leaves' optics are those of the first plant with a budget
    /// (its species' leaf_reflectance and leaf_transmittance). Photosynthesis needs each
    /// leaf's light, not each triangle's: the light is sampled from 8 triangles of each
    /// object (LightOptions::samplesPerObject; 0 traces every triangle), each casting 16 sky
    /// and 8 scattering rays (a leaf's 128 and 64 in all; a bean season's carbon within 1 %
    /// of 64 and 32 per sample, at 0.55 of the cost).
    LightOptions light{.diffuseRays = 16, .scatterRays = 8, .samplesPerObject = 8};
    /// Compute the sky's light every `lightEvery` hours of daylight and use it for the hours
    /// in between (1: every hour); photosynthesis is still computed each hour.
    unsigned lightEvery = 1;
    double co2 = 420.0;  ///< µmol mol⁻¹, where the weather gives none
};

/// Grows every plant of `architecture` through the weather's days, one day per UTC date in
/// `weather` (consecutive dates; hours in time order): each day the scene's light is traced
/// (the plants, the ground and every other object of the Context), each leaf's hourly net
/// photosynthesis (Farquhar, with the species' capacities and its nitrogen) becomes its
/// shoot's input, and the plants grow one day with their budgets at the day's mean
/// temperature. First switches the models on for plants whose species has them `enabled`.
/// Plants without a budget grow as usual; a plant whose budget has died has no more records.
/// Returns the records of the days, in day and plant order. Throws plantarch::Error for weather
/// that is empty or skips a date.
std::vector<PhysiologyRecord> growPhysiology(PlantArchitecture& architecture,
                                             const std::vector<WeatherHour>& weather,
                                             const PhysiologyOptions& options);

}  // namespace plantarch

namespace plantarch {

// ---- a season ---------------------------------------------------------------------------------

/// Nitrogen added to each plant's available pool once the plant reaches an age.
struct Fertilisation {
    double age = 0.0;    ///< days, >= 0
    double grams = 0.0;  ///< g N per plant, > 0
};

/// A season of physiology for growPhysiologySeason: which models, where, the weather (given,
/// or clear days from a date), fertilisation, how often the light is traced.
struct PhysiologySeason {
    bool carbon = false;    ///< the carbohydrate budget
    bool nitrogen = false;  ///< the nitrogen model
    Location location;
    /// Weather hours (consecutive dates, one day of growth per date); when empty, clear days
    /// from `start` with `clearness`.
    std::vector<WeatherHour> weather;
    UTCTime start;            ///< the first clear day (its date; the hour is ignored)
    double clearness = 0.75;  ///< of the clear days, 0 to 1
    std::vector<Fertilisation> fertilise;
    unsigned lightEvery = 1;  ///< PhysiologyOptions::lightEvery
};

/// The date after `time`'s (the hour kept), across months, years and leap days.
UTCTime nextDate(UTCTime time);

/// Checks a season before any work: the place, the clear days' date and clearness, the
/// fertilisations (age >= 0, grams > 0, nitrogen on), lightEvery 1 to 24, at least one model.
/// Throws plantarch::Error naming the field.
void checkPhysiologySeason(const PhysiologySeason& season);

/// Switches the season's models on for `plants` and grows every plant of `architecture`
/// `days` whole days through the season's weather (growPhysiology), each plant of `plants`
/// given a fertilisation's nitrogen at the start of the first day it is at least that old.
/// `progress` (optional) gets ("physiology", share of days done); one that throws stops the
/// season between days. Returns the records of the days. Throws plantarch::Error when the
/// weather has fewer dates than `days`.
std::vector<PhysiologyRecord> growPhysiologySeason(PlantArchitecture& architecture,
                                                   const std::vector<unsigned>& plants,
                                                   const PhysiologySeason& season, unsigned days,
                                                   const ProgressCallback& progress = {});

}  // namespace plantarch
