// Presets of the organ library: the family, parameters and colour that reproduce the flowers
// and fruit of the reference species (OrganLibrary.h, floralPresets()).
//
// prototypeScale is the organ's length along its axis in metres (the prototype convention
// scales x from 0 to 1). For open flowers most of the size is across the axis, so the scale
// is the flower's diameter divided by its diameter-to-length ratio (given per preset).

#include "plantarch/Error.h"
#include "plantarch/OrganLibrary.h"

namespace plantarch {

namespace {

void addRadialFlowerPresets(std::vector<FloralPreset>& v) {
    auto add = [&](FloralPreset p) { v.push_back(std::move(p)); };
    add({"almond_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.85f},
          {"cup_angle", 72},
          {"reflex", 8},
          {"stamen_count", 26},
          {"centre_r", 0.72f},
          {"centre_g", 0.28f},
          {"centre_b", 0.40f},
          {"sepal_angle", 110}},
         {0.98f, 0.91f, 0.93f},
         8,
         0.011f,
         {"almond", "almond_aldrich", "almond_wood_colony"}});
    add({"apple_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.8f},
          {"cup_angle", 65},
          {"reflex", 5},
          {"stamen_count", 20},
          {"centre_r", 0.93f},
          {"centre_g", 0.85f},
          {"centre_b", 0.35f},
          {"petal_cupping", 0.2f}},
         {0.99f, 0.94f, 0.95f},
         8,
         0.016f,
         {"apple", "apple_fruitingwall"}});
    add({"strawberry_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.95f},
          {"petal_widest", 0.55f},
          {"cup_angle", 80},
          {"reflex", 5},
          {"centre_size", 0.14f},
          {"stamen_count", 24},
          {"sepal_count", 10},
          {"sepal_length", 0.35f},
          {"sepal_angle", 95}},
         {0.99f, 0.99f, 0.97f},
         8,
         0.0075f,
         {"strawberry"}});
    add({"tomato_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.32f},
          {"petal_tip", 1},
          {"petal_widest", 0.3f},
          {"cup_angle", 80},
          {"reflex", 65},
          {"petal_cupping", 0.05f},
          {"stamen_count", 0},
          {"centre_size", 0.06f},
          {"anther_cone", 0.45f},
          {"centre_r", 0.95f},
          {"centre_g", 0.78f},
          {"centre_b", 0.08f},
          {"sepal_length", 0.45f},
          {"sepal_width", 0.16f},
          {"sepal_angle", 75}},
         {0.98f, 0.86f, 0.12f},
         8,
         0.0125f,
         {"tomato", "cherrytomato"}});
    add({"capsicum_flower",
         "petal_flower",
         false,
         {{"petal_count", 6},
          {"petal_width", 0.45f},
          {"petal_tip", 0.8f},
          {"petal_widest", 0.4f},
          {"cup_angle", 85},
          {"reflex", 12},
          {"stamen_count", 6},
          {"stamen_length", 0.2f},
          {"centre_size", 0.07f},
          {"centre_r", 0.45f},
          {"centre_g", 0.45f},
          {"centre_b", 0.72f},
          {"sepal_length", 0.12f}},
         {0.98f, 0.98f, 0.96f},
         8,
         0.005f,
         {"capsicum"}});
    add({"puncturevine_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.7f},
          {"petal_widest", 0.65f},
          {"cup_angle", 82},
          {"reflex", 5},
          {"stamen_count", 10},
          {"sepal_length", 0.35f},
          {"sepal_angle", 70}},
         {0.98f, 0.84f, 0.12f},
         6,
         0.003f,
         {"puncturevine"}});
    add({"olive_flower",
         "petal_flower",
         false,
         {{"petal_count", 4},
          {"petal_width", 0.55f},
          {"petal_tip", 0.4f},
          {"cup_angle", 88},
          {"reflex", 20},
          {"stamen_count", 2},
          {"stamen_length", 0.22f},
          {"sepal_length", 0.08f}},
         {0.97f, 0.96f, 0.88f},
         6,
         0.0016f,
         {"olive"}});
    add({"cheeseweed_flower",
         "petal_flower",
         false,
         {{"petal_count", 5},
          {"petal_width", 0.6f},
          {"cup_angle", 60},
          {"reflex", 10},
          {"stamen_count", 12},
          {"centre_r", 0.96f},
          {"centre_g", 0.94f},
          {"centre_b", 0.9f}},
         {0.88f, 0.76f, 0.90f},
         6,
         0.005f,
         {"cheeseweed"}});
}

void addOtherFlowerPresets(std::vector<FloralPreset>& v) {
    auto add = [&](FloralPreset p) { v.push_back(std::move(p)); };
    add({"bean_flower",
         "papilionaceous_flower",
         false,
         {{"keel_curl", 250}, {"banner_width", 1.1f}, {"banner_angle", 105}},
         {0.97f, 0.96f, 0.95f},
         8,
         0.018f,
         {"bean"}});
    add({"cowpea_flower",
         "papilionaceous_flower",
         false,
         {{"banner_length", 0.7f},
          {"banner_width", 1.25f},
          {"banner_angle", 110},
          {"keel_curl", 90},
          {"wing_angle", 28}},
         {0.94f, 0.92f, 0.55f},
         8,
         0.025f,
         {"cowpea"}});
    add({"soybean_flower",
         "papilionaceous_flower",
         false,
         {{"banner_length", 0.5f}, {"banner_width", 1.0f}, {"keel_curl", 45}},
         {0.80f, 0.62f, 0.88f},
         6,
         0.007f,
         {"soybean"}});
    add({"redbud_flower",
         "papilionaceous_flower",
         false,
         {{"banner_length", 0.35f},
          {"banner_width", 0.8f},
          {"banner_angle", 125},
          {"wing_length", 0.5f},
          {"wing_angle", 35},
          {"keel_curl", 20},
          {"keel_length", 0.5f}},
         {0.86f, 0.36f, 0.66f},
         6,
         0.011f,
         {"easternredbud"}});
    add({"bindweed_flower",
         "funnel_flower",
         false,
         {},
         {0.98f, 0.96f, 0.97f},
         10,
         0.011f,
         {"bindweed"}});
    add({"groundcherry_flower",
         "funnel_flower",
         false,
         {{"mouth_width", 2.8f},
          {"tube_width", 0.35f},
          {"flare", 1.4f},
          {"lobe_depth", 0.12f},
          {"pleat", 0.03f},
          {"throat_fraction", 0.3f},
          {"throat_r", 0.36f},
          {"throat_g", 0.22f},
          {"throat_b", 0.16f},
          {"sepal_length", 0.25f}},
         {0.96f, 0.88f, 0.35f},
         8,
         0.005f,
         {"groundcherryweed"}});
    add({"walnut_catkin", "catkin", false, {}, {0.62f, 0.64f, 0.30f}, 6, 0.08f, {"walnut"}});
    add({"bougainvillea_flower",
         "bract_flower",
         false,
         {},
         {0.78f, 0.14f, 0.50f},
         8,
         0.03f,
         {"bougainvillea"}});
}

void addFruitPresets(std::vector<FloralPreset>& v) {
    auto add = [&](FloralPreset p) { v.push_back(std::move(p)); };
    add({"almond_hull",
         "almond",
         true,
         {},
         {0.46f, 0.54f, 0.34f},
         10,
         0.04f,
         {"almond", "almond_aldrich", "almond_wood_colony"}});
    add({"apple_fruit",
         "apple",
         true,
         {},
         {0.74f, 0.13f, 0.10f},
         12,
         0.075f,
         {"apple", "apple_fruitingwall"}});
    add({"bean_pod",
         "legume_pod",
         true,
         {{"width", 0.09f},
          {"thickness", 0.065f},
          {"curvature", 25},
          {"seed_count", 6},
          {"seed_bump", 0.2f},
          {"beak_length", 0.06f}},
         {0.42f, 0.58f, 0.22f},
         10,
         0.15f,
         {"bean"}});
    add({"cowpea_pod",
         "legume_pod",
         true,
         {{"width", 0.045f},
          {"thickness", 0.035f},
          {"curvature", 15},
          {"seed_count", 14},
          {"seed_bump", 0.25f},
          {"beak_length", 0.04f}},
         {0.40f, 0.52f, 0.22f},
         10,
         0.2f,
         {"cowpea"}});
    add({"soybean_pod",
         "legume_pod",
         true,
         {{"width", 0.22f},
          {"thickness", 0.12f},
          {"curvature", 12},
          {"seed_count", 3},
          {"seed_bump", 0.3f},
          {"beak_length", 0.08f},
          {"hairs", 1}},
         {0.52f, 0.58f, 0.28f},
         8,
         0.05f,
         {"soybean"}});
    add({"redbud_pod",
         "legume_pod",
         true,
         {{"width", 0.2f},
          {"thickness", 0.02f},
          {"curvature", 8},
          {"seed_count", 6},
          {"seed_bump", 0.12f},
          {"section_lens", 1},
          {"beak_length", 0.06f}},
         {0.45f, 0.33f, 0.30f},
         8,
         0.08f,
         {"easternredbud"}});
    add({"capsicum_fruit", "pepper", true, {}, {0.78f, 0.10f, 0.07f}, 12, 0.14f, {"capsicum"}});
    add({"tomato_fruit",
         "berry",
         true,
         {{"aspect", 0.8f},
          {"ribs", 6},
          {"rib_depth", 0.08f},
          {"sepal_length", 0.35f},
          {"sepal_curl", 30},
          {"stem_length", 0.12f}},
         {0.85f, 0.14f, 0.07f},
         12,
         0.07f,
         {"tomato"}});
    add({"cherrytomato_fruit",
         "berry",
         true,
         {{"aspect", 1.0f}, {"sepal_length", 0.45f}, {"sepal_width", 0.18f}, {"stem_length", 0.2f}},
         {0.85f, 0.14f, 0.07f},
         10,
         0.03f,
         {"cherrytomato"}});
    add({"groundcherry_fruit",
         "berry",
         true,
         {{"aspect", 0.95f}, {"husk", 1}, {"husk_size", 1.5f}},
         {0.70f, 0.72f, 0.30f},
         10,
         0.035f,
         {"groundcherryweed"}});
    add({"grape_cluster",
         "grape_cluster",
         true,
         {},
         {0.24f, 0.18f, 0.34f},
         6,
         0.18f,
         {"grapevine_VSP", "grapevine_Wye"}});
    add({"olive_fruit", "olive", true, {}, {0.42f, 0.48f, 0.16f}, 10, 0.025f, {"olive"}});
    add({"pistachio_cluster",
         "pistachio_cluster",
         true,
         {},
         {0.86f, 0.64f, 0.56f},
         6,
         0.15f,
         {"pistachio"}});
    add({"strawberry_fruit",
         "strawberry",
         true,
         {},
         {0.82f, 0.08f, 0.10f},
         10,
         0.045f,
         {"strawberry"}});
    add({"walnut_fruit", "walnut", true, {}, {0.42f, 0.53f, 0.22f}, 10, 0.055f, {"walnut"}});
}

void addCerealPresets(std::vector<FloralPreset>& v) {
    auto add = [&](FloralPreset p) { v.push_back(std::move(p)); };
    add({"wheat_spike", "wheat_spike", true, {}, {0.50f, 0.58f, 0.26f}, 6, 0.1f, {"wheat"}});
    add({"rice_panicle", "rice_panicle", true, {}, {0.80f, 0.68f, 0.36f}, 6, 0.22f, {"rice"}});
    add({"sorghum_panicle",
         "sorghum_panicle",
         true,
         {},
         {0.58f, 0.33f, 0.20f},
         6,
         0.25f,
         {"sorghum"}});
    add({"maize_tassel", "maize_tassel", true, {}, {0.72f, 0.64f, 0.38f}, 6, 0.35f, {"maize"}});
    add({"maize_ear", "maize_ear", true, {}, {0.45f, 0.60f, 0.28f}, 10, 0.22f, {"maize"}});
}

}  // namespace

const std::vector<FloralPreset>& floralPresets() {
    static const std::vector<FloralPreset> presets = [] {
        std::vector<FloralPreset> v;
        addRadialFlowerPresets(v);
        addOtherFlowerPresets(v);
        addFruitPresets(v);
        addCerealPresets(v);
        return v;
    }();
    return presets;
}

const FloralPreset& floralPreset(std::string_view name) {
    for (const FloralPreset& p : floralPresets())
        if (p.name == name) return p;
    std::string names = "one of:";
    for (const FloralPreset& p : floralPresets()) names += " " + p.name;
    throw Error("unknown flower/fruit preset",
                {.parameter = "preset", .value = std::string(name), .validRange = names});
}

}  // namespace plantarch
