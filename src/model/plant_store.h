#pragma once
// The plants of one PlantArchitecture by ID, and the shoot types and phenology that plants
// added from now on start from.

#include <array>
#include <map>
#include <optional>
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

// Below a mesh detail of 0.5 the subdivisions' floors (3 sides to a tube, 4 rows to a leaf)
// would stop the meshes from getting coarser, so organs are thinned further: each organ
// prototype (leaf, flower, fruit) is simplified to coarseShare(detail) of its triangles, and
// each tube drawn with coarseSegments() of its segments. Both are 1 (no change) from 0.5 up,
// so that the meshes shrink steadily down to the lowest detail (0.1: about 1/25 of each
// prototype's triangles, a tube of 1 segment in 5).
inline constexpr float kCoarseDetail = 0.5f;
inline float coarseShare(float detail) {
    if (detail >= kCoarseDetail) return 1.0f;
    const float f = detail / kCoarseDetail;
    return f * f;
}
inline unsigned coarseSegments(unsigned segments, float detail) {
    if (detail >= kCoarseDetail) return segments;
    const float scaled = float(segments) * detail / kCoarseDetail + 0.5f;
    return scaled < 1.0f ? 1u : unsigned(scaled);
}

class PlantStore {
public:
    /// The shoot types by label. A plant takes a copy when it is added, and copies a type it
    /// does not hold yet from here on first use (shootTypeFor).
    std::map<std::string, ShootParameters> shootTypes;
    /// The phenological thresholds given to plants added from now on.
    PhenologyParameters defaultPhenology;
    std::map<unsigned, PlantInstance> plants;
    /// The random stream number the next plant gets (PlantInstance::stream): plants count
    /// from 0, or from PlantArchitecture::restartPlantStreams. IDs come from the Context.
    unsigned nextStream = 0;
    /// The ID the next plant gets instead of one from the Context (a canopy worker building
    /// plant i of IDs the caller reserved); used once.
    std::optional<unsigned> assignedID;
    /// Ground clearance of plants added from now on (setGroundClearance).
    bool groundClearance = true;
    /// Ground clipping (enableGroundClipping): leaves, flowers and fruit that reach below this
    /// height (m) fall off, side shoots growing into it are pruned. None: off.
    std::optional<float> groundClipping;
    /// Organ kinds whose geometry the Context gets (setOrganGeometry); all by default.
    std::array<bool, kOrganKinds> organGeometry = [] {
        std::array<bool, kOrganKinds> all;
        all.fill(true);
        return all;
    }();
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
