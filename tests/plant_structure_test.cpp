// Plant structure files: exact round trips (same geometry bytes now, same plant after more
// growth), canopies in one file, the specification's listing form, and clear errors.

#include <gtest/gtest.h>

#include <filesystem>

#include "plant_geometry_bytes.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::firstDifference;
using plantarch::testing::organBytes;

namespace {

namespace fs = std::filesystem;

std::string tempPath(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("plantarch_xml_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return (dir / name).string();
}

struct Built {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id = 0;
};

// The specification's sample listing, as printed.
const char* kListing = R"(<helios>
  <plant_instance ID="0">
    <base_position> 0 0 0 </base_position>
    <plant_age> 2 </plant_age>
    <shoot ID="0">
      <shoot_type_label> unifoliate </shoot_type_label>
      <parent_shoot_ID> -1 </parent_shoot_ID>
      <parent_node_index> 0 </parent_node_index>
      <parent_petiole_index> 0 </parent_petiole_index>
      <base_rotation> 7.79857 143.494 62.5022 </base_rotation>
      <phytomer>
        <internode>
          <internode_length>0.0063</internode_length>
          <internode_radius>0.000657844</internode_radius>
          <internode_pitch>0</internode_pitch>
          <phyllotactic_angle>213.865</phyllotactic_angle>
          <petiole>
            <petiole_length>0.00623</petiole_length>
            <petiole_radius>0.00145</petiole_radius>
            <petiole_pitch>58.0717</petiole_pitch>
            <petiole_curvature>-94.6669</petiole_curvature>
            <leaflet_scale>1</leaflet_scale>
            <leaf>
              <leaf_scale>0.0084</leaf_scale>
              <leaf_pitch>5.60887</leaf_pitch>
              <leaf_yaw>0</leaf_yaw>
              <leaf_roll>-15</leaf_roll>
            </leaf>
          </petiole>
        </internode>
      </phytomer>
    </shoot>
  </plant_instance>
</helios>
)";

// The error message of reading `xml` into a fresh PlantArchitecture ("" when it reads).
std::string readError(const std::string& xml) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    PlantStructureReadOptions o;
    o.nameForErrors = "plants.xml";
    try {
        arch.readPlantStructureXMLString(xml, o);
    } catch (const Error& e) {
        EXPECT_EQ(arch.getAllPlantIDs().size(), 0u) << "nothing is added on error";
        EXPECT_EQ(ctx.objectCount(), 0u);
        return e.what();
    }
    return "";
}

// A bean written to text, for the error tests to damage.
const std::string& beanXML() {
    static const std::string text = [] {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20.0f);
        return arch.getPlantStructureXML({id});
    }();
    return text;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

}  // namespace

TEST(PlantStructureXML, BeanRoundTripGivesTheSameGeometryAndText) {
    Built a;
    a.arch.loadPlantModelFromLibrary("bean");
    a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.1f, -0.2f, 0.0f), 45.0f);
    const std::string path = tempPath("bean45.xml");
    a.arch.writePlantStructureXML(a.id, path);

    Context ctx;
    PlantArchitecture b(&ctx);  // nothing loaded: the file carries the species parameters
    std::vector<std::string> warnings;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warnings.push_back(w); };
    const std::vector<unsigned> ids = b.readPlantStructureXML(path, o);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(firstDifference(organBytes(b, ids), organBytes(a.arch, {a.id})), "");
    EXPECT_EQ(firstDifference(b.getPlantStructureXML(ids), a.arch.getPlantStructureXML({a.id})), "");
    EXPECT_EQ(b.plant(ids[0]).rng, a.arch.plant(a.id).rng);
    EXPECT_EQ(b.getPlantLeafArea(ids[0]), a.arch.getPlantLeafArea(a.id));
    EXPECT_EQ(b.getShootChildren(ids[0], 0), a.arch.getShootChildren(a.id, 0));

    // Exported in organ order, both give the same OBJ and PLY bytes.
    const Context ca = plantarch::testing::canonicalScene(a.arch, {a.id});
    const Context cb = plantarch::testing::canonicalScene(b, ids);
    fs::create_directories(tempPath("a"));
    fs::create_directories(tempPath("b"));
    writeOBJ(ca, tempPath("a/scene.obj"));
    writeOBJ(cb, tempPath("b/scene.obj"));
    writePLY(ca, tempPath("a/scene.ply"));
    writePLY(cb, tempPath("b/scene.ply"));
    using plantarch::testing::fileBytes;
    const std::string obj = fileBytes(tempPath("a/scene.obj"));
    EXPECT_GT(obj.size(), 1000000u);
    EXPECT_EQ(firstDifference(obj, fileBytes(tempPath("b/scene.obj"))), "");
    EXPECT_EQ(firstDifference(fileBytes(tempPath("a/scene.mtl")), fileBytes(tempPath("b/scene.mtl"))), "");
    EXPECT_EQ(firstDifference(fileBytes(tempPath("a/scene.ply")), fileBytes(tempPath("b/scene.ply"))), "");
}

TEST(PlantStructureXML, ContinuedGrowthMatchesTheOriginal) {
    Built a;
    a.arch.loadPlantModelFromLibrary("bean");
    a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.0f), 25.0f);
    const std::string text = a.arch.getPlantStructureXML({a.id});

    Context ctx;
    PlantArchitecture b(&ctx);
    const unsigned id = b.readPlantStructureXMLString(text).at(0);
    a.arch.advanceTime(30.0);
    b.advanceTime(30.0);
    EXPECT_GT(a.arch.getPlantLeafCount(a.id), 0u);
    EXPECT_EQ(firstDifference(organBytes(b, {id}), organBytes(a.arch, {a.id})), "");
    EXPECT_EQ(firstDifference(b.getPlantStructureXML({id}), a.arch.getPlantStructureXML({a.id})), "");
}
