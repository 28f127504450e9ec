// `<helios>` files read as the reference system draws them (src/io/helios_pose.h): plants the
// reference system grew and wrote (tests/data/reference_plants/, README there), drawn by
// plantarch, against the boxes the reference drew from the same files; and single organs whose
// drawing by the reference was measured one angle at a time.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "plant_io/plant_structure.h"
#include "plantarch/Context.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

const std::string kDir = std::string(PLANTARCH_SOURCE_DIR) + "/tests/data/reference_plants/";

nlohmann::json boxes() {
    std::ifstream in(kDir + "boxes.json");
    return nlohmann::json::parse(in);
}

AABB boxOf(const Context& ctx, const std::vector<ObjectID>& objects) {
    AABB b;
    for (ObjectID id : objects) {
        const AABB o = ctx.objectBoundingBox(id);
        b.min = glm::min(b.min, o.min);
        b.max = glm::max(b.max, o.max);
    }
    return b;
}

// The largest difference between a box and one of the reference's ([min x y z, max x y z]).
float offBy(const AABB& b, const nlohmann::json& r) {
    float worst = 0.0f;
    for (int k = 0; k < 3; ++k) {
        worst = std::max(worst, std::abs(b.min[k] - r[k].get<float>()));
        worst = std::max(worst, std::abs(b.max[k] - r[k + 3].get<float>()));
    }
    return worst;
}

struct Read {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id = 0;
};

void readInto(Read& r, const std::string& species, const std::string& file) {
    r.arch.loadPlantModelFromLibrary(species);
    PlantStructureReadOptions o;
    o.onWarning = [](const std::string&) {};
    r.id = r.arch.readPlantStructureXML(kDir + file, o).at(0);
}

}  // namespace

// Stems and petioles are where the reference drew them, within a centimetre (measured: under
// 4 mm). Leaves are compared more loosely: the reference's leaf meshes are textured
// rectangles, wider and longer than the blades plantarch draws (its tomato leaflet mesh of
// scale 0.1 is a 9 x 5 cm rectangle beginning 2 cm before the petiole's tip), so their boxes
// differ by that margin even where the leaves lie alike.
TEST(HeliosPose, ReferenceFilesDrawAsTheReferenceDrewThem) {
    const nlohmann::json all = boxes();
    for (const char* name : {"bean_50d", "tomato_45d"}) {
        SCOPED_TRACE(name);
        const nlohmann::json& ref = all.at(name);
        Read r;
        readInto(r, ref.at("species").get<std::string>(), std::string(name) + ".helios.xml");
        const nlohmann::json& drawn = ref.at("drawn_from_file");
        const AABB stems = boxOf(r.ctx, r.arch.getPlantObjectIDs(r.id, OrganKind::Internode));
        const AABB petioles = boxOf(r.ctx, r.arch.getPlantObjectIDs(r.id, OrganKind::Petiole));
        const AABB leaves = boxOf(r.ctx, r.arch.getPlantObjectIDs(r.id, OrganKind::Leaf));
        EXPECT_LT(offBy(stems, drawn.at("internode")), 0.01f);
        EXPECT_LT(offBy(petioles, drawn.at("petiole")), 0.01f);
        EXPECT_LT(offBy(leaves, drawn.at("leaf")), 0.05f);
        // Nothing below the ground that the reference kept above it.
        EXPECT_GE(stems.min.z, std::min(drawn.at("internode")[2].get<float>(), 0.0f) - 0.001f);
        EXPECT_GE(petioles.min.z, std::min(drawn.at("petiole")[2].get<float>(), 0.0f) - 0.001f);
    }
}

// The reference's almond file leaves out the leafless petioles of its trunk, whose directions
// set where the scaffolds went when it grew the tree, and its reader draws another tree than
// the one it grew; plantarch reads the file (its lengths pass their maxima in the last digit)
// and draws the trunk as grown, keeping every organ above the ground.
TEST(HeliosPose, ReferenceAlmondReadsWithItsTrunkAsGrown) {
    const nlohmann::json ref = boxes().at("almond_200d");
    Read r;
    readInto(r, "almond", "almond_200d.helios.xml");
    const PlantInstance& p = r.arch.plant(r.id);
    ASSERT_EQ(p.shoots.size(), 10u);
    std::vector<ObjectID> trunk;
    for (const Phytomer& ph : p.shoots[0].phytomers) trunk.push_back(ph.internode.object);
    EXPECT_LT(offBy(boxOf(r.ctx, trunk), ref.at("built").at("trunk")), 0.001f);
    const AABB all = boxOf(r.ctx, r.arch.getAllPlantObjectIDs(r.id));
    EXPECT_GE(all.min.z, -0.001f);
}

namespace {

// One phytomer of the bean's unifoliate type: an internode 5 cm long and a petiole 5 cm long
// at pitch 90 carrying one leaf, the shoot turned by `rotation` (pitch yaw roll, degrees).
std::string onePhytomer(const std::string& rotation, const std::string& leafAngles) {
    return "<helios><plant_instance ID=\"0\"><base_position>0 0 0</base_position>"
           "<plant_age>30</plant_age><shoot ID=\"0\"><shoot_type_label>unifoliate"
           "</shoot_type_label><parent_shoot_ID>-1</parent_shoot_ID><parent_node_index>0"
           "</parent_node_index><parent_petiole_index>0</parent_petiole_index><base_rotation>" +
           rotation +
           "</base_rotation><phytomer><internode><internode_length>0.05</internode_length>"
           "<internode_radius>0.003</internode_radius><internode_pitch>0</internode_pitch>"
           "<internode_phyllotactic_angle>0</internode_phyllotactic_angle>"
           "<internode_length_max>0.05</internode_length_max><internode_length_segments>1"
           "</internode_length_segments><petiole><petiole_length>0.05</petiole_length>"
           "<petiole_radius>0.002</petiole_radius><petiole_pitch>90</petiole_pitch>"
           "<petiole_curvature>0</petiole_curvature><current_leaf_scale_factor>1"
           "</current_leaf_scale_factor><petiole_taper>0</petiole_taper>"
           "<petiole_length_segments>5</petiole_length_segments><leaf><leaf_scale>0.04"
           "</leaf_scale>" +
           leafAngles +
           "</leaf></petiole></internode></phytomer></shoot></plant_instance></helios>";
}

struct Drawn {
    AABB petiole, leaf;
};

Drawn drawOne(const std::string& rotation, const std::string& leafAngles = "") {
    Read r;
    r.arch.loadPlantModelFromLibrary("bean");
    PlantStructureReadOptions o;
    o.onWarning = [](const std::string&) {};
    r.id = r.arch.readPlantStructureXMLString(onePhytomer(rotation, leafAngles), o).at(0);
    return {boxOf(r.ctx, r.arch.getPlantObjectIDs(r.id, OrganKind::Petiole)),
            boxOf(r.ctx, r.arch.getPlantObjectIDs(r.id, OrganKind::Leaf))};
}

vec3 centre(const AABB& b) {
    return 0.5f * (b.min + b.max);
}

}  // namespace

// What the reference drew from such a file (measured with it): with no base rotation the
// petiole points along -y; yaw turns it about the vertical counterclockwise seen from above
// (90: +x, 180: +y, 270: -x); a single leaf faces the petiole tip's azimuth mirrored about the
// x axis (-y: the leaf turns back toward +y, over the petiole; +x: along it).
TEST(HeliosPose, OneOrganAngleConventions) {
    const struct {
        const char* rotation;
        vec3 petiole;  // direction of the petiole's centre from the node, horizontally
        vec3 leaf;     // direction of the leaf's centre from the petiole tip
    } cases[] = {
        {"0 0 0", {0, -1, 0}, {0, 1, 0}},
        {"0 90 0", {1, 0, 0}, {1, 0, 0}},
        {"0 180 0", {0, 1, 0}, {0, -1, 0}},
        {"0 270 0", {-1, 0, 0}, {-1, 0, 0}},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.rotation);
        const Drawn d = drawOne(c.rotation);
        vec3 p = centre(d.petiole);
        p.z = 0.0f;
        EXPECT_GT(glm::dot(glm::normalize(p), c.petiole), 0.99f);
        const vec3 tip = 2.0f * p;  // the petiole's far end, from its centre
        vec3 l = centre(d.leaf) - tip;
        l.z = 0.0f;
        EXPECT_GT(glm::dot(glm::normalize(l), c.leaf), 0.95f);
    }
    // The leaf's own angles in plantarch's convention, where the file gives them, win.
    const Drawn own = drawOne("0 0 0", "<leaf_angles>0 0 0</leaf_angles>");
    vec3 p = centre(own.petiole);
    vec3 l = centre(own.leaf) - 2.0f * vec3(p.x, p.y, 0.0f);
    l.z = 0.0f;
    EXPECT_GT(glm::dot(glm::normalize(l), vec3(0, -1, 0)), 0.95f) << "along the petiole";
}

// A compound leaf that shed a leaflet is written with the leaflets it keeps; read back, each
// kept leaflet lies where it lay (the file numbers them again: the middle one of three kept
// two becomes a lateral).
TEST(HeliosPose, ShedLeafletsKeepTheirPlaces) {
    Context ctx;
    PlantArchitecture a(&ctx);
    a.loadPlantModelFromLibrary("bean");
    const unsigned id = a.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
    PlantInstance p = a.plant(id);
    std::vector<std::vector<ObjectID>> keptObjects;  // per shedding petiole, left to right
    for (Shoot& s : p.shoots)
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles) {
                if (pt.leaves.size() != 3) continue;
                std::vector<ObjectID> kept;
                for (LeafOrgan& l : pt.leaves) {
                    if (l.leafletIndex == -1) l.removed = true;
                    if (l.leafletIndex == 0) kept.insert(kept.begin(), l.objects.at(0));
                    if (l.leafletIndex == 1) kept.push_back(l.objects.at(0));
                }
                keptObjects.push_back(kept);
            }
    ASSERT_GT(keptObjects.size(), 10u);
    const std::string text = plant_io::writeHeliosPlants({&p});
    Context ctx2;
    PlantArchitecture b(&ctx2);
    b.loadPlantModelFromLibrary("bean");
    PlantStructureReadOptions o;
    o.onWarning = [](const std::string&) {};
    const PlantInstance& q = b.plant(b.readPlantStructureXMLString(text, o).at(0));
    std::size_t at = 0, compared = 0;
    for (const Shoot& s : q.shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles) {
                if (pt.leaves.size() != 2) continue;
                ASSERT_LT(at, keptObjects.size());
                std::vector<const LeafOrgan*> read;
                for (const LeafOrgan& l : pt.leaves) read.push_back(&l);
                std::sort(read.begin(), read.end(), [](const LeafOrgan* x, const LeafOrgan* y) {
                    return x->leafletIndex < y->leafletIndex;
                });
                for (std::size_t i = 0; i < 2; ++i) {
                    // (its shape variant is not in the layout: a few millimetres of outline)
                    const vec3 was = centre(ctx.objectBoundingBox(keptObjects[at][i]));
                    const vec3 now = centre(ctx2.objectBoundingBox(read[i]->objects.at(0)));
                    EXPECT_LT(glm::length(was - now), 0.005f) << at << " " << i;
                    ++compared;
                }
                ++at;
            }
    EXPECT_EQ(at, keptObjects.size());
    EXPECT_GT(compared, 20u);
}
