#pragma once
// Internal state of PlantArchitecture shared by its implementation files: the plants, the
// shoot types, the prototype registries and the prototype cache.

#include <array>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <unordered_map>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/Species.h"

namespace plantarch {

namespace collision {
class World;
class AttractionIndex;
class ProxyCache;
struct Steering;
}  // namespace collision

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
    std::map<std::string, PhytomerCreationFunction> creationFunctions;
    std::map<std::string, PhytomerCallbackFunction> callbackFunctions;
    PrototypeCache cache;
    PhenologyParameters defaultPhenology;
    ProgressCallback progress;
    std::shared_ptr<const SpeciesModel> species;  ///< the loaded species, if any

    // Collision avoidance (collision/): the scene (shared with canopy workers; null until
    // enabled), the spatial indexes of the plants' own attraction points (a cache: the points
    // are PlantInstance::attraction, and an index is rebuilt when they differ from its own),
    // collision proxies of the cached prototypes (cleared with the cache), and the steering
    // of the plant being grown (set only while growth runs, so hand-built shoots are never
    // steered).
    std::shared_ptr<collision::World> collision;
    std::map<unsigned, std::shared_ptr<const collision::AttractionIndex>> attractionIndexes;
    std::shared_ptr<collision::ProxyCache> proxies;
    collision::Steering* steering = nullptr;

    /// The prototype a leaf uses (built and cached on first use).
    const OrganPrototype& leafPrototype(const LeafParameters& lp, const LeafOrgan& leaf);
    /// One-sided area of a leaf prototype at unit scale (cached).
    double leafPrototypeArea(const LeafParameters& lp, const LeafOrgan& leaf);
    /// Cache keys of leaf prototypes by address, valid during one grow or tessellate call
    /// (shoot types do not change within one); cleared at the start of each.
    std::map<const LeafPrototype*, std::string> prototypeKeys;
    using LeafKey =
        std::tuple<const LeafPrototype*, int, unsigned>;  ///< prototype, leaflet, variant
    struct LeafKeyHash {
        std::size_t operator()(const LeafKey& k) const {
            const std::uint64_t h =
                std::uint64_t(reinterpret_cast<std::uintptr_t>(std::get<0>(k))) ^
                (std::uint64_t(std::uint32_t(std::get<1>(k))) << 32) ^
                (std::uint64_t(std::get<2>(k)) * 0x9e3779b97f4a7c15ULL);
            return std::size_t(h ^ (h >> 29));
        }
    };
    std::unordered_map<LeafKey, double, LeafKeyHash> prototypeAreas;
    /// prototypeAreas of one prototype by leaflet (-3 to 3) and variant (under 8), at hand
    /// for girth updates (every growth step asks for every leaf's).
    struct LeafAreaTable {
        static constexpr int kLeaflets = 3;
        static constexpr unsigned kVariants = 8;
        std::array<double, (2 * kLeaflets + 1) * kVariants> area{};
        std::array<bool, (2 * kLeaflets + 1) * kVariants> set{};
    };
    std::unordered_map<const LeafPrototype*, LeafAreaTable> leafAreaTables;
    std::unordered_map<LeafKey, const OrganPrototype*, LeafKeyHash> prototypeMemo;
    /// Set while plants grow together in many short steps (collision avoidance): shoot types
    /// cannot change meanwhile, so the memos stay valid from one step to the next.
    bool memosPinned = false;
    /// Set while a canopy's plants are built only to be grown together (collision
    /// avoidance): their initial geometry would be thrown away, so updateGeometry skips it.
    bool geometryDeferred = false;
    void clearCallMemos() {
        if (memosPinned) return;
        prototypeKeys.clear();
        prototypeAreas.clear();
        leafAreaTables.clear();
        prototypeMemo.clear();
    }

    PlantInstance& plant(unsigned id);
    const PlantInstance& plant(unsigned id) const;
    Shoot& shoot(PlantInstance& p, unsigned shootID);
    const Shoot& shoot(const PlantInstance& p, unsigned shootID) const;
    /// The plant's copy of a shoot type, taken from the global table on first use.
    const ShootParameters& shootTypeFor(PlantInstance& p, const std::string& label);
    /// Throws if a prototype function named by the parameters is not registered.
    void checkFunctions(const ShootParameters& params, const std::string& label) const;
};

/// The internal state of `arch` (for tests of internal parts).
PlantArchitecture::Impl& implOf(PlantArchitecture& arch);

enum class StartMode { Base, Append, Child };

/// Creates a shoot (and its first spec.phytomers phytomers) as state; no geometry.
unsigned createShoot(PlantArchitecture::Impl& impl, PlantInstance& plant, const ShootSpec& spec,
                     StartMode mode, int parentID, unsigned parentNode, unsigned parentPetiole);
/// Appends one phytomer to a shoot as state (calls the creation function when named).
void createPhytomer(PlantArchitecture::Impl& impl, PlantInstance& plant, Shoot& shoot,
                    const PhytomerParameters& pp, float radius, float lengthMax,
                    float internodeFraction, float leafFraction, const Internode* start);

// Growth (growth/growth.cpp).
/// Grows one plant by `days`; object IDs of organs that fell off are added to `deletes`.
void growPlant(PlantArchitecture::Impl& impl, PlantInstance& plant, double days,
               std::vector<ObjectID>& deletes);
/// Draws a floral bud's peduncle and flowers from the phytomer parameters.
void realizeInflorescence(PlantInstance& plant, FloralBud& bud, const PhytomerParameters& pp);
/// Starts a newly created shoot's clock: its apical bud, its axillary buds.
void scheduleNewShoot(PlantArchitecture::Impl& impl, PlantInstance& plant, Shoot& shoot);

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
