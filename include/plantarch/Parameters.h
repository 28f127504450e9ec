#pragma once
// Species parameters: the phytomer template (internode, petiole, leaf, peduncle,
// inflorescence), the shoot type that embeds it, and the plant's phenology.
//
// Field names follow the model specification so that programs written against it compile
// unchanged (`params.phytomer_parameters.internode.pitch = 5.0;`). Units: metres, degrees,
// days. The unit, valid range, meaning and valid values of every field are declared once, in
// include/plantarch/ParameterTable.h, and listed in docs/parameters.md (or by
// `plantarch info --parameters`); comments here do not repeat them.
//
// Random parameters (RandomFloat, RandomInt) are realized once per organ when the organ is
// created, and the realized value is stored on the organ.

#include <map>
#include <string>
#include <vector>

#include "plantarch/Formula.h"
#include "plantarch/Mesh.h"
#include "plantarch/Random.h"

namespace plantarch {

/// RGB colour of "forest green", the default colour of stems and petioles.
inline constexpr vec3 kForestGreen{0.133f, 0.545f, 0.133f};

/// Outline family of a procedural leaf (LeafPrototype::shape). Names in files, and what each
/// family looks like: the parameter table (docs/parameters.md); leafShapePreset() in
/// plantarch/LeafShapes.h gives typical numbers for each.
enum class LeafShape {
    Elliptic,
    Ovate,
    Obovate,
    Lanceolate,
    Oblanceolate,
    Linear,
    Needle,
    Spatulate,
    Oblong,
    Orbicular,
    Deltoid,
    Cordate,
    Reniform,
    Sagittate,
    Hastate,
    Palmate,
};

/// Sides of successive flowers along a peduncle (InflorescenceParameters::flower_arrangement).
enum class FlowerArrangement { Alternate, Opposite };

/// How a leaf prototype is built. The outline is a procedural shape family (or a traced
/// PNG), meshed to its true outline, then deformed by the fold/curvature/wave/buckle fields.
struct LeafPrototype {
    std::string prototype_function = "procedural";
    std::string OBJ_model_file;
    bool normalize_OBJ_model = false;
    std::map<int, std::string> leaf_texture_file;

    // Outline (procedural leaves).
    LeafShape shape = LeafShape::Elliptic;
    RandomFloat leaf_aspect_ratio = 1.0f;
    RandomFloat widest_point = 0.5f;
    RandomFloat tip_angle = 60.0f;
    RandomFloat base_angle = 90.0f;
    RandomInt lobes = 0;
    RandomFloat lobe_depth = 0.0f;
    RandomInt serrations = 0;
    RandomFloat serration_depth = 0.0f;
    RandomFloat base_width = 0.0f;
    RandomFloat sinus_depth = 0.15f;

    // Deformations.
    RandomFloat midrib_fold_fraction = 0.0f;
    RandomFloat longitudinal_curvature = 0.0f;
    RandomFloat lateral_curvature = 0.0f;
    RandomFloat petiole_roll = 0.0f;
    RandomFloat wave_period = 0.0f;
    RandomFloat wave_amplitude = 0.0f;
    RandomFloat leaf_buckle_length = 0.0f;
    RandomFloat leaf_buckle_angle = 0.0f;
    RandomInt pleats = 0;
    RandomFloat pleat_depth = 0.0f;
    vec3 leaf_offset{0.0f};
    unsigned subdivisions = 1;
    unsigned unique_prototypes = 1;
    bool build_petiolule = false;
    vec3 color{0.18f, 0.42f, 0.12f};
};

struct InternodeParameters {
    RandomFloat pitch = 20.0f;
    RandomFloat phyllotactic_angle = 137.5f;
    RandomFloat radius_initial = 0.001f;
    RandomInt max_vegetative_buds_per_petiole = 1;
    RandomInt max_floral_buds_per_petiole = 1;
    vec3 color = kForestGreen;
    std::string image_texture;
    unsigned length_segments = 1;
    unsigned radial_subdivisions = 7;
};

struct PetioleParameters {
    unsigned petioles_per_internode = 1;
    RandomFloat pitch = 90.0f;
    RandomFloat radius = 0.001f;
    RandomFloat length = 0.05f;
    RandomFloat curvature = 0.0f;
    RandomFloat taper = 0.0f;
    vec3 color = kForestGreen;
    unsigned length_segments = 1;
    unsigned radial_subdivisions = 7;
};

struct LeafParameters {
    RandomInt leaves_per_petiole = 1;
    RandomFloat pitch = 0.0f;
    RandomFloat yaw = 0.0f;
    RandomFloat roll = 0.0f;
    RandomFloat leaflet_offset = 0.0f;
    RandomFloat leaflet_scale = 1.0f;
    RandomFloat prototype_scale = 0.05f;
    LeafPrototype prototype;
};

struct PeduncleParameters {
    RandomFloat length = 0.05f;
    RandomFloat radius = 0.001f;
    RandomFloat pitch = 0.0f;
    RandomFloat roll = 0.0f;
    RandomFloat curvature = 0.0f;
    vec3 color = kForestGreen;
    unsigned length_segments = 3;
    unsigned radial_subdivisions = 7;
};

struct InflorescenceParameters {
    RandomInt flowers_per_peduncle = 1;
    RandomFloat flower_offset = 0.0f;
    FlowerArrangement flower_arrangement = FlowerArrangement::Alternate;
    RandomFloat pitch = 0.0f;
    RandomFloat roll = 0.0f;
    RandomFloat flower_prototype_scale = 0.0075f;
    std::string flower_prototype_function;
    std::map<std::string, float> flower_prototype_parameters;
    vec3 flower_color{0.95f, 0.95f, 0.95f};
    unsigned flower_subdivisions = 8;
    RandomFloat fruit_prototype_scale = 0.0075f;
    std::string fruit_prototype_function;
    std::map<std::string, float> fruit_prototype_parameters;
    vec3 fruit_color{0.75f, 0.12f, 0.08f};
    unsigned fruit_subdivisions = 12;
    RandomFloat fruit_gravity_factor_fraction = 0.0f;
    unsigned unique_prototypes = 1;
    bool normalize_OBJ_model = false;
};

/// A node rule: when all its conditions hold for a phytomer, its actions change that phytomer
/// (buds, leaves, sizes, angles). Species files list them under <node_rules>; the fields, their
/// units, ranges and meaning are declared in include/plantarch/ParameterTable.h and described with
/// examples in docs/species-format.md ("Node rules"). A condition left at its default always
/// holds; an action left at its default does nothing.
/// When a node rule runs: as a phytomer is made, daily, or at the start of each winter.
enum class NodeRuleTime { Creation, Daily, Winter };

struct NodeRule {
    NodeRuleTime when = NodeRuleTime::Creation;

    // Conditions.
    int rank_min = 0;
    int rank_max = kNoLimit;
    int node_min = 0;
    int node_max = kNoLimit;
    int nodes_from_tip_min = 0;
    int nodes_from_tip_max = kNoLimit;
    int nodes_before_last_min = 0;
    int nodes_before_last_max = kNoLimit;
    float age_min = 0.0f;
    float age_max = 1e9f;
    float height_below = 1e9f;
    float internode_length_below = 1e9f;
    bool only_when_dormant = false;

    // Actions, in this order.
    bool remove_vegetative_buds = false;
    bool remove_floral_buds = false;
    bool remove_leaves = false;
    bool renew_floral_buds = false;
    std::string flowering_shoot_type;
    Formula leaf_scale;
    Formula internode_scale;
    Formula petiole_pitch_change;
    Formula leaf_pitch_change;
    int max_nodes_per_season = kNoLimit;
    RandomInt distal_vegetative_nodes = 0;

    static constexpr int kNoLimit = 1000000;
    /// The variables of the rule formulas, in the order they are evaluated with: age (plant
    /// age, days), node (index on the shoot from its base), rank (of the shoot), max_nodes
    /// (the shoot's realized count), nodes_from_tip (0 at the shoot's current tip).
    static const std::vector<std::string>& formulaVariables();
    /// A rule formula: `text` compiled with formulaVariables() (no random draws). Throws
    /// plantarch::Error for bad syntax or an unknown name.
    static Formula formula(std::string_view text);

    bool operator==(const NodeRule&) const = default;
};

struct PhytomerParameters {
    InternodeParameters internode;
    PetioleParameters petiole;
    LeafParameters leaf;
    PeduncleParameters peduncle;
    InflorescenceParameters inflorescence;
    std::string phytomer_creation_function;
    std::string phytomer_callback_function;
    /// Rules applied to every phytomer of this type, in order (see NodeRule).
    std::vector<NodeRule> node_rules;
};

struct ShootParameters {
    PhytomerParameters phytomer_parameters;

    // Geometry.
    RandomInt max_nodes = 10;
    RandomInt max_nodes_per_season = 9999;
    RandomFloat insertion_angle_tip = 20.0f;
    RandomFloat insertion_angle_decay_rate = 0.0f;
    RandomFloat internode_length_max = 0.02f;
    RandomFloat internode_length_min = 0.002f;
    RandomFloat internode_length_decay_rate = 0.0f;
    RandomFloat base_roll = 0.0f;
    RandomFloat base_yaw = 0.0f;
    RandomFloat gravitropic_curvature = 0.0f;
    RandomFloat tortuosity = 0.0f;

    // Growth.
    RandomFloat phyllochron_min = 2.0f;
    RandomFloat elongation_rate_max = 0.2f;
    RandomFloat girth_area_factor = 0.0f;
    RandomFloat vegetative_bud_break_time = 5.0f;
    RandomFloat vegetative_bud_break_probability_min = 0.0f;
    RandomFloat vegetative_bud_break_probability_max = 1.0f;
    RandomFloat vegetative_bud_break_probability_decay_rate = -0.5f;
    RandomInt max_terminal_floral_buds = 0;
    RandomFloat flower_bud_break_probability = 0.0f;
    RandomFloat fruit_set_probability = 0.0f;
    bool flowers_require_dormancy = false;
    bool growth_requires_dormancy = false;
    bool determinate_shoot_growth = true;

    std::map<std::string, float> child_shoot_types;

    /// Sets child_shoot_types from parallel lists; throws plantarch::Error when the lists differ
    /// in length or the probabilities are not each in [0, 1] summing to 1.
    void defineChildShootTypes(const std::vector<std::string>& labels,
                               const std::vector<float>& probabilities);
};

/// A plant's carbohydrate budget (docs/physiology.md): per-shoot sugar and starch pools fed
/// by its leaves' photosynthesis, spent on respiration and growth, limiting growth when low.
/// Concentrations and thresholds are g C per g of dry stem.
struct CarbohydrateParameters {
    bool enabled = false;
    float stem_density = 675000.0f;
    float stem_carbon_fraction = 0.457f;
    float nonstructural_fraction = 0.1228f;
    float shoot_root_ratio = 3.0f;
    float leaf_carbon_per_area = 20.0f;
    float flower_carbon = 8.33e-4f;
    float fruit_density = 525000.0f;
    float fruit_carbon_fraction = 0.475f;
    float wood_respiration_rate = 5.25164e-5f;
    float root_respiration_rate = 5.25164e-3f;
    float growth_respiration_fraction = 0.211f;
    float respiration_q10 = 1.8f;
    float initial_concentration = 0.15f;
    float storage_capacity = 0.3f;
    float seed_reserve = 0.02f;
    float abortion_threshold = 0.1f;
    float pruning_threshold = 0.025f;
    float phyllochron_threshold = 0.05f;
    float bud_break_threshold = 0.05f;
    float radial_growth_threshold = 0.2f;
    float transfer_up_threshold = 0.04f;
    float transfer_down_threshold = 0.025f;
    float starch_fraction = 0.025f;
    float conductance_up = 0.475f;
    float conductance_down = 0.95f;
    float bud_death_time = 2.0f;
    float branch_death_time = 5.0f;
    float max_phyllochron_factor = 10.0f;
};

/// A plant's nitrogen (docs/physiology.md): an available pool the leaves draw from, nitrogen
/// per leaf area, remobilisation from old leaves and a stress factor that slows leaf expansion
/// and photosynthesis.
struct NitrogenParameters {
    bool enabled = false;
    float initial_available = 0.0f;
    float target_leaf_nitrogen = 1.5f;
    float minimum_leaf_nitrogen = 0.5f;
    float initial_leaf_nitrogen = 1.5f;
    float root_allocation = 0.15f;
    float max_accumulation_rate = 0.1f;
    float remobilisation_efficiency = 0.7f;
    float remobilisation_rate = 0.05f;
    float old_leaf_age = 0.7f;
    float young_leaf_age = 0.5f;
    float fruit_nitrogen = 1.0f;
    float expansion_sensitivity = 1.0f;
};

/// A species' leaf photosynthesis at 25 degrees C (the Farquhar-von Caemmerer-Berry model's
/// capacities; the temperature responses are the model's) and its leaves' optics in PAR.
struct LeafPhysiologyParameters {
    float vcmax25 = 100.0f;
    float jmax25 = 175.0f;
    float rd25 = 1.5f;
    float leaf_reflectance = 0.10f;
    float leaf_transmittance = 0.05f;
};

/// How a plant's shoots bend under their own weight and what they carry (docs/measured-plants.md,
/// "Shoots bending under load"): the stiffness of their wood and the fresh masses that load it.
struct MechanicsParameters {
    bool enabled = false;
    float elastic_modulus = 5e9f;
    float stem_density = 1000.0f;
    float leaf_mass_per_area = 0.2f;
    float fruit_density = 900.0f;
};

/// The distribution a plant's leaves draw their inclination from (LeafAngleParameters): the
/// angle of a blade's upper-side normal from the zenith, which is also the blade's angle from
/// horizontal. Names in files and what each family means: the parameter table
/// (docs/parameters.md) and docs/measured-plants.md.
enum class LeafInclinationDistribution {
    None,
    Planophile,
    Erectophile,
    Plagiophile,
    Extremophile,
    Spherical,
    Uniform,
    Ellipsoidal,
    Beta,
    Histogram,
};

/// The distribution of the compass direction a blade's upper side faces (LeafAngleParameters).
enum class LeafAzimuthDistribution { Uniform, VonMises };

/// A plant's leaf angle distribution (docs/measured-plants.md, "Leaf angle distributions"):
/// with an inclination distribution other than none, every leaf draws a target inclination
/// and azimuth as it is made and its blade is turned so that its mean normal has them.
struct LeafAngleParameters {
    LeafInclinationDistribution inclination = LeafInclinationDistribution::None;
    float ellipsoidal_x = 1.0f;
    float beta_mu = 1.0f;
    float beta_nu = 1.0f;
    float beta_mean = 0.0f;
    float beta_sd = 0.0f;
    std::map<std::string, float> histogram;
    LeafAzimuthDistribution azimuth = LeafAzimuthDistribution::Uniform;
    float azimuth_mean = 0.0f;
    float azimuth_concentration = 0.0f;
    bool operator==(const LeafAngleParameters&) const = default;
};

/// Timing of a plant's phenological stages, days. A negative threshold disables that
/// transition (the next one is timed from the previous enabled one).
struct PhenologyParameters {
    float time_to_dormancy_break = 0.0f;
    float time_to_flower_initiation = -1.0f;
    float time_to_flower_opening = -1.0f;
    float time_to_fruit_set = -1.0f;
    float time_to_fruit_maturity = -1.0f;
    float time_to_senescence = -1.0f;
    float max_leaf_lifespan = 1e6f;
    bool evergreen = false;
    float max_age = 999.0f;
    /// The plant's physiology: carbon, nitrogen and its leaves' photosynthesis.
    CarbohydrateParameters carbohydrates;
    NitrogenParameters nitrogen;
    LeafPhysiologyParameters leaf_physiology;
    /// Shoots bending under load.
    MechanicsParameters mechanics;
    /// The leaves' inclination and azimuth distribution.
    LeafAngleParameters leaf_angles;
};

/// Checks every field against its declared range (and child probabilities: each in [0,1],
/// summing to 1). Throws plantarch::Error naming the parameter path, value and range;
/// `prefix` is put in front of the path (e.g. the shoot type label).
void validate(const ShootParameters& params, const std::string& prefix = "");
void validate(const PhytomerParameters& params, const std::string& prefix = "");
void validate(const PhenologyParameters& params, const std::string& prefix = "");

}  // namespace plantarch
