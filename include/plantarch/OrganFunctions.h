#pragma once
// The functions a shoot type can name: organ prototype builders (leaves, flowers, fruit) and
// the per-phytomer rules (a creation function run once per new phytomer, a callback run every
// whole day). PlantArchitecture registers them by name (registerLeafPrototype,
// registerFloralPrototype, registerPhytomerCreationFunction,
// registerPhytomerCallbackFunction); species files and shoot types refer to those names.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"
#include "plantarch/Random.h"

namespace plantarch {

/// One piece of an organ prototype: geometry in prototype units (unit length along +x, base
/// at the origin, +z up) and its material. A flower may have several (petals, centre).
struct PrototypePart {
    Mesh mesh;
    Material material;
};
using OrganPrototype = std::vector<PrototypePart>;

/// Builds a leaf prototype. `leafletIndex`: 0 tip, negative left, positive right.
using LeafPrototypeFunction =
    std::function<OrganPrototype(const LeafPrototype& params, Rng& rng, int leafletIndex)>;
/// What a flower or fruit prototype is asked to build.
struct FloralPrototypeRequest {
    bool fruit = false;  ///< a fruit (else a flower)
    bool open = true;    ///< for flowers: open (else a closed bud)
    /// Family shape parameters from the species (may be empty: family defaults apply).
    std::map<std::string, float> parameters;
    vec3 color{1.0f};           ///< main colour from the species
    unsigned subdivisions = 8;  ///< mesh resolution
};
/// Builds a flower or fruit prototype in prototype units (length 1 along +x).
using FloralPrototypeFunction =
    std::function<OrganPrototype(const FloralPrototypeRequest& request, Rng& rng)>;

/// What a phytomer creation function sees: the new phytomer (which it may change: kill
/// buds, scale organs, remove leaves) and where it stands.
struct PhytomerCreationContext {
    PlantInstance& plant;
    Shoot& shoot;
    Phytomer& phytomer;
    unsigned nodeIndex;   ///< index of the new phytomer on its shoot
    int parentNodeIndex;  ///< node of the parent shoot this shoot grows from (-1: none)
    int shootMaxNodes;    ///< the shoot's realized max_nodes
    double plantAge;      ///< days
};
using PhytomerCreationFunction = std::function<void(PhytomerCreationContext&)>;

/// What a phytomer callback sees, once per phytomer at every whole day of plant age (it may
/// change the phytomer: remove leaves, kill buds).
struct PhytomerCallbackContext {
    PlantInstance& plant;
    Shoot& shoot;
    Phytomer& phytomer;
    unsigned nodeIndex;
    double plantAge;  ///< days
    /// World position of the base of the phytomer's internode at this age (organs elongated
    /// to their size on this day); its height above the plant is nodeBase.z - plant.base.z.
    vec3 nodeBase{0.0f};
};
using PhytomerCallbackFunction = std::function<void(PhytomerCallbackContext&)>;

}  // namespace plantarch
