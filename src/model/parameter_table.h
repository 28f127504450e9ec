#pragma once
// The one declaration of every species parameter: name, unit, valid range, description.
//
// describeParameters(params, visitor) calls the visitor once per field, in file order:
//   visitor.field(info, member)            for every leaf field
//   visitor.group(name, member, callback)  for every nested group (callback visits it)
//   visitor.list(name, item, vector, callback)
//                                          for a list of groups (callback(element, visitor)
//                                          visits one element)
// with `member` a (const or not) reference to the struct member. Validation, the species
// file reader and writer, `plantarch info` and the Python binding are all visitors, so a
// field added here is read, written, checked and documented everywhere at once.

#include <limits>
#include <string>
#include <type_traits>

#include "plantarch/Parameters.h"

namespace plantarch::params {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// What a field is. Ranges bound every value a random parameter can take.
struct FieldInfo {
    const char* name;
    const char* unit;  ///< "" when dimensionless
    double min;
    double max;
    const char* doc;
    const char* choices = nullptr;  ///< for string fields: "a|b|c" (nullptr: any text)
};

template <class T, class U>
concept SameAs = std::is_same_v<std::remove_const_t<T>, U>;

template <class S, class V>
requires SameAs<S, LeafPrototype>
void describeParameters(S& p, V& v) {
    v.field({"prototype_function", "", 0, 0,
             "Registered leaf prototype function; 'procedural' builds the outline below"},
            p.prototype_function);
    v.field({"OBJ_model_file", "", 0, 0, "OBJ model used as the leaf instead of an outline"},
            p.OBJ_model_file);
    v.field({"normalize_OBJ_model", "", 0, 1,
             "Scale and move the OBJ model to unit length along +x with its base at the origin"},
            p.normalize_OBJ_model);
    v.field({"leaf_texture_file", "", 0, 0,
             "Image per leaflet index (0 tip, -n left, +n right); alpha gives the outline"},
            p.leaf_texture_file);
    v.field({"shape", "", 0, 0, "Outline family",
             "elliptic|ovate|obovate|lanceolate|oblanceolate|linear|needle|spatulate|oblong|"
             "orbicular|deltoid|cordate|reniform|sagittate|hastate|palmate"},
            p.shape);
    v.field({"leaf_aspect_ratio", "", 0.001, 100, "Leaf width / length"}, p.leaf_aspect_ratio);
    v.field({"widest_point", "", 0.01, 0.99, "Position of the widest point, fraction of length"},
            p.widest_point);
    v.field({"tip_angle", "degrees", 1, 180, "Included angle of the outline at the tip"},
            p.tip_angle);
    v.field({"base_angle", "degrees", 1, 360, "Included angle of the outline at the base"},
            p.base_angle);
    v.field({"lobes", "", 0, 15, "Number of lobes"}, p.lobes);
    v.field({"lobe_depth", "", 0, 0.95, "Depth of the sinuses, fraction of the half-width"},
            p.lobe_depth);
    v.field({"serrations", "", 0, 200, "Teeth along each margin"}, p.serrations);
    v.field({"serration_depth", "", 0, 0.2, "Tooth depth, fraction of length"}, p.serration_depth);
    v.field({"base_width", "", 0, 0.95,
             "Width of a truncate base, fraction of the maximum width (0: pointed base)"},
            p.base_width);
    v.field({"sinus_depth", "", 0.01, 0.6,
             "Notched shapes: depth of the basal sinus where the petiole attaches, fraction "
             "of length"},
            p.sinus_depth);
    v.field({"midrib_fold_fraction", "", -1, 1, "Fold about the midrib (0 flat, 1 closed)"},
            p.midrib_fold_fraction);
    v.field(
        {"longitudinal_curvature", "", -2, 2, "Curvature along the midrib; positive lifts the tip"},
        p.longitudinal_curvature);
    v.field({"lateral_curvature", "", -5, 5, "Curvature across the blade; positive cups it"},
            p.lateral_curvature);
    v.field({"petiole_roll", "degrees", -180, 180,
             "Curl of the blade's base about the midrib, fading over the basal 10-15 %"},
            p.petiole_roll);
    v.field({"wave_period", "", 0, 1,
             "Distance between sign changes of the marginal waves, fraction of length"},
            p.wave_period);
    v.field({"wave_amplitude", "", 0, 0.5,
             "Amplitude of the marginal waves, fraction of the local blade width"},
            p.wave_amplitude);
    v.field({"leaf_buckle_length", "", 0, 1, "Where the blade buckles, fraction of length"},
            p.leaf_buckle_length);
    v.field(
        {"leaf_buckle_angle", "degrees", -180, 180, "Buckle angle; positive bends the tip down"},
        p.leaf_buckle_angle);
    v.field({"leaf_offset", "", -kInf, kInf, "Shift of the blade from the petiole tip, leaf units"},
            p.leaf_offset);
    v.field({"subdivisions", "", 1, 200, "Mesh resolution (rows along the midrib)"},
            p.subdivisions);
    v.field({"unique_prototypes", "", 0, 1000,
             "Distinct shape variants reused by transform; 0 makes every leaf unique"},
            p.unique_prototypes);
    v.field({"build_petiolule", "", 0, 1, "Add a short stalk between leaflet and rachis"},
            p.build_petiolule);
    v.field({"color", "", 0, 1, "Upper-side RGB colour"}, p.color);
}

template <class S, class V>
requires SameAs<S, InternodeParameters>
void describeParameters(S& p, V& v) {
    v.field({"pitch", "degrees", -180, 180,
             "Zig-zag angle of the internode from the shoot axis, away from its petiole"},
            p.pitch);
    v.field({"phyllotactic_angle", "degrees", -360, 360,
             "Roll between the petioles of successive phytomers"},
            p.phyllotactic_angle);
    v.field({"radius_initial", "m", 1e-6, 1, "Internode radius when created"}, p.radius_initial);
    v.field({"max_vegetative_buds_per_petiole", "", 0, 10, "Axillary vegetative buds per petiole"},
            p.max_vegetative_buds_per_petiole);
    v.field({"max_floral_buds_per_petiole", "", 0, 10, "Axillary floral buds per petiole"},
            p.max_floral_buds_per_petiole);
    v.field({"color", "", 0, 1, "RGB colour"}, p.color);
    v.field({"image_texture", "", 0, 0, "Bark/stem image texture"}, p.image_texture);
    v.field({"length_segments", "", 1, 100, "Tube segments per internode"}, p.length_segments);
    v.field({"radial_subdivisions", "", 3, 100, "Vertices around the tube"}, p.radial_subdivisions);
}

template <class S, class V>
requires SameAs<S, PetioleParameters>
void describeParameters(S& p, V& v) {
    v.field({"petioles_per_internode", "", 0, 20, "Petioles at each node (2 = opposite)"},
            p.petioles_per_internode);
    v.field({"pitch", "degrees", -180, 180, "Angle of the petiole base from the internode axis"},
            p.pitch);
    v.field({"radius", "m", 0, 1, "Radius at the base"}, p.radius);
    v.field({"length", "m", 0, 10, "Length"}, p.length);
    v.field({"curvature", "degrees/m", -100000, 100000,
             "Curvature per unit length; positive curves up toward vertical"},
            p.curvature);
    v.field({"taper", "", 0, 1, "Tip radius / base radius"}, p.taper);
    v.field({"color", "", 0, 1, "RGB colour"}, p.color);
    v.field({"length_segments", "", 1, 100, "Tube segments"}, p.length_segments);
    v.field({"radial_subdivisions", "", 3, 100, "Vertices around the tube"}, p.radial_subdivisions);
}

template <class S, class V>
requires SameAs<S, LeafParameters>
void describeParameters(S& p, V& v) {
    v.field({"leaves_per_petiole", "", 1, 99, "Leaves per petiole; more than 1 is compound"},
            p.leaves_per_petiole);
    v.field({"pitch", "degrees", -180, 180, "Leaf axis from the petiole axis; positive lifts"},
            p.pitch);
    v.field({"yaw", "degrees", -180, 180, "Rotation about the leaf normal at its base"}, p.yaw);
    v.field({"roll", "degrees", -180, 180, "Rotation about the midrib"}, p.roll);
    v.field({"leaflet_offset", "", 0, 1, "Spacing of leaflet pairs, fraction of the petiole"},
            p.leaflet_offset);
    v.field({"leaflet_scale", "", 0, 10, "Size of each leaflet pair relative to the pair above"},
            p.leaflet_scale);
    v.field({"prototype_scale", "m", 0, 10, "Leaf length"}, p.prototype_scale);
    v.group("prototype", p.prototype, [&](auto& sub) { describeParameters(p.prototype, sub); });
}

template <class S, class V>
requires SameAs<S, PeduncleParameters>
void describeParameters(S& p, V& v) {
    v.field({"length", "m", 0, 10, "Length"}, p.length);
    v.field({"radius", "m", 0, 1, "Radius"}, p.radius);
    v.field({"pitch", "degrees", -180, 180, "Angle from the internode axis"}, p.pitch);
    v.field({"roll", "degrees", -360, 360, "Rotation about its own axis"}, p.roll);
    v.field({"curvature", "degrees/m", -100000, 100000, "Curvature per unit length"}, p.curvature);
    v.field({"color", "", 0, 1, "RGB colour"}, p.color);
    v.field({"length_segments", "", 1, 100, "Tube segments"}, p.length_segments);
    v.field({"radial_subdivisions", "", 3, 100, "Vertices around the tube"}, p.radial_subdivisions);
}

template <class S, class V>
requires SameAs<S, InflorescenceParameters>
void describeParameters(S& p, V& v) {
    v.field({"flowers_per_peduncle", "", 1, 200, "Flowers (potential fruit) per peduncle"},
            p.flowers_per_peduncle);
    v.field({"flower_offset", "", 0, 1, "Spacing along the peduncle, fraction of its length"},
            p.flower_offset);
    v.field({"flower_arrangement", "", 0, 0, "Side of successive flowers along the peduncle",
             "alternate|opposite"},
            p.flower_arrangement);
    v.field({"pitch", "degrees", -180, 180, "Flower/fruit axis from the peduncle axis"}, p.pitch);
    v.field({"roll", "degrees", -360, 360, "Rotation about the flower/fruit axis"}, p.roll);
    v.field({"flower_prototype_scale", "m", 0, 10, "Flower length"}, p.flower_prototype_scale);
    v.field({"flower_prototype_function", "", 0, 0, "Registered flower prototype, or an .obj file"},
            p.flower_prototype_function);
    v.field({"flower_prototype_parameters", "", -1e6, 1e6,
             "Shape parameters of the flower prototype family"},
            p.flower_prototype_parameters);
    v.field({"flower_color", "", 0, 1, "Main flower (petal) RGB colour"}, p.flower_color);
    v.field({"flower_subdivisions", "", 2, 200, "Flower mesh resolution"}, p.flower_subdivisions);
    v.field({"fruit_prototype_scale", "m", 0, 10, "Full-grown fruit length"},
            p.fruit_prototype_scale);
    v.field({"fruit_prototype_function", "", 0, 0, "Registered fruit prototype, or an .obj file"},
            p.fruit_prototype_function);
    v.field({"fruit_prototype_parameters", "", -1e6, 1e6,
             "Shape parameters of the fruit prototype family"},
            p.fruit_prototype_parameters);
    v.field({"fruit_color", "", 0, 1, "Main fruit RGB colour"}, p.fruit_color);
    v.field({"fruit_subdivisions", "", 2, 200, "Fruit mesh resolution"}, p.fruit_subdivisions);
    v.field({"fruit_gravity_factor_fraction", "", 0, 1,
             "How far fruit turn toward the ground as they grow (1 hangs vertically)"},
            p.fruit_gravity_factor_fraction);
    v.field({"unique_prototypes", "", 1, 1000, "Distinct flower/fruit shape variants"},
            p.unique_prototypes);
    v.field({"normalize_OBJ_model", "", 0, 1,
             "Scale and move .obj flower/fruit models to the prototype convention"},
            p.normalize_OBJ_model);
}

template <class S, class V>
requires SameAs<S, NodeRule>
void describeParameters(S& p, V& v) {
    constexpr double kMany = NodeRule::kNoLimit;
    v.field({"when", "", 0, 0,
             "When the rule runs: as the phytomer is made, at every whole day of plant age, or "
             "on the first whole day of each dormant period",
             "creation|daily|winter"},
            p.when);
    v.field({"rank_min", "", 0, kMany, "Applies to shoots of at least this rank (0: base stem)"},
            p.rank_min);
    v.field({"rank_max", "", 0, kMany, "Applies to shoots of at most this rank"}, p.rank_max);
    v.field({"node_min", "", 0, kMany, "Applies from this node up (0: the shoot's first node)"},
            p.node_min);
    v.field({"node_max", "", 0, kMany, "Applies up to this node"}, p.node_max);
    v.field({"nodes_from_tip_min", "", 0, kMany,
             "Applies to nodes at least this many nodes below the shoot's current tip (0: the "
             "tip node)"},
            p.nodes_from_tip_min);
    v.field({"nodes_from_tip_max", "", 0, kMany,
             "Applies to nodes at most this many nodes below the shoot's current tip"},
            p.nodes_from_tip_max);
    v.field({"nodes_before_last_min", "", 0, kMany,
             "Applies to nodes at least this many nodes before the shoot's last node (its "
             "realized max_nodes; 0: the last node)"},
            p.nodes_before_last_min);
    v.field({"nodes_before_last_max", "", 0, kMany,
             "Applies to nodes at most this many nodes before the shoot's last node"},
            p.nodes_before_last_max);
    v.field({"age_min", "days", 0, 1e9, "Applies from this plant age on"}, p.age_min);
    v.field({"age_max", "days", 0, 1e9, "Applies up to this plant age"}, p.age_max);
    v.field({"height_below", "m", -1e9, 1e9,
             "Daily and winter rules: applies to nodes whose base is lower than this above the "
             "plant's base"},
            p.height_below);
    v.field({"internode_length_below", "m", 0, 1e9,
             "Applies to phytomers whose full internode length is shorter than this (spurs)"},
            p.internode_length_below);
    v.field({"only_when_dormant", "", 0, 1, "Applies only while the plant is dormant"},
            p.only_when_dormant);
    v.field({"remove_vegetative_buds", "", 0, 1,
             "Kills the node's dormant axillary vegetative buds (no branch from it)"},
            p.remove_vegetative_buds);
    v.field({"remove_floral_buds", "", 0, 1,
             "Removes the node's unopened floral buds (no flowers from it)"},
            p.remove_floral_buds);
    v.field({"remove_leaves", "", 0, 1,
             "Removes the node's leaves with their petioles; the node keeps its buds"},
            p.remove_leaves);
    v.field({"renew_floral_buds", "", 0, 1,
             "Makes every floral bud of the node that flowered, fruited or failed an unopened "
             "dormant bud again, so it can flower in the next season"},
            p.renew_floral_buds);
    v.field({"flowering_shoot_type", "", 0, 0,
             "Makes the node's unopened dormant floral buds flower, with their inflorescence "
             "from this shoot type of the species (empty: none)"},
            p.flowering_shoot_type);
    v.field({"leaf_scale", "", 0, 0,
             "Formula multiplying the size of the node's leaves (variables: age, node, rank, "
             "max_nodes, nodes_from_tip)"},
            p.leaf_scale);
    v.field({"internode_scale", "", 0, 0,
             "Formula multiplying the node's full internode length (variables as leaf_scale)"},
            p.internode_scale);
    v.field({"petiole_pitch_change", "degrees", 0, 0,
             "Formula added to the pitch of the node's petioles (variables as leaf_scale)"},
            p.petiole_pitch_change);
    v.field({"leaf_pitch_change", "degrees", 0, 0,
             "Formula added to the pitch of the node's leaves (variables as leaf_scale)"},
            p.leaf_pitch_change);
    v.field({"max_nodes_per_season", "", 1, kMany,
             "Caps the shoot's realized max_nodes_per_season at this count"},
            p.max_nodes_per_season);
    v.field({"distal_vegetative_nodes", "", 0, 10000,
             "Applies to the node's whole shoot: its N most distal nodes (N drawn each time) lose "
             "their floral buds and the nodes below lose their vegetative buds (0: none)"},
            p.distal_vegetative_nodes);
}

template <class S, class V>
requires SameAs<S, PhytomerParameters>
void describeParameters(S& p, V& v) {
    v.group("internode", p.internode, [&](auto& sub) { describeParameters(p.internode, sub); });
    v.group("petiole", p.petiole, [&](auto& sub) { describeParameters(p.petiole, sub); });
    v.group("leaf", p.leaf, [&](auto& sub) { describeParameters(p.leaf, sub); });
    v.group("peduncle", p.peduncle, [&](auto& sub) { describeParameters(p.peduncle, sub); });
    v.group("inflorescence", p.inflorescence,
            [&](auto& sub) { describeParameters(p.inflorescence, sub); });
    v.field({"phytomer_creation_function", "", 0, 0,
             "Registered function called once per new phytomer"},
            p.phytomer_creation_function);
    v.field({"phytomer_callback_function", "", 0, 0,
             "Registered function called for every phytomer at every time step"},
            p.phytomer_callback_function);
    v.list("node_rules", "rule", p.node_rules,
           [&](auto& rule, auto& sub) { describeParameters(rule, sub); });
}

template <class S, class V>
requires SameAs<S, ShootParameters>
void describeParameters(S& p, V& v) {
    v.field({"max_nodes", "", 1, 100000, "Maximum phytomers on the shoot"}, p.max_nodes);
    v.field({"max_nodes_per_season", "", 1, 100000, "Maximum phytomers added in one season"},
            p.max_nodes_per_season);
    v.field({"insertion_angle_tip", "degrees", 0, 180,
             "Angle of a child shoot from this shoot at its tip"},
            p.insertion_angle_tip);
    v.field({"insertion_angle_decay_rate", "degrees/node", -180, 180,
             "Increase of the insertion angle per node down from the tip (capped at 90)"},
            p.insertion_angle_decay_rate);
    v.field({"internode_length_max", "m", 0, 10, "Full internode length (at base or tip)"},
            p.internode_length_max);
    v.field({"internode_length_min", "m", 0, 10, "Smallest full internode length"},
            p.internode_length_min);
    v.field({"internode_length_decay_rate", "m/node", -10, 10,
             "Change of full internode length per node (<0 basitonic, >0 acrotonic)"},
            p.internode_length_decay_rate);
    v.field({"base_roll", "degrees", -360, 360, "Roll of the shoot about its own axis"},
            p.base_roll);
    v.field({"base_yaw", "degrees", -360, 360, "Turn of the shoot about its parent's axis"},
            p.base_yaw);
    v.field({"gravitropic_curvature", "degrees/m", -100000, 100000,
             "Curvature toward vertical per unit length (negative: downward)"},
            p.gravitropic_curvature);
    v.field({"tortuosity", "degrees/m^0.5", 0, 10000, "Random-walk wiggle of the shoot path"},
            p.tortuosity);
    v.field({"phyllochron_min", "days", 0.001, 10000, "Days between successive phytomers"},
            p.phyllochron_min);
    v.field(
        {"elongation_rate_max", "1/day", 0, 100, "Elongation per day as a fraction of full length"},
        p.elongation_rate_max);
    v.field({"girth_area_factor", "cm^2/m^2", 0, 100000,
             "Internode cross-section per downstream leaf area (0 locks the radius)"},
            p.girth_area_factor);
    v.field({"vegetative_bud_break_time", "days", 0, 100000,
             "Time from bud creation (or dormancy break) to bud break"},
            p.vegetative_bud_break_time);
    v.field({"vegetative_bud_break_probability_min", "", 0, 1,
             "Smallest probability along the shoot that an axillary bud breaks"},
            p.vegetative_bud_break_probability_min);
    v.field({"vegetative_bud_break_probability_max", "", 0, 1,
             "Largest probability along the shoot that an axillary bud breaks"},
            p.vegetative_bud_break_probability_max);
    v.field({"vegetative_bud_break_probability_decay_rate", "1/node", -100, 100,
             "Change of the break probability per node"},
            p.vegetative_bud_break_probability_decay_rate);
    v.field({"max_terminal_floral_buds", "", 0, 100, "Floral buds at the shoot tip"},
            p.max_terminal_floral_buds);
    v.field({"flower_bud_break_probability", "", 0, 1, "Probability a floral bud flowers"},
            p.flower_bud_break_probability);
    v.field({"fruit_set_probability", "", 0, 1, "Probability a flower sets fruit"},
            p.fruit_set_probability);
    v.field({"flowers_require_dormancy", "", 0, 1, "Floral buds break only after dormancy"},
            p.flowers_require_dormancy);
    v.field({"growth_requires_dormancy", "", 0, 1, "Vegetative buds break only after dormancy"},
            p.growth_requires_dormancy);
    v.field({"determinate_shoot_growth", "", 0, 1, "Shoot stops growing when it flowers"},
            p.determinate_shoot_growth);
    v.field({"child_shoot_types", "", 0, 1,
             "Types of child shoots with probabilities summing to 1 (empty: same type)"},
            p.child_shoot_types);
    v.group("phytomer", p.phytomer_parameters,
            [&](auto& sub) { describeParameters(p.phytomer_parameters, sub); });
}

template <class S, class V>
requires SameAs<S, PhenologyParameters>
void describeParameters(S& p, V& v) {
    v.field({"time_to_dormancy_break", "days", -1, 100000,
             "Dormancy (and each winter) until buds break; negative disables"},
            p.time_to_dormancy_break);
    v.field({"time_to_flower_initiation", "days", -1, 100000,
             "Dormancy break until closed flowers appear; negative skips closed flowers"},
            p.time_to_flower_initiation);
    v.field({"time_to_flower_opening", "days", -1, 100000,
             "Flower initiation (or dormancy break) until flowers open; negative disables"},
            p.time_to_flower_opening);
    v.field({"time_to_fruit_set", "days", -1, 100000,
             "Previous enabled stage until flowers set fruit; negative disables fruit"},
            p.time_to_fruit_set);
    v.field({"time_to_fruit_maturity", "days", -1, 100000, "Fruit set until fruit reach full size"},
            p.time_to_fruit_maturity);
    v.field({"time_to_senescence", "days", -1, 100000,
             "Dormancy break until the season ends (leaves dropped unless evergreen)"},
            p.time_to_senescence);
    v.field({"max_leaf_lifespan", "days", 0, 1e6, "Leaves older than this are shed"},
            p.max_leaf_lifespan);
    v.field({"evergreen", "", 0, 1, "Keep leaves through dormancy"}, p.evergreen);
    v.field({"max_age", "days", 0, 1e6, "The plant stops developing at this age"}, p.max_age);
}

}  // namespace plantarch::params
