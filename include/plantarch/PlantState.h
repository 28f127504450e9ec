#pragma once
// The botanical state of a plant: what every organ is now. Growth changes this state only;
// geometry is a pure function of it (see PlantArchitecture). All directions are unit
// vectors in world coordinates (z up); angles are degrees; lengths metres; times days.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Context.h"
#include "plantarch/Parameters.h"
#include "plantarch/Random.h"

namespace plantarch {

inline constexpr ObjectID kNoObject = std::numeric_limits<ObjectID>::max();

/// Rotation of a shoot relative to its parent (or to vertical for a base stem), degrees:
/// pitch tilts it away from the parent axis, yaw turns it about the parent axis, roll turns
/// it about its own axis.
struct AxisRotation {
    float pitch = 0.0f;
    float yaw = 0.0f;
    float roll = 0.0f;
};

enum class BudState { Dormant, Active, Broken, Dead };
enum class FloralStage { Bud, FlowerClosed, FlowerOpen, Fruit, Removed };
enum class OrganKind { Internode, Petiole, Leaf, Peduncle, FlowerClosed, FlowerOpen, Fruit };
/// Where a plant is in its yearly cycle.
enum class PhenologyStage { Dormant, Vegetative, Reproductive, Senescent };

// ---- the names of the state enums -------------------------------------------------------
// Each state enum's one table of names: plant structure files write and read them, the
// "organ" object data holds OrganKind's, the Python module names its enum members after them,
// and docs/plant-xml.md lists them (tests check each). A new enumerator is one line in its
// table, in enumerator order (checked below).

/// One value of a state enum: the enumerator, its name, what it means.
template <class E>
struct StateName {
    E value;
    const char* name;
    const char* doc;
};

/// The values of the state enum E in enumerator order; empty for a type without a table.
template <class E>
inline constexpr std::span<const StateName<E>> kStateNames{};

inline constexpr StateName<BudState> kBudStates[] = {
    {BudState::Dormant, "dormant", "Waiting to break (a floral bud: to flower, if drawn to)"},
    {BudState::Active, "active", "Growing (an apical bud), or set to break without a draw"},
    {BudState::Broken, "broken", "Grown into a shoot"},
    {BudState::Dead, "dead", "Never grows or flowers"},
};
template <>
inline constexpr std::span<const StateName<BudState>> kStateNames<BudState> = kBudStates;

inline constexpr StateName<FloralStage> kFloralStages[] = {
    {FloralStage::Bud, "bud", "An unopened floral bud"},
    {FloralStage::FlowerClosed, "flower_closed", "Closed flowers"},
    {FloralStage::FlowerOpen, "flower_open", "Open flowers"},
    {FloralStage::Fruit, "fruit", "Fruit"},
    {FloralStage::Removed, "removed", "Its flowers or fruit fell or were removed"},
};
template <>
inline constexpr std::span<const StateName<FloralStage>> kStateNames<FloralStage> = kFloralStages;

inline constexpr StateName<OrganKind> kOrganKindNames[] = {
    {OrganKind::Internode, "internode", "An internode's tube"},
    {OrganKind::Petiole, "petiole", "A petiole's tube"},
    {OrganKind::Leaf, "leaf", "A leaf or leaflet blade"},
    {OrganKind::Peduncle, "peduncle", "A peduncle's tube"},
    {OrganKind::FlowerClosed, "flower_closed", "A closed flower"},
    {OrganKind::FlowerOpen, "flower_open", "An open flower"},
    {OrganKind::Fruit, "fruit", "A fruit"},
};
template <>
inline constexpr std::span<const StateName<OrganKind>> kStateNames<OrganKind> = kOrganKindNames;

inline constexpr StateName<PhenologyStage> kPhenologyStages[] = {
    {PhenologyStage::Dormant, "dormant", "Dormant: no growth until dormancy breaks"},
    {PhenologyStage::Vegetative, "vegetative", "Growing shoots and leaves"},
    {PhenologyStage::Reproductive, "reproductive", "Flowering or fruiting"},
    {PhenologyStage::Senescent, "senescent", "The season has ended"},
};
template <>
inline constexpr std::span<const StateName<PhenologyStage>> kStateNames<PhenologyStage> =
    kPhenologyStages;

/// An enum type with a table of names.
template <class E>
concept StateEnum = std::is_enum_v<E> && !kStateNames<E>.empty();

/// Whether E's table lists every enumerator from 0 up, in order (E(i) is entry i).
template <StateEnum E>
constexpr bool inEnumeratorOrder() {
    for (std::size_t i = 0; i < kStateNames<E>.size(); ++i)
        if (kStateNames<E>[i].value != E(i)) return false;
    return true;
}
static_assert(inEnumeratorOrder<BudState>() && inEnumeratorOrder<FloralStage>() &&
              inEnumeratorOrder<OrganKind>() && inEnumeratorOrder<PhenologyStage>());

/// The number of values of E.
template <StateEnum E>
inline constexpr std::size_t kStateCount = kStateNames<E>.size();
/// The number of organ kinds.
inline constexpr std::size_t kOrganKinds = kStateCount<OrganKind>;

/// The name of `value` ("unknown" for a value outside the table).
template <StateEnum E>
constexpr const char* stateName(E value) {
    const auto i = std::size_t(value);
    return i < kStateCount<E> ? kStateNames<E>[i].name : "unknown";
}

/// The value named `name` exactly, if there is one.
template <StateEnum E>
constexpr std::optional<E> stateNamed(std::string_view name) {
    for (const StateName<E>& n : kStateNames<E>)
        if (name == n.name) return n.value;
    return std::nullopt;
}

/// Every name of E, in enumerator order.
template <StateEnum E>
std::vector<std::string> stateNames() {
    std::vector<std::string> names;
    for (const StateName<E>& n : kStateNames<E>) names.emplace_back(n.name);
    return names;
}

/// Label written to object data "organ" for each kind.
constexpr const char* organName(OrganKind kind) {
    return stateName(kind);
}
constexpr const char* budStateName(BudState state) {
    return stateName(state);
}
constexpr const char* floralStageName(FloralStage stage) {
    return stateName(stage);
}
constexpr const char* phenologyStageName(PhenologyStage stage) {
    return stateName(stage);
}

/// A turn of an organ about its attachment point (world axis, degrees), set at the end of each
/// growth step to keep the organ above the ground (PlantInstance::groundClearance) and out of
/// solid obstacles; angle 0 means none.
struct OrganTurn {
    vec3 axis{0.0f, 0.0f, 1.0f};
    float angle = 0.0f;
    bool operator==(const OrganTurn&) const = default;
};

struct VegetativeBud {
    BudState state = BudState::Dormant;
    /// Plant age at which the bud breaks (or fails to); negative: waiting for dormancy to end.
    double breakTime = -1.0;
    int childShoot = -1;    ///< shoot grown from this bud, -1 if none
    std::string shootType;  ///< type the bud will grow into (chosen when it breaks)
};

struct FlowerOrgan {
    float position = 1.0f;     ///< along the peduncle from its base, fraction of its length
    float azimuth = 0.0f;      ///< side of the peduncle, degrees
    float pitch = 0.0f;        ///< from the peduncle axis, degrees
    float roll = 0.0f;         ///< about its own axis, degrees
    float flowerScale = 0.0f;  ///< flower length, m
    float fruitScale = 0.0f;   ///< full-grown fruit length, m
    float gravityFactor = 0.0f;
    unsigned variant = 0;           ///< prototype variant
    OrganTurn clearance;            ///< out of the ground and solid obstacles, after gravity
    std::vector<ObjectID> objects;  ///< one per prototype part
};

struct FloralBud {
    FloralStage stage = FloralStage::Bud;
    /// At stage Bud: Dormant waits to flower with flower_bud_break_probability; Active (set by
    /// a rule function) flowers without that draw; Dead never flowers.
    BudState state = BudState::Dormant;
    bool terminal = false;  ///< at the shoot tip (else axillary)
    /// Terminal buds: the bud's place around the shoot tip, degrees from the last internode's
    /// azimuth (the n buds of a shoot stand 360 / n apart, dead ones keeping their place).
    float terminalAzimuth = 0.0f;
    /// Shoot type whose phytomer template (peduncle, inflorescence) realizes and draws this
    /// bud; empty: the type that made its phytomer (terminal buds: the shoot's type). Rule
    /// functions set it to give some nodes other flowers or fruit (maize ears).
    std::string parametersLabel;
    float fruitAge = 0.0f;     ///< days since fruit set
    float fruitGrowth = 1.0f;  ///< current fruit size / full-grown size
    double stageTime = 0.0;    ///< plant age when the current stage began
    /// Plant age of the next stage change; negative: none pending (or waiting for dormancy).
    double nextTime = -1.0;
    // Peduncle, realized when the bud breaks.
    float peduncleLength = 0.0f;
    float peduncleRadius = 0.0f;
    float pedunclePitch = 0.0f;  ///< from the internode axis, toward its petiole's side, degrees
    float peduncleRoll = 0.0f;   ///< the flowers turned about the peduncle's own axis, degrees
    float peduncleCurvature = 0.0f;
    /// The peduncle's side turned about the stem from its petiole's, degrees (0 unless soft
    /// collision avoidance steered it).
    float peduncleAzimuth = 0.0f;
    OrganTurn peduncleClearance;  ///< peduncle and flowers turned out of ground, obstacles
    ObjectID peduncleObject = kNoObject;
    std::vector<FlowerOrgan> flowers;
};

/// A leaf's nitrogen, when the plant's nitrogen model runs.
struct LeafNitrogen {
    double content = 0.0;  ///< g N in the leaf
};

/// The pose a leaf was given by its plant's leaf angle distribution (LeafAngleParameters),
/// drawn as it was made: its blade's mean normal stands at this inclination and faces this
/// azimuth, whatever its petiole and stem do.
struct LeafAngleTarget {
    /// Of the blade's mean normal from the zenith (of the blade from horizontal), degrees.
    float inclination = 0.0f;
    /// The compass direction its upper side faces, degrees clockwise from north (+y).
    float azimuth = 0.0f;
    bool operator==(const LeafAngleTarget&) const = default;
};

struct LeafOrgan {
    int leafletIndex = 0;   ///< 0 tip, negative left, positive right (pairs from the tip)
    float position = 1.0f;  ///< along the petiole from its base, fraction of its length
    float scale = 0.0f;     ///< full-grown length, m
    float pitch = 0.0f;
    float yaw = 0.0f;
    float roll = 0.0f;
    unsigned variant = 0;  ///< prototype variant
    int leafID = -1;       ///< unique within the plant
    float age = 0.0f;      ///< days
    double birth = 0.0;    ///< plant age when it appeared
    bool removed = false;
    std::vector<ObjectID> objects;
    std::optional<LeafNitrogen> nitrogen;  ///< none unless the plant's nitrogen model runs
    /// None unless its plant has a leaf angle distribution (LeafAngleParameters).
    std::optional<LeafAngleTarget> angleTarget;
};

struct Petiole {
    float azimuth = 0.0f;    ///< about the internode axis from its roll reference, degrees
    float pitch = 0.0f;      ///< from the internode axis, degrees
    float length = 0.0f;     ///< full-grown length, m
    float radius = 0.0f;     ///< base radius, m
    float curvature = 0.0f;  ///< degrees per m
    float taper = 0.0f;
    OrganTurn clearance;  ///< petiole and leaves turned out of the ground and obstacles
    std::vector<LeafOrgan> leaves;
    std::vector<VegetativeBud> vegetativeBuds;
    std::vector<FloralBud> floralBuds;
    ObjectID object = kNoObject;
};

/// How far an internode and everything it carries (its node's organs, the shoots above it) is
/// turned from its rest place by the shoots bending under load (docs/measured-plants.md):
/// the whole turn of the plant's bending up to it, about a world axis through each node.
struct InternodeBend {
    vec3 axis{0.0f, 0.0f, 1.0f};
    float angle = 0.0f;  ///< degrees
};

struct Internode {
    vec3 direction{0, 0, 1};         ///< axis of this internode (after zig-zag pitch)
    vec3 guide{0, 0, 1};             ///< shoot axis here (curvature, random walk, steering applied)
    vec3 rollReference{1, 0, 0};     ///< unit, perpendicular to guide: azimuth 0 of the petioles
    float length = 0.0f;             ///< full-grown length, m
    float radius = 0.0f;             ///< current radius, m
    float pitch = 0.0f;              ///< realized zig-zag pitch, degrees
    float phyllotacticAngle = 0.0f;  ///< realized roll from the previous phytomer, degrees
    float azimuth = 0.0f;            ///< accumulated phyllotactic roll, degrees
    float gravitropicTurn = 0.0f;    ///< zenith change from gravitropism, degrees
    float walkZenith = 0.0f;         ///< random-walk zenith perturbation, degrees
    float walkYaw = 0.0f;            ///< random-walk yaw perturbation, degrees
    ObjectID object = kNoObject;
    /// Set while the plant bends under load (docs/measured-plants.md): direction, guide and
    /// roll reference are the rest shape; geometry turns them by this.
    std::optional<InternodeBend> bend;
};

/// What was measured of an internode (plantarch/MeasuredShoots.h).
struct MeasuredInternode {
    float radius = 0.0f;  ///< m
};

struct Phytomer {
    Internode internode;
    std::vector<Petiole> petioles;
    float age = 0.0f;                 ///< days
    double birth = 0.0;               ///< plant age when it was created
    float internodeFraction = 1.0f;   ///< current internode length / full length
    float leafFraction = 1.0f;        ///< current petiole and leaf size / full size
    float internodeFraction0 = 1.0f;  ///< internode fraction at creation
    float leafFraction0 = 1.0f;       ///< petiole and leaf fraction at creation
    float radiusInitial = 0.0f;       ///< internode radius at creation (girth never goes below)
    std::string parametersLabel;      ///< shoot type whose phytomer template built it
    /// Set when its internode follows measured points (addShootFromNodePositions): growth
    /// never changes its length, direction or radius.
    std::optional<MeasuredInternode> measured;
};

/// A shoot's carbohydrates, when the plant's budget runs (docs/physiology.md): its pools and
/// what the budget remembers of its size at the last daily step, to charge the growth since.
struct ShootCarbon {
    double sugar = 0.0;           ///< mol C
    double starch = 0.0;          ///< mol C
    double woodCarbon = 0.0;      ///< mol C of structure in its internodes at the last step
    double leafArea = 0.0;        ///< m² of leaves at the last step
    double fruitVolume = 0.0;     ///< m³ of fruit at the last step
    unsigned flowers = 0;         ///< flowers formed so far (each paid for once)
    float poorDays = 0.0f;        ///< days in a row below the abortion threshold
    float starvedDays = 0.0f;     ///< days in a row below the pruning threshold
    float phyllochron = 0.0f;     ///< the shoot's own phyllochron, days, before any slowing
    float budBreakFactor = 1.0f;  ///< the shoot's buds break with their probability times this
    /// mol C the shoot may spend thickening its internodes until the next step (its pool
    /// above the radial growth threshold); thickening takes at least 5 % of its full increase.
    double radialAllowance = 0.0;
};

struct Shoot {
    unsigned id = 0;
    std::string type;
    int parent = -1;        ///< parent shoot ID, -1 for the base stem
    int parentNode = -1;    ///< node index on the parent
    int parentPetiole = 0;  ///< petiole index on that node
    unsigned rank = 0;      ///< 0 base stem, 1 its children, ...
    AxisRotation baseRotation;
    float insertionAngle = 0.0f;  ///< realized angle from the parent axis, degrees
    float radiusTaper = 0.0f;
    // Realized shoot parameters.
    int maxNodes = 0;
    int maxNodesPerSeason = 0;
    float internodeLengthMax = 0.0f;
    float phyllochron = 0.0f;
    float elongationRate = 0.0f;
    float gravitropicCurvature = 0.0f;
    float tortuosity = 0.0f;
    float girthAreaFactor = 0.0f;
    VegetativeBud apicalBud;
    std::vector<FloralBud> terminalFloralBuds;
    std::vector<Phytomer> phytomers;
    std::vector<unsigned> children;
    /// Phytomers the apex has added this season: max_nodes_per_season limits these. The nodes a
    /// shoot starts with (the first node of a shoot from a bud, the nodes of a shoot built
    /// whole) are not among them; a phytomer appended through the API is.
    int nodesThisSeason = 0;
    /// Plant age at which the apical bud makes its next phytomer; negative: not scheduled.
    double nextPhytomerTime = -1.0;
    bool flowering = false;  ///< determinate shoots stop growing once flowering
    bool removed = false;
    std::optional<ShootCarbon> carbon;  ///< none unless the plant's budget runs
};

// ---- organ sizes ------------------------------------------------------------------------
// An organ's size now, m. An organ of size 0 (a fruit at the moment it sets, a leaf whose
// full-grown scale is 0) has no geometry: tessellation gives it no Context object and no
// triangles until it starts to grow, so the object queries (getPlantObjectIDs, leaf area,
// exports) do not see it, and the counting queries (getPlantLeafCount, the flower and fruit
// counts of `plantarch build --stats`) leave it out too. It keeps its place in the state
// (plant XML, plant strings and further growth are as for any organ).

/// A leaf's current length along the blade: its full-grown scale times its phytomer's leaf
/// fraction.
inline float currentLeafSize(const Phytomer& ph, const LeafOrgan& leaf) {
    return leaf.scale * ph.leafFraction;
}
/// A flower's length, or a fruit's current length (its full-grown length times fruitGrowth).
inline float currentFloralSize(const FloralBud& fb, const FlowerOrgan& fl) {
    return fb.stage == FloralStage::Fruit ? fl.fruitScale * std::clamp(fb.fruitGrowth, 0.0f, 1.0f)
                                          : fl.flowerScale;
}
/// Whether an organ of that current size (m) has geometry.
inline bool hasSize(float size) {
    return size > 0.0f;
}

/// Water sprouts: shoots that grow from the wood of older shoots rather than from a bud of
/// the current season (PlantArchitecture::enableEpicormicChildShoots).
struct EpicormicShoots {
    std::string shootType;     ///< type of the shoots made
    float probability = 0.0f;  ///< per m of parent shoot per day, at a vertical parent
};

/// A plant's nitrogen, when its nitrogen model runs (docs/physiology.md).
struct PlantNitrogen {
    double available = 0.0;  ///< g N the leaves and fruit may take up
    double roots = 0.0;      ///< g N kept by the roots
    double uptake = 0.0;     ///< g N taken up by leaves and fruit so far
    double fruit = 0.0;      ///< g N in fruit so far
    double leaves = 0.0;     ///< g N in its leaves after the last step
    float stress = 1.0f;     ///< area-weighted leaf N over its target, at most 1 (1: none)
};

struct PlantInstance {
    unsigned id = 0;
    /// The number of its random streams (Rng::forPlant(seed, stream)): the plants of one
    /// PlantArchitecture count from 0 (PlantArchitecture::restartPlantStreams), whatever
    /// their IDs, which the Context hands out.
    unsigned stream = 0;
    std::string name;  ///< species or user label (object data plant_name)
    vec3 base{0.0f};
    double age = 0.0;                                   ///< days
    std::vector<Shoot> shoots;                          ///< indexed by shoot ID
    std::map<std::string, ShootParameters> shootTypes;  ///< the plant's own copy
    PhenologyParameters phenology;
    Rng rng;
    int nextLeafID = 0;
    // Phenology clock (plant ages, days).
    PhenologyStage stage = PhenologyStage::Dormant;
    double dormancyBreakTime = -1.0;  ///< when the current season began; negative: not yet
    double nextDormancyBreak = 0.0;   ///< when dormancy breaks next; negative: never
    double senescenceTime = -1.0;     ///< when the current season ends; negative: never
    int season = 0;                   ///< growing seasons begun
    /// Ground clearance: petioles with their leaves, peduncles with their flowers and fruit
    /// are turned about their attachment point wherever they would go below base.z (turns
    /// recomputed at the end of every growth step). On by default
    /// (PlantArchitecture::setGroundClearance).
    bool groundClearance = true;
    /// The plant's own attraction points (a trellis species' wires, or set with
    /// PlantArchitecture::enableAttractionPoints(plantID, ...)): it steers by these instead
    /// of the global ones. None: it follows the global points, if any.
    std::optional<AttractionPoints> attraction;
    /// Water sprouts (none: the plant makes none).
    std::optional<EpicormicShoots> epicormic;
    std::optional<PlantNitrogen> nitrogen;  ///< none unless its nitrogen model runs
};

}  // namespace plantarch
