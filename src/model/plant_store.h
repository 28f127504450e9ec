#pragma once
// The plants of one PlantArchitecture by ID, and the shoot types and phenology that plants
// added from now on start from.

#include <map>
#include <string>

#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"

namespace plantarch {

/// The range of PlantArchitecture::setMeshDetail.
inline constexpr float kMinMeshDetail = 0.1f, kMaxMeshDetail = 4.0f;

/// A resolution of `n` at mesh detail `detail`, never below `floor`: exactly `n` at detail 1.
inline unsigned detailed(unsigned n, float detail, unsigned floor) {
    if (detail == 1.0f) return n;
    const float scaled = float(n) * detail + 0.5f;
    return scaled < float(floor) ? floor : unsigned(scaled);
}

class PlantStore {
public:
    /// The shoot types by label. A plant takes a copy when it is added, and copies a type it
    /// does not hold yet from here on first use (shootTypeFor).
    std::map<std::string, ShootParameters> shootTypes;
    /// The phenological thresholds given to plants added from now on.
    PhenologyParameters defaultPhenology;
    std::map<unsigned, PlantInstance> plants;
    /// The ID the next plant gets (IDs are never reused).
    unsigned nextPlantID = 0;
    /// The ID of the first plant added since PlantArchitecture::restartPlantStreams (0 until
    /// then): a plant's random streams are numbered from it (stream()).
    unsigned streamBase = 0;
    /// The number of the random streams of the plant with this ID (Rng::forPlant(seed, n)).
    unsigned stream(unsigned id) const { return id - streamBase; }
    /// Ground clearance of plants added from now on (setGroundClearance).
    bool groundClearance = true;
    /// The factor on every organ's mesh resolution (setMeshDetail).
    float meshDetail = 1.0f;
    /// Growth stops with TriangleBudgetError once a plant's organs need more triangles than
    /// this (0: no limit; PlantArchitecture::setTriangleLimit).
    std::size_t triangleLimit = 0;

    /// The plant with this ID; throws naming the valid IDs.
    PlantInstance& plant(unsigned id);
    const PlantInstance& plant(unsigned id) const;
    /// A shoot of `p` that exists (not removed); throws naming the valid IDs.
    static Shoot& shoot(PlantInstance& p, unsigned shootID);
    static const Shoot& shoot(const PlantInstance& p, unsigned shootID);
    /// The plant's copy of a shoot type, taken from this table on first use; throws naming
    /// the known labels. Only the plant changes, so threads growing different plants may
    /// call it at once.
    const ShootParameters& shootTypeFor(PlantInstance& p, const std::string& label) const;
};

}  // namespace plantarch
