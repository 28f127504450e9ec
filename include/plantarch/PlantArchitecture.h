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
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Context.h"
#include "plantarch/OrganFunctions.h"
#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"
#include "plantarch/PlantStructureIO.h"
#include "plantarch/Progress.h"
#include "plantarch/ShootSpec.h"

namespace plantarch {
struct PhysiologyRecord;  // plantarch/Physiology.h
struct SpeciesModel;      // plantarch/Species.h
}  // namespace plantarch

namespace plantarch {

/// How buildPlantCanopyFromLibrary places plants: on a grid (the specification's form) or
/// scattered at random over a rectangle. Errors name the specification's argument names,
/// given in brackets.
///
/// Grid position (i, j), 0 <= i < count.x along x and 0 <= j < count.y along y, is
/// center + ((i - (count.x - 1) / 2) spacing.x, (j - (count.y - 1) / 2) spacing.y, 0).
/// Positions are taken row by row, i fastest (i = 0..count.x - 1 for j = 0, then for j = 1,
/// ...), and plants are numbered in that order; a position that does not germinate is
/// skipped.
struct CanopyOptions {
    enum class Layout {
        Grid,     ///< `count` plants along x and y, `spacing` apart
        Scatter,  ///< `plants` positions drawn uniformly over `extent`
    };
    Layout layout = Layout::Grid;
    vec3 center{0.0f};  ///< centre of the canopy, m (canopy_center)
    /// Grid: distance between neighbours along x and y, m, > 0 (plant_spacing).
    vec2 spacing{0.3f};
    /// Grid: plants along x and y, each >= 1, at most 10^6 in all (plant_count).
    glm::ivec2 count{1};
    /// Scatter: size of the rectangle along x and y, m, >= 0 (canopy_extent).
    vec2 extent{1.0f};
    unsigned plants = 1;  ///< Scatter: positions drawn, 1 to 10^6 (plant_count)
    /// Probability that a position gets a plant, [0, 1] (germination_rate).
    float germinationRate = 1.0f;
    /// Build parameters overriding the species' defaults, checked against their ranges
    /// (build_parameters).
    std::map<std::string, float> buildParameters;
    /// Only these plants of the canopy (indices in plant order, increasing, each below the
    /// number of plants the whole canopy has), for a canopy built in parts (plantarch/Field.h);
    /// absent: every plant. Each plant built gets the ID and random stream it gets when the
    /// whole canopy is built (the IDs of the others are reserved and stay unused), so the
    /// parts hold the same plants as the whole, exactly without soft collision avoidance (with
    /// it a plant steers by the neighbours built with it).
    std::optional<std::vector<unsigned>> only;
};

/// The bases of a canopy's plants in plant order, as buildPlantCanopyFromLibrary places them
/// with scene seed `seed` (the germination and scatter draws included), without building
/// anything. Throws plantarch::Error for a count, spacing, extent or germination rate out of
/// range, as buildPlantCanopyFromLibrary does.
std::vector<vec3> canopyPositions(const CanopyOptions& options, std::uint64_t seed);

class PlantArchitecture {
public:
    /// Plants are built into `context` (not owned; it must outlive this object).
    explicit PlantArchitecture(Context* context);
    ~PlantArchitecture();
    PlantArchitecture(const PlantArchitecture&) = delete;
    PlantArchitecture& operator=(const PlantArchitecture&) = delete;

    /// The Context the plants' geometry lives in.
    Context& context() { return *context_; }
    const Context& context() const { return *context_; }

    /// Seed of the scene (42 by default): plant i draws from Rng::forPlant(seed, i). It
    /// applies to plants added afterwards.
    void setSeed(std::uint64_t seed);
    std::uint64_t seed() const { return seed_; }
    /// Numbers the random streams of the plants added from now on from 0: the next plant
    /// added draws from Rng::forPlant(seed, 0), the one after from 1, ... (plant IDs go on as
    /// before). By default a plant's streams are numbered by its ID. A canopy built after
    /// other plants then grows as it would alone (without collision avoidance, whose cones
    /// draw by plant ID): plantarch project files build each block so.
    void restartPlantStreams();
    /// The number of a plant's random streams (its ID minus the ID of the first plant added
    /// after the last restartPlantStreams; its ID when never restarted).
    unsigned plantStream(unsigned plantID) const;

    // ---- shoot types ---------------------------------------------------------------
    /// Defines (or replaces) a shoot type for plants added from now on. Validated.
    void defineShootType(const std::string& label, const ShootParameters& params);
    /// A defined shoot type (an unknown label is an Error).
    const ShootParameters& shootType(const std::string& label) const;
    /// The labels of the defined shoot types, sorted.
    std::vector<std::string> listShootTypeLabels() const;
    /// The shoot types of one plant (its own copy).
    std::vector<std::string> listShootTypeLabels(unsigned plantID) const;

    // ---- species library -----------------------------------------------------------
    /// Loads a species by library name ("bean") or file path ("my/plant.xml"): its shoot
    /// types replace the current ones and its phenology becomes the default.
    void loadPlantModelFromLibrary(const std::string& nameOrPath);
    /// Loads a species already read (loadSpecies, editSpecies), as loadPlantModelFromLibrary
    /// does; the files it names are found beside its sourceFile.
    void loadPlantModel(const SpeciesModel& species);
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
    /// A canopy of the loaded species grown to `age` days, laid out as `options` say. Each
    /// position gets a plant with probability options.germinationRate (one draw per
    /// position from the scene's stream). Plants are grown in parallel (OpenMP), each from
    /// its own random stream, and added to the Context in a fixed order: the same seed gives
    /// the same bytes for any thread count. Returns the IDs of the plants made.
    std::vector<unsigned> buildPlantCanopyFromLibrary(const CanopyOptions& options, float age);
    /// The specification's form: a grid of `plant_count` (x, y) plants `plant_spacing` apart
    /// (m), centred on `canopy_center` (CanopyOptions::Layout::Grid).
    std::vector<unsigned> buildPlantCanopyFromLibrary(
        const vec3& canopy_center, const vec2& plant_spacing, const glm::ivec2& plant_count,
        float age, float germination_rate = 1.0f,
        const std::map<std::string, float>& build_parameters = {});

    /// Whether plants built from the library get their species' trellis (<trellis>: posts
    /// and wires as Context objects with object data organ = "trellis" and trellis_part =
    /// "post" or "wire"; on by default). They are scene, not plant: the plant's queries,
    /// statistics and files leave them out; deleting the plant deletes them.
    void setTrellisGeometry(bool on);
    bool getTrellisGeometry() const;

    /// How finely organs are meshed, as a factor on each organ's own resolution in its
    /// species file (leaf `subdivisions`, `flower_subdivisions`, `fruit_subdivisions`, the
    /// `radial_subdivisions` of internodes, petioles and peduncles): 0.1 to 4, default 1.
    /// Coarser meshes for large scenes, finer ones for close-ups. Geometry only: plants grow
    /// the same at any detail (their leaf areas, girths and every state value are unchanged).
    /// Redraws the plants there are; throws naming the range for a value outside it.
    void setMeshDetail(float detail);
    float getMeshDetail() const;
    /// Whether organs of `kind` get geometry in the Context (all kinds do by default). Off,
    /// the plants grow exactly as before and every other organ stands where it did; only
    /// those objects are left out (a light model that needs no stems, say). Redraws the
    /// plants there are and applies to plants added from now on.
    void setOrganGeometry(OrganKind kind, bool build);
    bool getOrganGeometry(OrganKind kind) const;
    /// At most this many triangles in the Context (0, the default: no limit; it sets
    /// Context::setTriangleLimit). A canopy whose estimate passes it is refused before it is
    /// grown: its first plants (as many as there are threads) are grown and the estimate is
    /// their mean triangle count times the number of plants, plus the Context's triangles.
    /// A plant whose organs need more (at least 2 triangles per internode side and 2 per leaf)
    /// stops growing at once. Either throws TriangleBudgetError naming the estimate and the
    /// limit, and the scene is left as it was.
    void setTriangleLimit(std::size_t limit);
    std::size_t getTriangleLimit() const;
    /// A limit that fits the machine: half its physical memory at kBytesPerTriangle each
    /// (the peak of building and writing a scene; the CLI's default --max-triangles).
    static std::size_t defaultTriangleLimit();
    static constexpr std::size_t kBytesPerTriangle = 100;

    /// The trellis objects made with a plant (empty: its species has none, or it was off).
    std::vector<ObjectID> getPlantTrellisObjectIDs(unsigned plantID) const;

    /// Current parameters of one shoot type.
    ShootParameters getCurrentShootParameters(const std::string& shoot_type_label) const;
    /// Current parameters of every shoot type, by label.
    std::map<std::string, ShootParameters> getCurrentShootParameters() const;
    /// Replaces a shoot type's parameters (every field; validated). Plants built afterwards
    /// use them; existing plants keep their own copy.
    void updateCurrentShootParameters(const std::string& shoot_type_label,
                                      const ShootParameters& params);
    /// The same for several shoot types at once (all validated before any is replaced).
    void updateCurrentShootParameters(const std::map<std::string, ShootParameters>& params);

    // ---- manual building -----------------------------------------------------------
    /// A new plant with no shoots, its base at `base_position`, `current_age` days old.
    unsigned addPlantInstance(const vec3& base_position, float current_age);
    /// Removes a plant and its objects from the Context.
    void deletePlantInstance(unsigned plantID);
    /// A copy of a plant standing at `base_position`, turned about its base by `rotation`
    /// (the frame a base stem with that rotation gets: pitch tilts it from the vertical, yaw
    /// turns it about the vertical, roll about its own axis) and `age` days old: the same
    /// shoots and organs, its scheduled events (phytomers, bud breaks, flowering, seasons)
    /// moved with its clock. It grows on with random numbers of its own (the next stream);
    /// its own attraction points move and turn with it; trellis objects are not copied.
    /// Returns its ID.
    unsigned duplicatePlantInstance(unsigned plantID, const vec3& base_position,
                                    const AxisRotation& rotation, float age);

    /// The base stem of a plant (which must have no shoots yet). Returns its shoot ID (0).
    unsigned addBaseStemShoot(unsigned plantID, const ShootSpec& spec);
    /// A shoot continuing from the tip of `parentShootID` (same axis, rotated by the spec;
    /// same rank). Returns its shoot ID.
    unsigned appendShoot(unsigned plantID, unsigned parentShootID, const ShootSpec& spec);
    /// A lateral shoot from the axil of petiole `petioleIndex` at node `parentNode`, starting
    /// spec.baseRotation.pitch degrees from the parent's axis (its type's base_yaw and
    /// base_roll are added to the spec's yaw and roll). The type's insertion_angle_tip and
    /// decay rate apply to shoots that grow from buds as the plant grows, not to shoots
    /// placed by hand. Returns its shoot ID.
    unsigned addChildShoot(unsigned plantID, unsigned parentShootID, unsigned parentNode,
                           const ShootSpec& spec, unsigned petioleIndex = 0);
    /// An epicormic shoot (water sprout) from the wood of `parentShootID` at `position` along
    /// it (a fraction of its length, (0, 1]: the node whose internode holds that point). It
    /// grows from no axillary bud (the node's buds are left as they are) and starts upright,
    /// spec.baseRotation.pitch degrees from the vertical. Returns its shoot ID.
    unsigned addEpicormicShoot(unsigned plantID, unsigned parentShootID, float position,
                               const ShootSpec& spec);
    /// Water sprouts as the plant grows: on each day, each shoot of the plant grows an
    /// epicormic shoot of `shootType` with probability `perMetrePerDay` x its length (m) x the
    /// vertical part of its axis at a point drawn uniformly along it, at that point (one
    /// phytomer, at the type's internode radius and length, 1% grown). 0 turns it off. Kept in
    /// plant structure files.
    void enableEpicormicChildShoots(unsigned plantID, const std::string& shootType,
                                    float perMetrePerDay);
    /// One more phytomer at the tip of a shoot, built from `phytomer_parameters` at `size`.
    /// Returns the shoot's phytomer count.
    unsigned appendPhytomerToShoot(unsigned plantID, unsigned shootID,
                                   const PhytomerParameters& phytomer_parameters,
                                   const PhytomerSize& size = {});

    /// Removes the shoot's phytomers from `node` on, and every shoot growing from them.
    void pruneBranch(unsigned plantID, unsigned shootID, unsigned node);
    /// Removes every leaf of the plant (petioles stay).
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
    /// Removes the floral buds of a shoot that have not flowered yet (flowers and fruit stay).
    void removeShootFloralBuds(unsigned plantID, unsigned shootID);
    /// Removes flowers (open and closed) and fruit, keeping peduncles.
    void removePlantFlowers(unsigned plantID);
    /// Harvest: removes all fruit and returns how many there were (fruit of zero size, just
    /// set, included).
    unsigned harvestPlant(unsigned plantID);

    /// A shoot of `shootType` on measured points (a digitiser's nodes, a point-cloud
    /// skeleton): docs/measured-plants.md. Point 0 is where the shoot starts, the plant's
    /// base for the base stem (parentShootID -1) or node `parentNode` of the parent, and
    /// must lie within options.attachTolerance of it; each further point ends one internode
    /// (n points, n - 1 phytomers). `nodeRadii` holds the radius at each point (n values,
    /// m, > 0; internode i takes the radius at its tip, point i + 1, and the first value is
    /// not used) or is empty (the type's radius_initial). Petioles, leaves and buds are placed by
    /// the type's parameters. The measured internodes keep their length, direction and radius as
    /// the plant grows (Phytomer::measured); growth goes on from the tip and the axillary buds as
    /// the type says. Returns the shoot's ID. Bad input throws naming the argument, value and
    /// range.
    unsigned addShootFromNodePositions(unsigned plantID, int parentShootID, unsigned parentNode,
                                       const std::vector<vec3>& nodePositions,
                                       const std::vector<float>& nodeRadii,
                                       const std::string& shootType,
                                       const MeasuredShootOptions& options = {});
    /// The shoot type the loaded species makes its base stem of (its first build step); ""
    /// when no species is loaded or it has no build steps.
    std::string getBaseStemShootType() const;

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
    /// Grows one plant by `days`.
    void advanceTime(unsigned plantID, double days);
    /// Grows the given plants by `days` (together, as advanceTime(days) grows them all).
    /// Plants with their carbohydrate or nitrogen model on grow in steps of at most a day,
    /// each followed by their budgets (docs/physiology.md).
    void advanceTime(const std::vector<unsigned>& plantIDs, double days);

    // ---- physiology (docs/physiology.md) ---------------------------------------------
    /// Runs the plant's carbohydrate budget from now on: each shoot starts with the species'
    /// initial concentration and its organs as now counted as paid for. Its parameters are
    /// the plant's (`carbohydrates` of its phenology; growPhysiology switches it on for the
    /// plants of a species with `enabled` set).
    void enableCarbohydrateModel(unsigned plantID);
    /// Runs the plant's nitrogen model from now on (its leaves at the initial nitrogen, its
    /// available pool at the initial value).
    void enableNitrogenModel(unsigned plantID);
    /// Whether the plant's carbohydrate budget runs.
    bool hasCarbohydrateModel(unsigned plantID) const;
    /// Whether the plant's nitrogen model runs.
    bool hasNitrogenModel(unsigned plantID) const;
    /// Fertilises a plant whose nitrogen model runs: `grams` of nitrogen (> 0, finite), of
    /// which the species' root allocation stays in the roots and the rest becomes available.
    void addPlantNitrogen(unsigned plantID, double grams);
    /// Adds leaves' own net photosynthesis (µmol CO2 m⁻² s⁻¹ per leaf object, measured or
    /// from another model) over `hours` (0 to 24) to their shoots' input for the next budget
    /// step. Each object must be a leaf of a plant whose budget runs; nothing is added when
    /// one is not.
    void addLeafPhotosynthesis(const std::map<ObjectID, double>& netRates, double hours);
    /// The mean air temperature (°C, -50 to 60) the budgets' respiration uses; 20 by default.
    void setAirTemperature(double celsius);
    /// Adds light absorbed by a plant's leaves (mol photons) to its next record.
    void addAbsorbedLight(unsigned plantID, double molPhotons);
    /// Every budget step's record of the plant so far (empty while its models are off).
    const std::vector<PhysiologyRecord>& getPhysiologyRecords(unsigned plantID) const;

    /// Ground clearance (docs/growth.md), on by default: no petiole with its leaves, peduncle
    /// with its flowers or fruit of a plant goes below the plant's ground, the z of its base.
    /// An organ that would is turned about its attachment point, as little as keeps it clear
    /// (whole degrees); the turns are recomputed from the plant's shape at the end of every
    /// growth step (PlantInstance::groundClearance, kept in plant structure files). Stems are
    /// never turned. Sets it for every plant there is (their turns and geometry redone now)
    /// and for the plants added from now on.
    void setGroundClearance(bool on);
    /// The setting plants added from now on get.
    bool getGroundClearance() const;
    /// The same for one plant.
    void setGroundClearance(unsigned plantID, bool on);
    bool getGroundClearance(unsigned plantID) const;
    /// Ground clipping, beside clearance: at the end of every growth step each leaf, flower
    /// and fruit whose geometry reaches below z = `height` (m) falls off (as at leaf fall),
    /// and a side shoot whose stem reaches below it is pruned from its first node under it.
    /// For every plant there is (applied now) and those added from now on; off by default.
    void enableGroundClipping(float height = 0.0f);
    void disableGroundClipping();
    /// The clipping height, or none when off.
    std::optional<float> getGroundClipping() const;

    // ---- collision avoidance and attraction points (docs/collision.md) ------------------
    /// Soft avoidance: new internodes (optionally petioles, peduncles) turn toward the
    /// largest open gap in their perception cone among plant organs (leaves by default) and
    /// the given obstacle objects. With it on, plants grow together in steps of the update
    /// interval so that each sees its neighbours. Options are validated.
    void enableSoftCollisionAvoidance(const SoftCollisionOptions& options = {});
    /// Turns soft avoidance off (growth is no longer steered by plant organs).
    void disableSoftCollisionAvoidance();
    /// Which plant organs are obstacles for soft avoidance (SoftCollisionOptions::obstacles;
    /// leaves only by default). Soft avoidance must be enabled.
    void setCollisionRelevantOrgans(const CollisionOrgans& organs);
    /// Solid obstacles: Context objects growth never enters. Growth within
    /// options.avoidanceDistance of one turns along its surface; with fruitAdjustment, fruit
    /// crossing one are turned out of it about their attachment point. Options are validated.
    void enableSolidObstacleAvoidance(const SolidObstacleOptions& options);
    /// Forgets the solid obstacles.
    void disableSolidObstacleAvoidance();
    /// Attraction points for every plant that has none of its own: a growing tip that sees
    /// one in its cone turns toward the nearest. Solid obstacles keep priority.
    void enableAttractionPoints(const AttractionPoints& points);
    /// A plant's own attraction points (library plants on trellises set theirs when built);
    /// they replace the global ones for this plant.
    void enableAttractionPoints(unsigned plantID, const AttractionPoints& points);
    /// Replaces the global points, keeping their cone (they must be enabled).
    void updateAttractionPoints(const std::vector<vec3>& attraction_points);
    /// Replaces a plant's own points, keeping their cone (they must be enabled).
    void updateAttractionPoints(unsigned plantID, const std::vector<vec3>& attraction_points);
    /// Adds points to the global ones (they must be enabled).
    void appendAttractionPoints(const std::vector<vec3>& attraction_points);
    /// Adds points to a plant's own ones (they must be enabled).
    void appendAttractionPoints(unsigned plantID, const std::vector<vec3>& attraction_points);
    /// Removes the global points (plants with their own keep them).
    void disableAttractionPoints();
    /// Removes a plant's own points: it follows the global ones again, if any.
    void disableAttractionPoints(unsigned plantID);
    /// The attraction points a plant steers by (its own, else the global ones; empty: none).
    std::vector<vec3> getAttractionPoints(unsigned plantID) const;
    /// Work done by collision avoidance since it was enabled or the counts were reset.
    CollisionStats getCollisionStats() const;
    /// Sets the counts of getCollisionStats to zero.
    void resetCollisionStats();

    /// Receives progress of advanceTime over the plants ("growing", 0..1); may be empty.
    void setProgressCallback(ProgressCallback callback);

    /// Sets the phenological thresholds of a plant (validated).
    void setPlantPhenologicalThresholds(unsigned plantID, const PhenologyParameters& thresholds);
    /// Thresholds given to plants added from now on.
    void setDefaultPhenology(const PhenologyParameters& thresholds);
    /// The thresholds plants added from now on get (the loaded species' phenology, or what
    /// setDefaultPhenology set): change one group, such as leaf_angles, and set them back.
    PhenologyParameters getDefaultPhenology() const;
    /// Where the plant is in its yearly cycle now.
    PhenologyStage getPhenologyStage(unsigned plantID) const;
    /// Ends the plant's growing season now, as at its time_to_senescence: leaves fall unless
    /// evergreen, flowers and fruit are shed, shoots stop, and dormancy breaks again after
    /// time_to_dormancy_break days. Nothing happens to a plant that is dormant already.
    void makePlantDormant(unsigned plantID);
    /// Starts a growing season now, as at the end of time_to_dormancy_break: shoots and buds
    /// resume, buds that need a winter are sorted. Nothing happens unless it is dormant.
    void breakPlantDormancy(unsigned plantID);
    /// Whether the plant is dormant (getPhenologyStage is Dormant).
    bool isPlantDormant(unsigned plantID) const;

    /// Named functions that shoot types refer to (phytomer_creation_function,
    /// phytomer_callback_function). Registering a name again replaces it.
    void registerPhytomerCreationFunction(const std::string& name, PhytomerCreationFunction fn);
    void registerPhytomerCallbackFunction(const std::string& name, PhytomerCallbackFunction fn);

    // ---- organ prototypes ----------------------------------------------------------
    /// Named prototype builders that shoot types refer to (leaf_prototype_function,
    /// flower_prototype_function, fruit_prototype_function). Registering a name again
    /// replaces it (prototypes already built are made again).
    void registerLeafPrototype(const std::string& name, LeafPrototypeFunction fn);
    void registerFloralPrototype(const std::string& name, FloralPrototypeFunction fn);
    /// Whether a prototype builder of that name is registered.
    bool hasLeafPrototype(const std::string& name) const;
    bool hasFloralPrototype(const std::string& name) const;

    // ---- queries (an unknown plant or shoot ID is an Error) ---------------------------
    /// IDs of every plant, in increasing order.
    std::vector<unsigned> getAllPlantIDs() const;
    /// The plant's whole state (PlantState.h), read-only.
    const PlantInstance& plant(unsigned plantID) const;
    /// Where the plant's base stands, m.
    vec3 getPlantBasePosition(unsigned plantID) const;
    /// Moves the plant (its state, geometry and own attraction points) so its base stands at
    /// `base_position`; trellis objects made with it move too.
    void setPlantBasePosition(unsigned plantID, const vec3& base_position);
    /// The plant's name: its species, or the label a plant file gave it.
    std::string getPlantName(unsigned plantID) const;
    /// Age of the plant, days.
    float getPlantAge(unsigned plantID) const;
    /// Top of the plant's geometry above its base, m.
    float getPlantHeight(unsigned plantID) const;
    /// Height of the tip of the base stem above the plant base, m.
    float getPlantStemHeight(unsigned plantID) const;
    /// Leaves (leaflets of compound leaves counted one by one) the plant has now. A leaf of
    /// zero size (currentLeafSize 0, e.g. a stand-in of prototype_scale 0) is not counted: it
    /// has no geometry (PlantState.h, "organ sizes").
    unsigned getPlantLeafCount(unsigned plantID) const;
    /// One-sided area of all leaves, m^2.
    float getPlantLeafArea(unsigned plantID) const;
    /// The same summed over several plants.
    float sumPlantLeafArea(const std::vector<unsigned>& plantIDs) const;
    /// Context objects of the plant's organs of one kind (the kind its objects' "organ" data
    /// names), shoot by shoot from the base. A leaf or flower may have several (one per
    /// prototype part); an organ of zero size (a fruit at the moment it sets) has none.
    std::vector<ObjectID> getPlantObjectIDs(unsigned plantID, OrganKind kind) const;
    /// Context objects of every organ of the plant, in increasing ID order.
    std::vector<ObjectID> getAllPlantObjectIDs(unsigned plantID) const;
    /// Context objects of every plant, in increasing ID order.
    std::vector<ObjectID> getAllObjectIDs() const;

    /// Shoots the plant has now (pruned ones not counted).
    unsigned getShootCount(unsigned plantID) const;
    /// Phytomers (nodes) of a shoot.
    unsigned getShootNodeCount(unsigned plantID, unsigned shootID) const;
    /// The shoot a shoot grows from; -1 for the base stem.
    int getShootParent(unsigned plantID, unsigned shootID) const;
    /// 0 for the base stem (and shoots appended to it), parent's rank + 1 for a child shoot.
    unsigned getShootRank(unsigned plantID, unsigned shootID) const;
    /// Shoots growing directly from this one, in the order they were made.
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
    /// The same for several plants in one file.
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
    /// The same from a document in a string (options.nameForErrors stands for the file).
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
    /// Builds the plants at `positions`, plant i with ID first + index(i) and stream
    /// firstStream + index(i), where index is `indices` (empty: i itself) and `count` IDs and
    /// streams are taken (at least positions.size()).
    std::vector<unsigned> buildPlantsAt(const std::vector<vec3>& positions, float age,
                                        const std::map<std::string, float>& build_parameters,
                                        const std::vector<unsigned>& indices = {},
                                        unsigned count = 0);
    struct GrownPlant;   ///< a plant grown in a canopy worker (src/api/canopy.cpp)
    struct CanopyBuild;  ///< one canopy's build (src/api/canopy.cpp)
    void adoptPlants(std::span<GrownPlant> plants);
    /// Adds the loaded species' trellis for a plant built at `base` (when on and declared).
    void addTrellis(unsigned plantID, const vec3& base,
                    const std::map<std::string, float>& build_parameters);

    /// Grows the plants by `days` without their budgets (advanceTime's growth).
    void growPlants(const std::vector<unsigned>& plantIDs, double days);
    /// Starts the models a plant has enabled and not yet started (src/api/physiology_api.cpp).
    void startPhysiology(unsigned plantID);
    /// One budget step of `days` for a plant whose models run (src/api/physiology_api.cpp).
    void stepPhysiology(unsigned plantID, double days);

    Context* context_;
    std::uint64_t seed_ = 42;
    std::unique_ptr<Impl> impl_;
};

}  // namespace plantarch
