#pragma once
// The angles of a `<helios>` file as the reference system draws them (docs/plant-xml.md,
// "Angle conventions of <helios> files"). Its files give each organ's angles relative to
// frames that the reference system rebuilds organ by organ: an internode turns from the one
// before by -1.25 times its pitch about the axis across the previous internode and petiole,
// its segments bend by the shoot's gravitropic curvature and the listed perturbations, a
// petiole leaves the internode's first direction by its pitch about that axis turned by the
// phyllotactic angle, and a leaf is turned about fixed world axes. Reading, poseAsReference()
// turns all of it into plantarch's own frames (internode directions, petiole azimuths and
// pitches, leaf angles), so that plantarch draws what the reference system drew from the
// file; writing, referenceAngles() finds the file's angles that make the reference system
// draw what plantarch draws.

#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plant_io/plant_structure.h"

namespace plantarch::plant_io {

/// What a `<helios>` file says of an internode beyond plantarch's state ...
struct HeliosInternode {
    float pitch = 0.0f;            ///< degrees (`<internode_pitch>`)
    float phyllotaxis = 0.0f;      ///< degrees (`<internode_phyllotactic_angle>`)
    unsigned segments = 1;         ///< `<internode_length_segments>`
    std::vector<float> curvature;  ///< degrees per segment (`<curvature_perturbations>`)
    std::vector<float> yaw;        ///< degrees per segment (`<yaw_perturbations>`)
};

/// ... of a petiole ...
struct HeliosPetiole {
    float pitch = 0.0f;          ///< degrees (`<petiole_pitch>`)
    unsigned segments = 1;       ///< `<petiole_length_segments>`
    float leafletOffset = 0.0f;  ///< fraction of the petiole between leaflet pairs
};

/// ... and of a leaf: its angles in the file, degrees, and where the reference's angles cannot
/// turn it as plantarch does (a single leaf or a tip leaflet faces the mirror image of its
/// petiole's azimuth there), plantarch's own pitch, yaw and roll (`<leaf_angles>`).
struct HeliosLeaf {
    float pitch = 0.0f, yaw = 0.0f, roll = 0.0f;
    std::optional<vec3> own;
};

/// The file's side of one plant, by organ (addresses stay valid while it is read or written).
struct HeliosExtras {
    std::unordered_map<const Shoot*, AxisRotation> baseRotations;  ///< degrees
    std::unordered_map<const Internode*, HeliosInternode> internodes;
    std::unordered_map<const Petiole*, HeliosPetiole> petioles;
    std::unordered_map<const LeafOrgan*, HeliosLeaf> leaves;
};

/// The leaflet index of leaf `i` of `n` listed left to right: 0 the tip, negative on the left,
/// positive on the right; an even count has no tip (-n/2 ... -1, 1 ... n/2).
int leafletIndexOf(int i, int n);

/// Reading: sets the frames of every internode, petiole and leaf of `plant` (read from a
/// `<helios>` file with its values in `extras`, not yet completed) so that plantarch draws
/// what the reference system draws from the file, and notes each member set in `given`.
/// Shoot types (for the gravitropic curvature the reference adds to each internode segment)
/// come from `shootTypes` (may be null: none). A parent reference out of range (left to
/// checkPlant) is posed as a base shoot.
void poseAsReference(PlantInstance& plant, const HeliosExtras& extras,
                     const std::map<std::string, ShootParameters>* shootTypes, Presence& given);

/// Writing: the file's values of every organ of `plant` that make the reference system draw
/// the plant as plantarch draws it (internode, petiole and leaf directions; what the layout
/// cannot hold, such as a tip leaflet's roll on a compound leaf, is lost). Removed shoots are
/// posed too, so that the values of the others do not depend on them.
HeliosExtras referenceAngles(const PlantInstance& plant);

}  // namespace plantarch::plant_io
