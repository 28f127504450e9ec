#pragma once
// Internal state of PlantArchitecture shared by its implementation files: the plants, the
// shoot types, the prototype registries and the prototype cache.

#include <map>
#include <memory>
#include <string>

#include "plantarch/PlantArchitecture.h"

namespace plantarch {

/// Prototypes built once per (function, parameters, leaflet index, variant) and placed by
/// transform, so a canopy does not rebuild a leaf mesh per leaf.
class PrototypeCache {
public:
    std::shared_ptr<const OrganPrototype> find(const std::string& key) const;
    void insert(const std::string& key, std::shared_ptr<const OrganPrototype> proto);
    std::size_t size() const { return entries_.size(); }
    void clear() { entries_.clear(); }

private:
    std::map<std::string, std::shared_ptr<const OrganPrototype>> entries_;
};

struct PlantArchitecture::Impl {
    std::map<std::string, ShootParameters> shootTypes;
    std::map<unsigned, PlantInstance> plants;
    unsigned nextPlantID = 0;
    std::map<std::string, LeafPrototypeFunction> leafPrototypes;
    std::map<std::string, FloralPrototypeFunction> floralPrototypes;
    PrototypeCache cache;

    PlantInstance& plant(unsigned id);
    const PlantInstance& plant(unsigned id) const;
    Shoot& shoot(PlantInstance& p, unsigned shootID);
    const Shoot& shoot(const PlantInstance& p, unsigned shootID) const;
    /// The plant's copy of a shoot type, taken from the global table on first use.
    const ShootParameters& shootTypeFor(PlantInstance& p, const std::string& label);
    /// Throws if a prototype function named by the parameters is not registered.
    void checkFunctions(const ShootParameters& params, const std::string& label) const;
};

// Builtin organ prototypes (geometry/builtin_prototypes.cpp).
void registerBuiltinPrototypes(PlantArchitecture& arch);

// Geometry regeneration (geometry/tessellate.cpp).
void tessellatePlant(PlantArchitecture::Impl& impl, Context& ctx, PlantInstance& plant);
/// Deletes the objects of every organ of a shoot from the Context (before pruning it).
void deleteShootObjects(Context& ctx, Shoot& shoot);
void deletePhytomerObjects(Context& ctx, Phytomer& phytomer);
/// World positions of the nodes of a shoot: [0] its base, [i+1] the tip of internode i.
std::vector<vec3> shootNodePositions(const PlantInstance& plant, unsigned shootID);

}  // namespace plantarch
