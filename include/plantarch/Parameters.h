#pragma once
// Species parameters: the phytomer template (internode, petiole, leaf, peduncle,
// inflorescence) and the shoot type that embeds it.
//
// Field names follow the model specification so that programs written against it compile
// unchanged (`params.phytomer_parameters.internode.pitch = 5.0;`). Units: metres, degrees,
// days; curvature in degrees per metre; girth_area_factor in cm^2 per m^2 of downstream leaf
// area. Every field is declared once, with its unit, valid range and description, in
// src/model/parameter_table.h; that table drives validation, species files, `plantarch info`
// and the Python binding.
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

/// How a leaf prototype is built. The outline is a procedural shape family (or a traced
/// PNG), meshed to its true outline, then deformed by the fold/curvature/wave/buckle fields.
struct LeafPrototype {
    /// Name of a registered leaf prototype function; "procedural" uses the outline below.
    std::string prototype_function = "procedural";
    /// OBJ file used instead of the procedural outline when not empty.
    std::string OBJ_model_file;
    /// Scale and move an OBJ model to the prototype convention (length 1 along +x, base at
    /// the origin); false: a model that does not already follow it is an error.
    bool normalize_OBJ_model = false;
    /// Image per leaflet index (0 tip, negative left, positive right): its alpha channel
    /// gives the outline and its colours the texture. Empty: procedural outline and colour.
    std::map<int, std::string> leaf_texture_file;

    // Outline (procedural leaves).
    std::string shape = "elliptic";        ///< outline family, see docs/organs.md
    RandomFloat leaf_aspect_ratio = 1.0f;  ///< width / length
    RandomFloat widest_point = 0.5f;       ///< position of the widest point, fraction of length
    RandomFloat tip_angle = 60.0f;         ///< included angle at the tip, degrees
    RandomFloat base_angle = 90.0f;        ///< included angle at the base, degrees
    RandomInt lobes = 0;                   ///< number of lobes (palmate/pinnate families)
    RandomFloat lobe_depth = 0.0f;         ///< lobe sinus depth, fraction of half-width
    RandomInt serrations = 0;              ///< teeth along each margin
    RandomFloat serration_depth = 0.0f;    ///< tooth depth, fraction of length
    /// Width of a truncate base (grass blades), fraction of the maximum width (0: pointed)
    RandomFloat base_width = 0.0f;
    /// Depth of the basal sinus of notched shapes (cordate, reniform, sagittate, hastate,
    /// palmately lobed), fraction of length: the petiole attaches at (sinus_depth, 0)
    RandomFloat sinus_depth = 0.15f;

    // Deformations.
    RandomFloat midrib_fold_fraction = 0.0f;  ///< fold about the midrib (0 flat, 1 closed)
    /// Curvature along the midrib: the tip rises by about this fraction of the length (- droops)
    RandomFloat longitudinal_curvature = 0.0f;
    /// Curvature across the blade (+ cups up): the margin at the widest point moves by 1/16 of
    /// this, in leaf lengths
    RandomFloat lateral_curvature = 0.0f;
    /// Curl of the blade's base about the midrib (both halves rise), degrees, fading over the
    /// basal 10-15 % of the blade
    RandomFloat petiole_roll = 0.0f;
    /// Distance between sign changes of the marginal waves (half a wavelength, as in the
    /// reference), fraction of length
    RandomFloat wave_period = 0.0f;
    /// Amplitude of the marginal waves, fraction of the local blade width
    RandomFloat wave_amplitude = 0.0f;
    RandomFloat leaf_buckle_length = 0.0f;  ///< where the blade buckles, fraction of length
    RandomFloat leaf_buckle_angle = 0.0f;   ///< buckle angle, degrees (+ bends the tip down)
    vec3 leaf_offset{0.0f};                 ///< shift of the blade from the petiole tip
    unsigned subdivisions = 1;              ///< mesh resolution (rows along the midrib)
    /// Distinct shape variants per prototype, reused by transform; 0 = every leaf unique.
    unsigned unique_prototypes = 1;
    bool build_petiolule = false;     ///< add a short stalk between leaflet and rachis
    vec3 color{0.18f, 0.42f, 0.12f};  ///< upper-side colour (procedural leaves)
};

struct InternodeParameters {
    RandomFloat pitch = 20.0f;  ///< zig-zag angle of an internode from the shoot axis, degrees
    RandomFloat phyllotactic_angle = 137.5f;  ///< roll between successive phytomers, degrees
    RandomFloat radius_initial = 0.001f;      ///< radius when created, m
    RandomInt max_vegetative_buds_per_petiole = 1;
    RandomInt max_floral_buds_per_petiole = 1;
    vec3 color = kForestGreen;
    std::string image_texture;
    unsigned length_segments = 1;
    unsigned radial_subdivisions = 7;
};

struct PetioleParameters {
    unsigned petioles_per_internode = 1;
    RandomFloat pitch = 90.0f;     ///< angle from the internode axis, degrees
    RandomFloat radius = 0.001f;   ///< m
    RandomFloat length = 0.05f;    ///< m
    RandomFloat curvature = 0.0f;  ///< degrees per m (+ curves up toward vertical)
    RandomFloat taper = 0.0f;      ///< tip radius / base radius
    vec3 color = kForestGreen;
    unsigned length_segments = 1;
    unsigned radial_subdivisions = 7;
};

struct LeafParameters {
    RandomInt leaves_per_petiole = 1;     ///< > 1 makes a compound leaf
    RandomFloat pitch = 0.0f;             ///< from the petiole axis, degrees (+ raises the tip)
    RandomFloat yaw = 0.0f;               ///< about the leaf normal, degrees
    RandomFloat roll = 0.0f;              ///< about the midrib, degrees
    RandomFloat leaflet_offset = 0.0f;    ///< spacing of leaflet pairs, fraction of petiole
    RandomFloat leaflet_scale = 1.0f;     ///< size of each pair relative to the one above
    RandomFloat prototype_scale = 0.05f;  ///< leaf length, m
    LeafPrototype prototype;
};

struct PeduncleParameters {
    RandomFloat length = 0.05f;    ///< m
    RandomFloat radius = 0.001f;   ///< m
    RandomFloat pitch = 0.0f;      ///< from the internode axis, degrees
    RandomFloat roll = 0.0f;       ///< about its own axis, degrees
    RandomFloat curvature = 0.0f;  ///< degrees per m
    vec3 color = kForestGreen;
    unsigned length_segments = 3;
    unsigned radial_subdivisions = 7;
};

struct InflorescenceParameters {
    RandomInt flowers_per_peduncle = 1;
    RandomFloat flower_offset = 0.0f;  ///< spacing along the peduncle, fraction of its length
    /// "alternate" (successive flowers on opposite sides) or "opposite" (in pairs).
    std::string flower_arrangement = "alternate";
    RandomFloat pitch = 0.0f;  ///< flower/fruit axis from the peduncle axis, degrees
    RandomFloat roll = 0.0f;   ///< about the flower/fruit axis, degrees
    RandomFloat flower_prototype_scale = 0.0075f;  ///< m
    std::string flower_prototype_function;         ///< registered prototype name
    /// Shape parameters of the flower prototype family (names and ranges per family).
    std::map<std::string, float> flower_prototype_parameters;
    vec3 flower_color{0.95f, 0.95f, 0.95f};       ///< main (petal) colour
    unsigned flower_subdivisions = 8;             ///< flower mesh resolution
    RandomFloat fruit_prototype_scale = 0.0075f;  ///< m
    std::string fruit_prototype_function;         ///< registered prototype name
    /// Shape parameters of the fruit prototype family (names and ranges per family).
    std::map<std::string, float> fruit_prototype_parameters;
    vec3 fruit_color{0.75f, 0.12f, 0.08f};  ///< main fruit colour
    unsigned fruit_subdivisions = 12;       ///< fruit mesh resolution
    /// How far fruit turn toward the ground as they grow (0 none, 1 hang vertically).
    RandomFloat fruit_gravity_factor_fraction = 0.0f;
    unsigned unique_prototypes = 1;
    /// Scale and move OBJ flower/fruit models (a prototype function naming a .obj file) to
    /// the prototype convention; false: a model that does not follow it is an error.
    bool normalize_OBJ_model = false;
};

/// A node rule: when all its conditions hold for a phytomer, its actions change that phytomer
/// (buds, leaves, sizes, angles). Species files list them under <node_rules>; the fields, their
/// units, ranges and meaning are declared in src/model/parameter_table.h and described with
/// examples in docs/species-format.md ("Node rules"). A condition left at its default always
/// holds; an action left at its default does nothing.
struct NodeRule {
    std::string when = "creation";  ///< creation, daily or winter

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
    /// Registered function called once per new phytomer (empty: none).
    std::string phytomer_creation_function;
    /// Registered function called for every phytomer at every time step (empty: none).
    std::string phytomer_callback_function;
    /// Rules applied to every phytomer of this type, in order (see NodeRule).
    std::vector<NodeRule> node_rules;
};

struct ShootParameters {
    PhytomerParameters phytomer_parameters;

    // Geometry.
    RandomInt max_nodes = 10;
    RandomInt max_nodes_per_season = 9999;
    RandomFloat insertion_angle_tip = 20.0f;         ///< degrees
    RandomFloat insertion_angle_decay_rate = 0.0f;   ///< degrees per node
    RandomFloat internode_length_max = 0.02f;        ///< m
    RandomFloat internode_length_min = 0.002f;       ///< m
    RandomFloat internode_length_decay_rate = 0.0f;  ///< m per node
    RandomFloat base_roll = 0.0f;                    ///< degrees
    RandomFloat base_yaw = 0.0f;                     ///< degrees
    RandomFloat gravitropic_curvature = 0.0f;        ///< degrees per m
    RandomFloat tortuosity = 0.0f;                   ///< degrees per sqrt(m)

    // Growth.
    RandomFloat phyllochron_min = 2.0f;            ///< days per node
    RandomFloat elongation_rate_max = 0.2f;        ///< m per m of final length per day
    RandomFloat girth_area_factor = 0.0f;          ///< cm^2 per m^2 downstream leaf area
    RandomFloat vegetative_bud_break_time = 5.0f;  ///< days
    RandomFloat vegetative_bud_break_probability_min = 0.0f;
    RandomFloat vegetative_bud_break_probability_max = 1.0f;
    RandomFloat vegetative_bud_break_probability_decay_rate = -0.5f;  ///< per node
    RandomInt max_terminal_floral_buds = 0;
    RandomFloat flower_bud_break_probability = 0.0f;
    RandomFloat fruit_set_probability = 0.0f;
    bool flowers_require_dormancy = false;
    bool growth_requires_dormancy = false;
    bool determinate_shoot_growth = true;

    /// Shoot types of child shoots with their probabilities (in [0,1], summing to 1).
    /// Empty: children are of the same type as this shoot.
    std::map<std::string, float> child_shoot_types;

    /// Adds a child type. Probabilities are checked when the shoot type is defined.
    void defineChildShootTypes(const std::vector<std::string>& labels,
                               const std::vector<float>& probabilities);
};

/// Timing of a plant's phenological stages, days. A negative threshold disables that
/// transition (the next one is timed from the previous enabled one).
struct PhenologyParameters {
    float time_to_dormancy_break = 0.0f;      ///< dormancy (also winter length) to bud break
    float time_to_flower_initiation = -1.0f;  ///< dormancy break to closed flowers
    float time_to_flower_opening = -1.0f;     ///< flower initiation to open flowers
    float time_to_fruit_set = -1.0f;          ///< previous stage to fruit
    float time_to_fruit_maturity = -1.0f;     ///< fruit set to full-size fruit
    float time_to_senescence = -1.0f;         ///< dormancy break to senescence (season end)
    float max_leaf_lifespan = 1e6f;           ///< leaves older than this are shed
    bool evergreen = false;                   ///< keep leaves through dormancy
    float max_age = 999.0f;                   ///< the plant stops developing at this age
};

/// Checks every field against its declared range (and child probabilities: each in [0,1],
/// summing to 1). Throws plantarch::Error naming the parameter path, value and range;
/// `prefix` is put in front of the path (e.g. the shoot type label).
void validate(const ShootParameters& params, const std::string& prefix = "");
void validate(const PhytomerParameters& params, const std::string& prefix = "");
void validate(const PhenologyParameters& params, const std::string& prefix = "");

}  // namespace plantarch
