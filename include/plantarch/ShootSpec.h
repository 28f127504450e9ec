#pragma once
// What a manual-building call of PlantArchitecture (addBaseStemShoot, appendShoot,
// addChildShoot, appendPhytomerToShoot) is given: where a shoot starts and how large its new
// phytomers are.

#include <optional>
#include <string>
#include <vector>

#include "plantarch/PlantState.h"

namespace plantarch {

/// Size of the phytomers a manual-building call makes. Errors name the specification's
/// argument names, given in brackets.
struct PhytomerSize {
    float internodeRadius = 0.001f;     ///< m, (0, 10] (internode_radius)
    float internodeLengthMax = 0.02f;   ///< full-grown internode length, m, [0, 100]
                                        ///< (internode_length_max)
    float internodeLengthScale = 1.0f;  ///< current / full internode length, (0, 1]
                                        ///< (internode_length_scale_factor_fraction)
    float leafScale = 1.0f;             ///< current / full petiole and leaf size, (0, 1]
                                        ///< (leaf_scale_factor_fraction)
};

/// Where and how a new shoot starts: the options of addBaseStemShoot, appendShoot and
/// addChildShoot. Errors name the specification's argument names, given in brackets.
struct ShootSpec {
    unsigned phytomers = 1;     ///< phytomers to create now, 1 to 100000 (current_node_number)
    AxisRotation baseRotation;  ///< degrees (base_rotation)
    PhytomerSize size;          ///< size of the phytomers created
    float radiusTaper = 0.0f;   ///< tip radius reduction along the shoot, [0, 1] (radius_taper)
    std::string shootType;      ///< label given to defineShootType (shoot_type_label)
};

/// The leaves measured at one node of a measured shoot (MeasuredShootOptions::leaves).
struct MeasuredLeaf {
    unsigned node = 0;  ///< the phytomer (0 for the first internode's)
    /// The way the blade faces (any length > 0; pointing down, taken as its opposite): its
    /// leaves are posed so their mean normal stands so (LeafOrgan::angleTarget). None: as the
    /// species places them.
    std::optional<vec3> normal;
    /// The blade's length, m, [0, 10]; its leaflets keep their proportions (0: the species').
    float length = 0.0f;
};

/// Options of PlantArchitecture::addShootFromNodePositions. Errors name the option.
struct MeasuredShootOptions {
    /// Petiole and leaf size of the measured phytomers now, as a fraction of full size,
    /// (0, 1] (leaf_scale); below 1 they grow on as young leaves do.
    float leafScale = 1.0f;
    /// How far the first point may be from where the shoot starts (the plant's base, or
    /// the parent's node), m, [0, 10] (attach_tolerance).
    float attachTolerance = 0.01f;
    /// A shoot from a parent continues its tip (as appendShoot, `parentNode` its last node)
    /// instead of growing from the axil of `petioleIndex` at `parentNode` (continue_parent).
    bool continueParent = false;
    unsigned petioleIndex = 0;  ///< axil of a lateral shoot (petiole_index)
    /// Phytomers (0 for the first internode's) measured bare: their leaves are removed, with
    /// their petioles' length and radius (bare_nodes).
    std::vector<unsigned> bareNodes;
    /// Leaves measured at nodes: the way their blades face and their length (leaves).
    std::vector<MeasuredLeaf> leaves;
};

}  // namespace plantarch
