#pragma once
// Organ prototypes built once per (function, parameters, leaflet, variant) and placed by
// transform, so a canopy does not rebuild a leaf mesh per leaf; and memos that find a leaf's
// prototype without building its key, valid during one growth or tessellation call.
//
// Shapes made by the library's own prototype functions depend on nothing but their key, so
// they are also kept process-wide: the next PlantArchitecture (a new one per plant, per
// request or per notebook cell) finds them built. Shapes of functions the user registered, and
// of OBJ models read from files, stay with their own cache.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <unordered_map>

#include "model/function_registry.h"

namespace plantarch {

class PrototypeCache {
public:
    /// Builds prototypes with the functions of `functions`, which must outlive the cache.
    explicit PrototypeCache(const FunctionRegistry& functions) : functions_(&functions) {}
    /// A cache for another thread: the same functions and the prototypes built so far
    /// (shared, immutable), with memos of its own.
    PrototypeCache share() const;

    const FunctionRegistry& functions() const { return *functions_; }

    // ---- prototypes by key ---------------------------------------------------------
    /// Who may reuse a prototype: this cache only, or every cache in the process (a shape
    /// made by a library function from its key alone).
    enum class Scope { Own, Process };
    /// The prototype of `key`, from this cache or, for Scope::Process, the process's.
    std::shared_ptr<const OrganPrototype> find(const std::string& key, Scope scope = Scope::Own);
    void insert(const std::string& key, std::shared_ptr<const OrganPrototype> proto,
                Scope scope = Scope::Own);
    /// The scope of shapes made by leaf (or flower/fruit) prototype function `name`.
    Scope leafScope(const std::string& name) const {
        return functions_->userLeafPrototypes.count(name) ? Scope::Own : Scope::Process;
    }
    Scope floralScope(const std::string& name) const {
        return functions_->userFloralPrototypes.count(name) ? Scope::Own : Scope::Process;
    }
    std::size_t size() const { return entries_.size(); }
    /// Drops every prototype (a prototype function was registered again).
    void clear() { entries_.clear(); }

    /// `proto` (cached under `key`) thinned to coarseShare(detail) of each part's triangles,
    /// never below `floor` a part, cached under its own key; `proto` itself from 0.5 up.
    const OrganPrototype& coarse(const OrganPrototype& proto, const std::string& key, float detail,
                                 std::size_t floor, Scope scope);

    // ---- leaves ----------------------------------------------------------------------
    /// The prototype a leaf uses (built and cached on first use; tessellate.cpp), at a mesh
    /// detail (PlantArchitecture::setMeshDetail; growth always asks at 1).
    const OrganPrototype& leafPrototype(const LeafParameters& lp, const LeafOrgan& leaf,
                                        float detail = 1.0f);
    /// One-sided area of a leaf prototype at unit scale (cached).
    double leafPrototypeArea(const LeafParameters& lp, const LeafOrgan& leaf);

    /// leafPrototypeArea of one prototype by leaflet (-3 to 3) and variant (under 8), at hand
    /// for girth updates (every growth step asks for every leaf's).
    struct LeafAreaTable {
        static constexpr int kLeaflets = 3;
        static constexpr unsigned kVariants = 8;
        std::array<double, (2 * kLeaflets + 1) * kVariants> area{};
        std::array<bool, (2 * kLeaflets + 1) * kVariants> set{};
    };
    /// The table of one leaf prototype (a call memo).
    LeafAreaTable& leafAreaTable(const LeafPrototype* prototype) {
        return leafAreaTables_[prototype];
    }

    // ---- call memos ------------------------------------------------------------------
    /// Forgets the memos, which key prototypes by the address of their parameters: called at
    /// the start of each growth or tessellation call (shoot types do not change within one),
    /// unless pinned.
    void clearCallMemos() {
        if (memosPinned) return;
        prototypeKeys_.clear();
        prototypeAreas_.clear();
        leafAreaTables_.clear();
        prototypeMemo_.clear();
    }
    /// Set while plants grow together in many short steps (collision avoidance): shoot types
    /// cannot change meanwhile, so the memos stay valid from one step to the next.
    bool memosPinned = false;

private:
    /// The prototype of `proto`'s leaflet and variant, whose parameters `description` gives;
    /// below a mesh detail of 0.5, thinned to coarseShare(detail) of its triangles.
    const OrganPrototype& buildLeafPrototype(const LeafPrototype& proto, int leaflet,
                                             unsigned variant, const std::string& description,
                                             float detail = 1.0f);

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

    const FunctionRegistry* functions_;
    std::map<std::string, std::shared_ptr<const OrganPrototype>> entries_;
    /// Cache keys of leaf prototypes by the address of their parameters.
    std::map<const LeafPrototype*, std::string> prototypeKeys_;
    std::unordered_map<LeafKey, double, LeafKeyHash> prototypeAreas_;
    std::unordered_map<const LeafPrototype*, LeafAreaTable> leafAreaTables_;
    std::unordered_map<LeafKey, const OrganPrototype*, LeafKeyHash> prototypeMemo_;
};

}  // namespace plantarch
