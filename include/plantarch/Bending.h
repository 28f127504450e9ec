#pragma once
// Shoots bending under load (docs/measured-plants.md, "Shoots bending under load"): each
// shoot a chain of elastic rods, one per internode, loaded by its own weight, its leaves,
// petioles, flowers and fruit and the shoots growing from it, bent to its large-deflection
// equilibrium. A plant whose species enables `mechanics` is bent after every growth step;
// these functions bend a plant now, and pull one of its nodes with a force or move it by a
// displacement (a hand or a robot pulling a branch), giving the forces that takes.
//
// The result is state (each internode's InternodeBend, kept in plant structure files) and
// geometry (the plant is tessellated again). Deterministic: no random numbers, one thread.
// Every bad argument (unknown plant, shoot or node; a force or displacement that is not
// finite or is out of range) throws plantarch::Error and changes nothing.

#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch {

class PlantArchitecture;

/// What a pull did. Forces in N and moments in N m, world axes; positions in m.
struct PullResult {
    vec3 position{0.0f};      ///< where the node is now
    vec3 displacement{0.0f};  ///< how far it moved from where its plant's weight alone holds it
    vec3 force{0.0f};         ///< the force on the node (given, or the one found to move it)
    vec3 nodeReaction{0.0f};  ///< what the node pushes back with on whatever pulls it (-force)
    /// At the pulled shoot's base: the force and moment (about its base node) its support
    /// (the parent's node, or the ground) exerts on it, weight and pull together.
    vec3 baseForce{0.0f};
    vec3 baseMoment{0.0f};
    /// The same at the plant's base (the ground on the base stem).
    vec3 groundForce{0.0f};
    vec3 groundMoment{0.0f};
    unsigned iterations = 0;  ///< fixed-point iterations of the last solve
};

/// Bends the plant's shoots under their own load now, with its mechanics parameters (used
/// whether `enabled` is set or not), and regenerates its geometry.
void bendPlant(PlantArchitecture& arch, unsigned plantID);

/// Puts the plant back in its rest shape (removes every bend) and regenerates its geometry.
void straightenPlant(PlantArchitecture& arch, unsigned plantID);

/// Pulls node `node` of shoot `shootID` (the top of its internode `node`, where that
/// phytomer's petioles are) with `force` (N, world, each component within +-1e6), on top of
/// the plant's weight, and leaves the plant bent so.
PullResult pullNode(PlantArchitecture& arch, unsigned plantID, unsigned shootID, unsigned node,
                    const vec3& force);

/// Moves that node by `displacement` (m, world, each component within +-100) from where the
/// plant's weight alone holds it, finding the force that does it, and leaves the plant bent
/// so. Internodes do not stretch: the force is found across the node's internode, for the
/// displacement's part across it (the part along it is not imposed: the node goes along the
/// internode where the bending takes it; PullResult::displacement says where). A displacement
/// the shoots cannot bend to throws plantarch::Error.
PullResult displaceNode(PlantArchitecture& arch, unsigned plantID, unsigned shootID, unsigned node,
                        const vec3& displacement);

/// The positions of a shoot's nodes as drawn (0: its base; node k of the pull functions is
/// k + 1 here), bends applied, m: PlantArchitecture::getNodePosition's positions, all at once.
std::vector<vec3> bentNodePositions(const PlantArchitecture& arch, unsigned plantID,
                                    unsigned shootID);

}  // namespace plantarch
