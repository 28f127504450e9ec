#pragma once
// plantarch::PlantArchitecture: builds plants from shoot types and keeps their geometry in a
// Context. Method names follow the model specification so its example programs compile with
// only the include line and namespace changed.
//
// A plant is state (PlantState.h); after every call that changes a plant, its geometry in
// the Context is regenerated from that state. Each organ keeps its object IDs while its
// shape changes. Every object carries the data a segmentation user needs: plantID,
// plant_name, organ, shootID, rank, age, and leafID for leaves.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Context.h"
#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"
#include "plantarch/PlantStructureIO.h"
#include "plantarch/Progress.h"

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

/// Where and how a new shoot starts (the options of addBaseStemShoot and friends).
struct ShootSpec {
    unsigned phytomers = 1;             ///< number of phytomers to create now
    AxisRotation baseRotation;          ///< degrees
    float internodeRadius = 0.001f;     ///< m
    float internodeLengthMax = 0.02f;   ///< full internode length, m
    float internodeLengthScale = 1.0f;  ///< current / full internode length, (0, 1]
    float leafScale = 1.0f;             ///< current / full petiole and leaf size, (0, 1]
    float radiusTaper = 0.0f;           ///< tip radius reduction along the shoot, [0, 1]
    std::string shootType;              ///< label given to defineShootType
};

class PlantArchitecture {
public:
    explicit PlantArchitecture(Context* context);
    ~PlantArchitecture();
    PlantArchitecture(const PlantArchitecture&) = delete;
    PlantArchitecture& operator=(const PlantArchitecture&) = delete;

    Context& context() { return *context_; }

    /// Seed of the scene: plant i draws from Rng::forPlant(seed, i).
    void setSeed(std::uint64_t seed);
    std::uint64_t seed() const { return seed_; }

    // ---- shoot types ---------------------------------------------------------------
    /// Defines (or replaces) a shoot type for plants added from now on. Validated.
    void defineShootType(const std::string& label, const ShootParameters& params);
    const ShootParameters& shootType(const std::string& label) const;
    std::vector<std::string> listShootTypeLabels() const;
    /// The shoot types of one plant (its own copy).
    std::vector<std::string> listShootTypeLabels(unsigned plantID) const;

    // ---- species library -----------------------------------------------------------
    /// Loads a species by library name ("bean") or file path ("my/plant.xml"): its shoot
    /// types replace the current ones and its phenology becomes the default.
    void loadPlantModelFromLibrary(const std::string& nameOrPath);
    /// Names of the species in the library directory, sorted.
    std::vector<std::string> getAvailablePlantModels() const;
    /// Name of the loaded species ("" when none).
    std::string getCurrentPlantModel() const;
    /// Shoot types of any library species (or file) without loading it.
    std::vector<std::string> listShootTypeLabels(const std::string& nameOrPath) const;
    /// Builds a plant of the loaded species at `base_position`, grown to `age` days. Build
    /// parameters (trunk height, scaffolds...) override the species' defaults and are checked
    /// against their ranges.
    unsigned buildPlantInstanceFromLibrary(
        const vec3& base_position, float age,
        const std::map<std::string, float>& build_parameters = {});
    /// A canopy of the loaded species on a grid of `plant_count` (x, y) plants `plant_spacing`
    /// apart (m), centred on `canopy_center`. Each position germinates with probability
    /// `germination_rate`. Plants are grown in parallel (OpenMP), each from its own random
    /// stream, and added to the Context in a fixed order: the same seed gives the same bytes
    /// for any thread count. Returns the IDs of the plants made.
    std::vector<unsigned> buildPlantCanopyFromLibrary(
        const vec3& canopy_center, const vec2& plant_spacing, const glm::ivec2& plant_count,
        float age, float germination_rate = 1.0f,
        const std::map<std::string, float>& build_parameters = {});
    /// A canopy of `plant_count` plants scattered uniformly at random over a rectangle of
    /// `canopy_extent` (x, y) metres centred on `canopy_center`.
    std::vector<unsigned> buildPlantCanopyFromLibrary(
        const vec3& canopy_center, const vec2& canopy_extent, unsigned plant_count, float age,
        float germination_rate = 1.0f, const std::map<std::string, float>& build_parameters = {});

    /// Current parameters of one shoot type, or of all of them.
    ShootParameters getCurrentShootParameters(const std::string& shoot_type_label) const;
    std::map<std::string, ShootParameters> getCurrentShootParameters() const;
    /// Replaces a shoot type's parameters (every field; validated). Plants built afterwards
    /// use them; existing plants keep their own copy.
    void updateCurrentShootParameters(const std::string& shoot_type_label,
                                      const ShootParameters& params);
    void updateCurrentShootParameters(const std::map<std::string, ShootParameters>& params);

    // ---- manual building -----------------------------------------------------------
    /// A new plant with no shoots, its base at `base_position`, `current_age` days old.
    unsigned addPlantInstance(const vec3& base_position, float current_age);
    void deletePlantInstance(unsigned plantID);

    /// The base stem of a plant. Returns the shoot ID (0).
    unsigned addBaseStemShoot(unsigned plantID, const ShootSpec& spec);
    unsigned addBaseStemShoot(unsigned plantID, unsigned current_node_number,
                              const AxisRotation& base_rotation, float internode_radius,
                              float internode_length_max,
                              float internode_length_scale_factor_fraction,
                              float leaf_scale_factor_fraction, float radius_taper,
                              const std::string& shoot_type_label);
    /// A shoot continuing from the tip of `parentShootID` (same axis, rotated by the spec).
    unsigned appendShoot(unsigned plantID, unsigned parentShootID, const ShootSpec& spec);
    unsigned appendShoot(unsigned plantID, int parent_shoot_ID, unsigned current_node_number,
                         const AxisRotation& base_rotation, float internode_radius,
                         float internode_length_max, float internode_length_scale_factor_fraction,
                         float leaf_scale_factor_fraction, float radius_taper,
                         const std::string& shoot_type_label);
    /// A lateral shoot from the axil of petiole `petioleIndex` at node `parentNode`. The
    /// insertion angle comes from the parent type's insertion_angle_tip and decay rate,
    /// measured from the tip; spec.baseRotation.pitch is added to it.
    unsigned addChildShoot(unsigned plantID, unsigned parentShootID, unsigned parentNode,
                           const ShootSpec& spec, unsigned petioleIndex = 0);
    unsigned addChildShoot(unsigned plantID, int parent_shoot_ID, unsigned parent_node_index,
                           unsigned current_node_number, const AxisRotation& shoot_base_rotation,
                           float internode_radius, float internode_length_max,
                           float internode_length_scale_factor_fraction,
                           float leaf_scale_factor_fraction, float radius_taper,
                           const std::string& shoot_type_label, unsigned petiole_index = 0);
    /// One more phytomer at the tip of a shoot, built from `phytomer_parameters`.
    unsigned appendPhytomerToShoot(unsigned plantID, unsigned shootID,
                                   const PhytomerParameters& phytomer_parameters,
                                   float internode_radius, float internode_length_max,
                                   float internode_length_scale_factor_fraction,
                                   float leaf_scale_factor_fraction);

    /// Removes the shoot's phytomers from `node` on, and every shoot growing from them.
    void pruneBranch(unsigned plantID, unsigned shootID, unsigned node);
    void removePlantLeaves(unsigned plantID);
    /// Removes the leaves of a shoot together with their petioles (bare nodes that keep their
    /// buds), as on a trained trunk.
    void removeShootLeaves(unsigned plantID, unsigned shootID);
    /// Removes every vegetative bud (apical and axillary) so the plant stops branching.
    void removeShootVegetativeBuds(unsigned plantID, unsigned shootID);
    /// Removes the axillary vegetative buds only; the shoot keeps growing from its tip.
    void removeShootAxillaryVegetativeBuds(unsigned plantID, unsigned shootID);
    /// Kills the apical bud: the shoot makes no more phytomers (a headed or topped shoot).
    void removeShootApex(unsigned plantID, unsigned shootID);
    void removeShootFloralBuds(unsigned plantID, unsigned shootID);
    /// Removes flowers (open and closed) and fruit, keeping peduncles.
    void removePlantFlowers(unsigned plantID);
    /// Harvest: removes all fruit and returns how many there were.
    unsigned harvestPlant(unsigned plantID);

    /// Adds a flowering bud at a node with the given stage (for hand-built plants; growth
    /// makes them on its own). Returns the number of flowers on its peduncle.
    unsigned addFloralBud(unsigned plantID, unsigned shootID, unsigned node, FloralStage stage,
                          unsigned petioleIndex = 0);

    // ---- growth --------------------------------------------------------------------
    /// Grows every plant by `days` (any step size: the same plant results from one call of
    /// 60 days, 60 calls of 1 day or any other split, because growth is driven by events at
    /// exact plant ages). Geometry is regenerated once at the end. With collision avoidance
    /// on, new organs are steered as they are made; with soft avoidance the plants grow
    /// together (in parallel) in steps of the collision scene's update interval.
    void advanceTime(double days);
    void advanceTime(unsigned plantID, double days);
    void advanceTime(const std::vector<unsigned>& plantIDs, double days);

    // ---- collision avoidance and attraction points (docs/collision.md) ------------------
    /// Soft avoidance: new internodes (optionally petioles, peduncles) turn toward the
    /// largest open gap in their perception cone among plant organs (leaves by default) and
    /// the given obstacle objects. With it on, plants grow together in steps of the update
    /// interval so that each sees its neighbours. Options are validated.
    void enableSoftCollisionAvoidance(const SoftCollisionOptions& options = {});
    /// The same with the cone given: half-angle (degrees), look-ahead distance (m), number
    /// of rays, inertia (0: turn fully to the gap, 1: unchanged).
    void enableSoftCollisionAvoidance(float view_half_angle_deg, float look_ahead_distance,
                                      unsigned ray_count, float inertia);
    void disableSoftCollisionAvoidance();
    /// Which plant organs are obstacles for soft avoidance (leaves only by default).
    void setCollisionRelevantOrgans(bool internodes, bool leaves, bool petioles, bool flowers,
                                    bool fruit);
    /// Solid obstacles: Context objects growth never enters. Growth within
    /// `avoidance_distance` (m) of one turns along its surface; with `fruit_adjustment`, fruit
    /// crossing one are turned out of it about their attachment point.
    void enableSolidObstacleAvoidance(const std::vector<ObjectID>& obstacle_IDs,
                                      float avoidance_distance = 0.2f,
                                      bool fruit_adjustment = false);
    void enableSolidObstacleAvoidance(const SolidObstacleOptions& options);
    void disableSolidObstacleAvoidance();
    /// Attraction points for every plant that has none of its own: a growing tip that sees
    /// one in its cone turns toward the nearest. Solid obstacles keep priority.
    void enableAttractionPoints(const std::vector<vec3>& attraction_points,
                                float view_half_angle_deg = 80.0f, float look_ahead_distance = 0.1f,
                                float inertia = 0.4f);
    void enableAttractionPoints(const AttractionPoints& points);
    /// A plant's own attraction points (library plants on trellises set theirs when built);
    /// they replace the global ones for this plant.
    void enableAttractionPoints(unsigned plantID, const std::vector<vec3>& attraction_points,
                                float view_half_angle_deg = 80.0f, float look_ahead_distance = 0.1f,
                                float inertia = 0.4f);
    void enableAttractionPoints(unsigned plantID, const AttractionPoints& points);
    /// Replaces or extends the points, keeping the cone (attraction points must be enabled).
    void updateAttractionPoints(const std::vector<vec3>& attraction_points);
    void updateAttractionPoints(unsigned plantID, const std::vector<vec3>& attraction_points);
    void appendAttractionPoints(const std::vector<vec3>& attraction_points);
    void appendAttractionPoints(unsigned plantID, const std::vector<vec3>& attraction_points);
    void disableAttractionPoints();
    void disableAttractionPoints(unsigned plantID);
    /// The attraction points a plant steers by (its own, else the global ones; empty: none).
    std::vector<vec3> getAttractionPoints(unsigned plantID) const;
    /// Work done by collision avoidance since it was enabled or the counts were reset.
    CollisionStats getCollisionStats() const;
    void resetCollisionStats();

    /// Receives progress of advanceTime over the plants ("growing", 0..1); may be empty.
    void setProgressCallback(ProgressCallback callback);

    /// Sets the phenological thresholds of a plant (validated).
    void setPlantPhenologicalThresholds(unsigned plantID, const PhenologyParameters& thresholds);
    /// Thresholds given to plants added from now on.
    void setDefaultPhenology(const PhenologyParameters& thresholds);
    PhenologyStage getPhenologyStage(unsigned plantID) const;

    /// Named functions that shoot types refer to (phytomer_creation_function,
    /// phytomer_callback_function). Registering a name again replaces it.
    void registerPhytomerCreationFunction(const std::string& name, PhytomerCreationFunction fn);
    void registerPhytomerCallbackFunction(const std::string& name, PhytomerCallbackFunction fn);

    // ---- organ prototypes ----------------------------------------------------------
    void registerLeafPrototype(const std::string& name, LeafPrototypeFunction fn);
    void registerFloralPrototype(const std::string& name, FloralPrototypeFunction fn);
    bool hasLeafPrototype(const std::string& name) const;
    bool hasFloralPrototype(const std::string& name) const;

    // ---- queries -------------------------------------------------------------------
    std::vector<unsigned> getAllPlantIDs() const;
    const PlantInstance& plant(unsigned plantID) const;
    vec3 getPlantBasePosition(unsigned plantID) const;
    float getPlantAge(unsigned plantID) const;
    /// Top of the plant's geometry above its base, m.
    float getPlantHeight(unsigned plantID) const;
    /// Height of the tip of the base stem above the plant base, m.
    float getPlantStemHeight(unsigned plantID) const;
    unsigned getPlantLeafCount(unsigned plantID) const;
    /// One-sided area of all leaves, m^2.
    float getPlantLeafArea(unsigned plantID) const;
    std::vector<ObjectID> getPlantInternodeObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getPlantPetioleObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getPlantLeafObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getPlantPeduncleObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getPlantFlowerObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getPlantFruitObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getAllPlantObjectIDs(unsigned plantID) const;
    std::vector<ObjectID> getAllObjectIDs() const;

    unsigned getShootCount(unsigned plantID) const;
    unsigned getShootNodeCount(unsigned plantID, unsigned shootID) const;
    int getShootParent(unsigned plantID, unsigned shootID) const;
    unsigned getShootRank(unsigned plantID, unsigned shootID) const;
    std::vector<unsigned> getShootChildren(unsigned plantID, unsigned shootID) const;
    /// Every shoot growing from this one, at any depth, in increasing ID order.
    std::vector<unsigned> getShootDescendants(unsigned plantID, unsigned shootID) const;
    /// Shoots with no children.
    std::vector<unsigned> getTerminalShoots(unsigned plantID) const;
    /// Shoot IDs from this shoot down to the base stem (inclusive).
    std::vector<unsigned> getShootPathToRoot(unsigned plantID, unsigned shootID) const;

    /// World position of a node (the tip of internode `node`) as the geometry stands now.
    vec3 getNodePosition(unsigned plantID, unsigned shootID, unsigned node) const;

    // ---- plant structure files and strings (docs/plant-xml.md) ------------------------
    /// Writes plants as a plant structure XML file: their whole state (every organ's realized
    /// values, directions, bud states and timers, the phenology clock, the random stream) and
    /// their species parameters, so the file needs nothing loaded to be read back, and reading
    /// it gives the same plants: the same geometry now and the same growth later. Written
    /// through a temporary file (never half a file). Several plants (a canopy) share one file.
    void writePlantStructureXML(unsigned plantID, const std::string& filename) const;
    void writePlantStructureXML(const std::vector<unsigned>& plantIDs,
                                const std::string& filename) const;
    /// The document writePlantStructureXML writes, as a string.
    std::string getPlantStructureXML(const std::vector<unsigned>& plantIDs) const;
    /// Adds every plant of a plant structure file and returns their IDs, in file order (new
    /// IDs: the file's are not reused). A file in the specification's listing form (root
    /// <helios>, only the values its sample shows) loads too: missing values take defaults
    /// (shoot types from this PlantArchitecture, realized values at their means) and
    /// options.onWarning receives the list. Bad input throws plantarch::Error naming the
    /// file, line, element path and value; nothing is added then.
    std::vector<unsigned> readPlantStructureXML(const std::string& filename,
                                                const PlantStructureReadOptions& options = {});
    std::vector<unsigned> readPlantStructureXMLString(
        const std::string& xml, const PlantStructureReadOptions& options = {});
    /// A compact one-line text of the plant's visible structure (shoots, internodes,
    /// petioles, leaves, flowers and fruit with their current sizes and angles), for machine
    /// learning. Its grammar is in docs/plant-xml.md.
    std::string getPlantString(unsigned plantID, const PlantStringOptions& options = {}) const;
    /// Adds the plant a plant string describes and returns its ID. Shoot types are this
    /// PlantArchitecture's current ones (load the species first). getPlantString of the
    /// result, with the digits the string was written with, gives the same string.
    unsigned generatePlantFromString(const std::string& plantString,
                                     const PlantStructureReadOptions& options = {});

    // ---- geometry ------------------------------------------------------------------
    /// Regenerates the plant's geometry from its state (called by every mutating method;
    /// call it after editing state through other means).
    void updateGeometry(unsigned plantID);

private:
    struct Impl;  ///< the state behind the facade (src/api/facade_impl.h)

    /// A plant of the loaded species with its initial structure (and its own attraction
    /// points), not grown.
    unsigned buildPlantStructure(const vec3& base_position,
                                 const std::map<std::string, float>& build_parameters);
    std::vector<unsigned> buildPlantsAt(const std::vector<vec3>& positions, float age,
                                        const std::map<std::string, float>& build_parameters);
    void mergePlant(const Context& from, PlantInstance plant, Impl& owner);

    Context* context_;
    std::uint64_t seed_ = 42;
    std::unique_ptr<Impl> impl_;
};

}  // namespace plantarch
