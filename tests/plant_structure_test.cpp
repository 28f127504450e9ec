// Plant structure files: exact round trips (same geometry bytes now, same plant after more
// growth), canopies in one file, the specification's listing form, and clear errors.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include "collision_scenes.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStateTable.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::firstDifference;
using plantarch::testing::organBytes;

namespace {

namespace fs = std::filesystem;

std::string tempPath(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("plantarch_xml_test_" + std::to_string(::getpid()));
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
    EXPECT_EQ(firstDifference(b.getPlantStructureXML(ids), a.arch.getPlantStructureXML({a.id})),
              "");
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
    EXPECT_EQ(
        firstDifference(fileBytes(tempPath("a/scene.mtl")), fileBytes(tempPath("b/scene.mtl"))),
        "");
    EXPECT_EQ(
        firstDifference(fileBytes(tempPath("a/scene.ply")), fileBytes(tempPath("b/scene.ply"))),
        "");
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
    EXPECT_EQ(firstDifference(b.getPlantStructureXML({id}), a.arch.getPlantStructureXML({a.id})),
              "");
}

// Every library species at its youngest, usual and oldest recommended ages, each with the
// default seed and one other (1, 2, 3): written, read into a fresh PlantArchitecture with
// nothing loaded, every organ's geometry byte for byte the same and the file rewritten the
// same; grown on, the copy stays the original (same events, same random numbers).
class PlantStructureXMLSpecies : public ::testing::TestWithParam<std::string> {};

TEST_P(PlantStructureXMLSpecies, RoundTripsAndGrowsOnIdenticallyAtThreeAgesAndSeeds) {
    const std::string name = GetParam();
    const SpeciesModel model = loadSpecies(name);
    const float ages[] = {model.recommendedAgeMin, model.recommendedAge, model.recommendedAgeMax};
    for (int i = 0; i < 3; ++i)
        for (std::uint64_t seed : {std::uint64_t(42), std::uint64_t(1 + i)}) {
            SCOPED_TRACE(name + " at " + std::to_string(ages[i]) + " days, seed " +
                         std::to_string(seed));
            Built a;
            a.arch.setSeed(seed);
            a.arch.loadPlantModelFromLibrary(name);
            a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.0f), ages[i]);
            const std::string text = a.arch.getPlantStructureXML({a.id});

            Context ctx;
            PlantArchitecture b(&ctx);
            PlantStructureReadOptions o;
            std::string warning;
            o.onWarning = [&](const std::string& w) { warning = w; };
            const unsigned id = b.readPlantStructureXMLString(text, o).at(0);
            EXPECT_EQ(warning, "");
            EXPECT_EQ(firstDifference(organBytes(b, {id}), organBytes(a.arch, {a.id})), "");
            EXPECT_EQ(firstDifference(b.getPlantStructureXML({id}), text), "");

            const double more = std::max(10.0, 0.25 * model.recommendedAge);
            a.arch.advanceTime(more);
            b.advanceTime(more);
            EXPECT_EQ(firstDifference(organBytes(b, {id}), organBytes(a.arch, {a.id})), "");
            EXPECT_EQ(
                firstDifference(b.getPlantStructureXML({id}), a.arch.getPlantStructureXML({a.id})),
                "");
        }
}

INSTANTIATE_TEST_SUITE_P(Library, PlantStructureXMLSpecies, ::testing::ValuesIn(listSpecies()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             return info.param;
                         });

TEST(PlantStructureXML, CanopyInOneFile) {
    Context ctx;
    PlantArchitecture a(&ctx);
    a.setSeed(3);
    a.loadPlantModelFromLibrary("cowpea");
    const auto ids =
        a.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.4f, 0.4f), glm::ivec2(3, 2), 30.0f);
    ASSERT_EQ(ids.size(), 6u);
    const std::string path = tempPath("canopy.xml");
    a.writePlantStructureXML(ids, path);

    Context ctx2;
    PlantArchitecture b(&ctx2);
    const auto read = b.readPlantStructureXML(path);
    EXPECT_EQ(read, ids);  // a fresh PlantArchitecture numbers them as the original did
    EXPECT_EQ(firstDifference(organBytes(b, read), organBytes(a, ids)), "");
    for (std::size_t i = 0; i < ids.size(); ++i)
        EXPECT_EQ(b.getPlantBasePosition(read[i]), a.getPlantBasePosition(ids[i]));
    // Read again into the same PlantArchitecture: six more plants with new IDs.
    const auto again = b.readPlantStructureXML(path);
    EXPECT_EQ(again, (std::vector<unsigned>{6, 7, 8, 9, 10, 11}));
    EXPECT_EQ(b.getAllPlantIDs().size(), 12u);
}

TEST(PlantStructureXML, HandBuiltPlantWithItsOwnShootTypeNeedsNothingPreloaded) {
    Context ctx;
    PlantArchitecture a(&ctx);
    ShootParameters sp;
    sp.phytomer_parameters.leaf.leaves_per_petiole = 5;
    sp.phytomer_parameters.leaf.leaflet_offset = 0.2f;
    sp.phytomer_parameters.leaf.prototype.shape = LeafShape::Lanceolate;
    sp.phytomer_parameters.internode.phyllotactic_angle = RandomFloat::normal(137.5f, 10.0f);
    sp.child_shoot_types = {{"mine", 1.0f}};
    sp.max_nodes = 12;
    a.defineShootType("mine", sp);
    const unsigned p = a.addPlantInstance(vec3(1, 2, 0), 3.0f);
    a.addBaseStemShoot(p, {4, {5, 10, 0}, {0.002f, 0.1f, 1.0f, 1.0f}, 0.2f, "mine"});
    a.addChildShoot(p, 0, 2, ShootSpec{2, {}, {0.001f, 0.05f, 1.0f, 1.0f}, 0.0f, "mine"});
    a.advanceTime(12.0);
    const std::string text = a.getPlantStructureXML({p});
    // Numbers in their shortest round-trip form.
    EXPECT_NE(text.find("<internode_length>0.1</internode_length>"), std::string::npos);
    EXPECT_NE(text.find("<base_position>1 2 0</base_position>"), std::string::npos);
    EXPECT_NE(text.find("<phyllotactic_angle>normal(137.5, 10)</phyllotactic_angle>"),
              std::string::npos);

    Context ctx2;
    PlantArchitecture b(&ctx2);
    EXPECT_TRUE(b.listShootTypeLabels().empty());
    const unsigned q = b.readPlantStructureXMLString(text).at(0);
    EXPECT_EQ(b.listShootTypeLabels(q), std::vector<std::string>{"mine"});
    EXPECT_EQ(firstDifference(organBytes(b, {q}), organBytes(a, {p})), "");
    a.advanceTime(20.0);
    b.advanceTime(20.0);
    EXPECT_EQ(firstDifference(b.getPlantStructureXML({q}), a.getPlantStructureXML({p})), "");
}

TEST(PlantStructureXML, PrunedAndHarvestedPlantsRoundTrip) {
    Context ctx;
    PlantArchitecture a(&ctx);
    a.loadPlantModelFromLibrary("bean");
    const unsigned p = a.buildPlantInstanceFromLibrary(vec3(0.0f), 75.0f);
    ASSERT_GT(a.getShootCount(p), 3u);
    // Harvest returns the fruit the plant carried (a bean at 75 days has pods) and leaves none.
    const std::size_t fruit = a.getPlantObjectIDs(p, OrganKind::Fruit).size();
    ASSERT_GT(fruit, 0u);
    unsigned pods = 0;
    for (const Shoot& s : a.plant(p).shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds)
                    if (fb.stage == FloralStage::Fruit) pods += unsigned(fb.flowers.size());
    const unsigned harvested = a.harvestPlant(p);
    EXPECT_EQ(harvested, pods);
    EXPECT_EQ(a.getPlantObjectIDs(p, OrganKind::Fruit).size(), 0u);
    const unsigned last = unsigned(a.plant(p).shoots.size()) - 1;
    a.pruneBranch(p, last, 0);  // a whole shoot goes
    a.pruneBranch(p, 1, 6);     // the main stem is cut back, with the branches above node 6
    a.removeShootLeaves(p, 1);
    const std::string text = a.getPlantStructureXML({p});
    EXPECT_NE(text.find("<removed>true</removed>"), std::string::npos);

    Context ctx2;
    PlantArchitecture b(&ctx2);
    const unsigned q = b.readPlantStructureXMLString(text).at(0);
    EXPECT_EQ(b.getShootCount(q), a.getShootCount(p));
    EXPECT_EQ(b.getTerminalShoots(q), a.getTerminalShoots(p));
    for (unsigned s = 0; s < a.plant(p).shoots.size(); ++s)
        if (!a.plant(p).shoots[s].removed) {
            EXPECT_EQ(b.getShootChildren(q, s), a.getShootChildren(p, s));
        }
    EXPECT_EQ(b.getPlantObjectIDs(q, OrganKind::Fruit).size(), 0u);
    EXPECT_EQ(firstDifference(organBytes(b, {q}), organBytes(a, {p})), "");
    a.advanceTime(15.0);
    b.advanceTime(15.0);
    EXPECT_EQ(firstDifference(b.getPlantStructureXML({q}), a.getPlantStructureXML({p})), "");
}

TEST(PlantStructureXML, SpecificationListingLoadsWithDefaultsAndAWarning) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    std::vector<std::string> warnings;
    PlantStructureReadOptions o;
    o.nameForErrors = "listing.xml";
    o.onWarning = [&](const std::string& w) { warnings.push_back(w); };
    const auto ids = arch.readPlantStructureXMLString(kListing, o);
    ASSERT_EQ(ids.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    const std::string& w = warnings[0];
    // The growth state a <helios> file does not hold is said once, not named field by field.
    EXPECT_EQ(w.rfind("listing.xml: plant_instance 0: values the file gives nowhere (growth "
                      "state: ages, phenology, random generator, ...) take plantarch's defaults",
                      0),
              0u)
        << w;
    EXPECT_EQ(w.find("random_generator"), std::string::npos) << w;
    EXPECT_NE(w.find("petiole_taper (1): the shoot type's mean"), std::string::npos) << w;
    EXPECT_NE(w.find("the current ones of the PlantArchitecture"), std::string::npos) << w;

    // The listed values are the plant's.
    const unsigned id = ids[0];
    const PlantInstance& p = arch.plant(id);
    EXPECT_EQ(p.age, 2.0);
    ASSERT_EQ(p.shoots.size(), 1u);
    EXPECT_EQ(p.shoots[0].type, "unifoliate");
    EXPECT_EQ(p.shoots[0].baseRotation.yaw, 143.494f);
    const Phytomer& ph = p.shoots[0].phytomers.at(0);
    EXPECT_EQ(ph.internode.length, 0.0063f);
    EXPECT_EQ(ph.internode.phyllotacticAngle, 213.865f);
    EXPECT_EQ(ph.petioles.at(0).curvature, -94.6669f);
    EXPECT_EQ(ph.petioles[0].leaves.at(0).scale, 0.0084f);
    // (its angles become plantarch's own: helios_pose_test.cpp)
    // Drawn: one internode, one petiole, one leaf; the stem tilts by the base pitch.
    EXPECT_EQ(arch.getPlantObjectIDs(id, OrganKind::Internode).size(), 1u);
    EXPECT_EQ(arch.getPlantObjectIDs(id, OrganKind::Petiole).size(), 1u);
    EXPECT_EQ(arch.getPlantObjectIDs(id, OrganKind::Leaf).size(), 1u);
    const vec3 tip = arch.getNodePosition(id, 0, 0);
    EXPECT_NEAR(glm::length(tip), 0.0063f, 1e-6f);
    EXPECT_NEAR(std::acos(tip.z / glm::length(tip)) * 180.0 / 3.14159265, 7.79857, 1e-3);
    // The bean's unifoliate stem has one node; as a trifoliate shoot the same listing grows on
    // with the bean's parameters.
    arch.advanceTime(20.0);
    EXPECT_EQ(arch.getPlantAge(id), 22.0f);
    EXPECT_EQ(arch.getShootNodeCount(id, 0), 1u);
    const std::string trifoliate = replaced(kListing, "> unifoliate <", ">trifoliate<");
    const unsigned grown = arch.readPlantStructureXMLString(trifoliate).at(0);
    arch.advanceTime(grown, 20.0);
    EXPECT_GT(arch.getShootNodeCount(grown, 0), 5u);
}

TEST(PlantStructureXML, ListingWithoutASpeciesUsesDefaultParameters) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    std::string warning;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warning = w; };
    const auto ids = arch.readPlantStructureXMLString(kListing, o);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_NE(warning.find("shoot type unifoliate: plantarch's default parameters"),
              std::string::npos)
        << warning;
    EXPECT_EQ(arch.getPlantObjectIDs(ids[0], OrganKind::Leaf).size(), 1u);
}

namespace {

int lineOf(const std::string& text, const std::string& needle) {
    const auto at = text.find(needle);
    return at == std::string::npos
               ? -1
               : 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

// Reads `damaged` and expects one error, on the line of `marker`, saying `message`.
void expectError(const std::string& damaged, const std::string& marker,
                 const std::string& message) {
    SCOPED_TRACE(message);
    const std::string e = readError(damaged);
    const std::string where = "plants.xml:" + std::to_string(lineOf(damaged, marker)) + ": ";
    EXPECT_EQ(e.rfind(where, 0), 0u) << e;
    EXPECT_NE(e.find(message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

// The bean file with the first `from` replaced.
std::string damage(const std::string& from, const std::string& to) {
    return replaced(beanXML(), from, to);
}

// The bean file with the value of the first <tag> (after `after`) set to `value`.
std::string setFirst(const std::string& tag, const std::string& value,
                     const std::string& after = "") {
    std::string s = beanXML();
    const auto open = s.find("<" + tag + ">", after.empty() ? 0 : s.find(after));
    const auto close = s.find("</" + tag + ">", open);
    EXPECT_NE(open, std::string::npos) << tag;
    const auto start = open + tag.size() + 2;
    s.replace(start, close - start, value);
    return s;
}

// The bean file with the first element <from> renamed to <to>.
std::string renameElement(const std::string& from, const std::string& to) {
    std::string s = beanXML();
    const auto open = s.find("<" + from + ">");
    const auto close = s.find("</" + from + ">", open);
    s.replace(close, from.size() + 3, "</" + to + ">");
    s.replace(open, from.size() + 2, "<" + to + ">");
    return s;
}

}  // namespace

TEST(PlantStructureXML, MalformedInputGivesOneClearError) {
    EXPECT_EQ(readError(beanXML()), "");
    EXPECT_EQ(readError(""), "plants.xml:1: empty file, expected a <plantarch_plants> document");
    // Cut after a whole line half way through: every element still open.
    const std::string half = beanXML().substr(0, beanXML().find('\n', beanXML().size() / 2) + 1);
    EXPECT_NE(readError(half).find("the file ends too early"), std::string::npos)
        << readError(half);
    EXPECT_NE(readError("<plant_instance/>")
                  .find("not a plant structure file: root element <plant_instance>"),
              std::string::npos);
    EXPECT_NE(readError("<plantarch_plants format=\"7\"/>").find("newer format"),
              std::string::npos);
    EXPECT_NE(readError("<plantarch_plants/>").find("missing required attribute 'format'"),
              std::string::npos);
    EXPECT_EQ(readError("<plantarch_plants format=\"1\"/>"), "");  // no plants is fine

    // Wrong types and values out of range.
    std::string d = setFirst("internode_length", "abc");
    expectError(d, ">abc<",
                "plant_instance[0].shoot[0].phytomer[0].internode.internode_length = abc");
    expectError(d, ">abc<", "expected a number");
    d = setFirst("internode_length", "1e30");
    expectError(d, ">1e30<", "out of range (valid: 0 to 1000000)");
    d = setFirst("internode_length", "-0.01");  // lengths are never negative
    expectError(d, ">-0.01<", "internode_length = -0.01: out of range (valid: 0 to 1000000)");
    d = setFirst("internode_length", "nan");
    expectError(d, ">nan<", "expected a number");
    d = setFirst("next_leaf_ID", "99999999999999");
    expectError(d, "99999999999999", "next_leaf_ID = 99999999999999: expected a whole number");
    d = setFirst("next_leaf_ID", "-5");
    expectError(d, ">-5<", "next_leaf_ID = -5: out of range (valid: 0 to 1073741824)");
    d = setFirst("state", "sleeping");
    expectError(d, "sleeping", "unknown value");
    d = setFirst("phenology_stage", "reproductiv");
    expectError(d, "reproductiv<", "did you mean 'reproductive'?");
    d = setFirst("direction", "0 0.5 0.5");
    expectError(d, ">0 0.5 0.5<", "not a unit vector");
    d = setFirst("direction", "0 0 2");
    expectError(d, ">0 0 2<", "not a unit vector");
    // A normalized direction may pass 1 by a rounding; its length is still 1.
    EXPECT_EQ(readError(setFirst("direction", "1.8239518e-08 -1.0000001 -3.972412e-08")), "");
    d = setFirst("random_generator", "12 4");
    expectError(d, ">12 4<", "increment");
    d = setFirst("random_generator", "12");
    expectError(d, ">12<", "expected two whole numbers");
    d = setFirst("flowering", "yes");
    expectError(d, ">yes<", "expected true or false");

    // Unknown, duplicate and misplaced elements.
    d = renameElement("internode_length", "internode_lenght");
    expectError(d, "<internode_lenght>", "did you mean <internode_length>?");
    d = damage("<leaf_pitch>", "<leaf_roll>1</leaf_roll><leaf_pitch>");
    expectError(d, "<leaf_roll>1</leaf_roll><leaf_pitch>", "duplicate element <leaf_roll>");
    d = damage("<plant_age>", "<plant_age>3</plant_age><plant_age>");
    expectError(d, "<plant_age>3", "duplicate element <plant_age>");
    d = damage("<internode_radius>", "<internode_radius><x/>");
    expectError(d, "<x/>", "holds a value, not elements");
    d = damage("<shoot ID=\"1\">", "<shoot ID=\"7\">");
    expectError(d, "<shoot ID=\"7\">", "IDs must count 0, 1, 2, ... in file order");

    // References that do not hold.
    d = damage("<parent_shoot_ID>0</parent_shoot_ID>", "<parent_shoot_ID>99</parent_shoot_ID>");
    expectError(d, "<parent_shoot_ID>99", "a shoot grows from a shoot listed before it");
    d = damage(
        "<parent_node_index>0</parent_node_index>\n      "
        "<parent_petiole_index>0</parent_petiole_index>\n      <base_rotation>0 0 90",
        "<parent_node_index>40</parent_node_index>\n      "
        "<parent_petiole_index>0</parent_petiole_index>\n      <base_rotation>0 0 90");
    expectError(d, "<parent_node_index>40", "no such node on the parent shoot (valid: 0 to 0)");
    d = setFirst("shoot_type_label", "trifoliat", "<shoot ID=\"1\">");
    expectError(d, "trifoliat<", "shoot[1].shoot_type_label = trifoliat: unknown shoot type");
    d = setFirst("shoot_type_label", "trifoliat", "<vegetative_bud>");
    expectError(d, "trifoliat<", "shoot_type_label = trifoliat: unknown shoot type");

    d = damage("<shoot ID=\"0\">\n      <shoot_type_label>unifoliate</shoot_type_label>",
               "<shoot ID=\"0\">");
    expectError(d, "<shoot ID=\"0\">",
                "plant_instance[0].shoot[0].shoot_type_label: missing <shoot_type_label>");

    // Embedded parameters are validated like species files.
    d = damage("<max_nodes>25</max_nodes>", "<max_nodes>-3</max_nodes>");
    expectError(d, "<max_nodes>-3", "max_nodes = -3: out of range");
    d = damage("<phytomer_creation_function/>",
               "<phytomer_creation_function>no_such_function</phytomer_creation_function>");
    const std::string e = readError(d);
    EXPECT_NE(e.find("unknown phytomer creation function"), std::string::npos) << e;
    EXPECT_EQ(e.rfind("plants.xml: ", 0), 0u) << e;
    // And so are the node rules they carry.
    d = damage("<when>creation</when>", "<when>weekly</when>");
    expectError(d, "<when>weekly", "node_rules.rule[0].when = weekly: unknown value");
    d = damage("<leaf_scale>min(1, 0.6 + 0.4 * age / 8)</leaf_scale>",
               "<leaf_scale>min(1, 0.6 + 0.4 * ages / 8)</leaf_scale>");
    expectError(d, "<leaf_scale>min(1, 0.6 + 0.4 * ages",
                "bad expression: unknown name 'ages' at column 20, did you mean 'age'?");
}

namespace {

// Names of every state field, group and list, at every level of the state table.
struct StateNames {
    std::vector<std::string> names;
    template <class T>
    void field(const plantarch::state::FieldInfo& f, T&) {
        names.emplace_back(f.name);
    }
    void legacy(const char* name) { names.emplace_back(name); }
    template <class T>
    void objects(const char* name, T&) {
        names.emplace_back(name);
    }
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        names.emplace_back(name);
        fn(*this);
    }
    template <class T>
    void list(const char* name, std::vector<T>& items, bool = false) {
        names.emplace_back(name);
        items.resize(1);
        plantarch::state::describeState(items[0], *this);
    }
    template <class T>
    void values(const plantarch::state::FieldInfo& f, std::vector<T>&) {
        names.emplace_back(f.name);
    }
    template <class T>
    void optional(const char* name, std::optional<T>& item) {
        names.emplace_back(name);
        item.emplace();
        plantarch::state::describeState(*item, *this);
    }
    template <class P>
    void parameters(const char* name, P&) {
        names.emplace_back(name);
    }
};

}  // namespace

TEST(PlantStructureXML, DocsNameEveryElement) {
    PlantInstance p;
    StateNames v;
    plantarch::state::describeState(p, v);
    ASSERT_GT(v.names.size(), 80u);
    const std::string doc =
        plantarch::testing::fileBytes(std::string(PLANTARCH_SOURCE_DIR) + "/docs/plant-xml.md");
    for (const std::string& name : v.names)
        EXPECT_NE(doc.find("`" + name + "`"), std::string::npos)
            << name << " is not in docs/plant-xml.md";
}

namespace {

// Every value of a state enum has one name, in enumerator order, that parses back, with a
// doc; the names are distinct; docs/`doc` names each as `name`.
template <class E>
void expectNamed(const std::string& doc, const char* file) {
    using namespace plantarch;
    std::set<std::string> seen;
    ASSERT_EQ(kStateCount<E>, kStateNames<E>.size());
    for (std::size_t i = 0; i < kStateCount<E>; ++i) {
        const std::string name = stateName(E(i));
        EXPECT_NE(name, "unknown");
        EXPECT_EQ(stateNamed<E>(name), E(i)) << name;
        EXPECT_TRUE(seen.insert(name).second) << name << " named twice";
        EXPECT_NE(std::string(kStateNames<E>[i].doc), "") << name;
        EXPECT_NE(doc.find("`" + name + "`"), std::string::npos) << name << " is not in " << file;
    }
    EXPECT_EQ(stateNames<E>().size(), kStateCount<E>);
    EXPECT_STREQ(stateName(E(kStateCount<E>)), "unknown");
    EXPECT_FALSE(stateNamed<E>("no such name"));
}

}  // namespace

TEST(PlantStructureXML, EveryStateEnumValueHasANameThatParsesBack) {
    const std::string plantXml =
        plantarch::testing::fileBytes(std::string(PLANTARCH_SOURCE_DIR) + "/docs/plant-xml.md");
    const std::string formats =
        plantarch::testing::fileBytes(std::string(PLANTARCH_SOURCE_DIR) + "/docs/formats.md");
    expectNamed<BudState>(plantXml, "docs/plant-xml.md");
    expectNamed<FloralStage>(plantXml, "docs/plant-xml.md");
    expectNamed<PhenologyStage>(plantXml, "docs/plant-xml.md");
    expectNamed<OrganKind>(formats, "docs/formats.md");
    // The organ labels of exports: "unlabelled", the organ kinds in order, ground, obstacle.
    EXPECT_EQ(plantarch::kOrganLabels.size(), plantarch::kOrganKinds + 3);
    for (std::size_t k = 0; k < plantarch::kOrganKinds; ++k)
        EXPECT_EQ(plantarch::kOrganLabels[k + 1], plantarch::organName(OrganKind(k)));
}

// Each state enum written to a plant file reads back, by its name (a bud's state, a floral
// bud's stage, the plant's phenology stage), and a wrong name is refused with the valid ones.
TEST(PlantStructureXML, StateEnumNamesAreWhatFilesHold) {
    Context ctx;
    PlantArchitecture a(&ctx);
    a.loadPlantModelFromLibrary("bean");
    const unsigned p = a.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
    const std::string text = a.getPlantStructureXML({p});
    for (const char* element : {"<phenology_stage>", "<state>", "<stage>"}) {
        const std::size_t at = text.find(element);
        ASSERT_NE(at, std::string::npos) << element;
        const std::size_t from = at + std::string(element).size();
        const std::string value = text.substr(from, text.find('<', from) - from);
        const bool known = plantarch::stateNamed<BudState>(value) ||
                           plantarch::stateNamed<FloralStage>(value) ||
                           plantarch::stateNamed<PhenologyStage>(value);
        EXPECT_TRUE(known) << element << value;
    }
    std::string bad = text;
    const std::size_t at = bad.find("<phenology_stage>") + std::string("<phenology_stage>").size();
    bad.replace(at, bad.find('<', at) - at, "sleeping");
    Context other;
    PlantArchitecture b(&other);
    try {
        b.readPlantStructureXMLString(bad);
        ADD_FAILURE() << "a wrong phenology stage was read";
    } catch (const plantarch::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("sleeping"), std::string::npos) << message;
        for (const std::string& name : plantarch::stateNames<PhenologyStage>())
            EXPECT_NE(message.find(name), std::string::npos) << message;
    }
}

// A shoot type defined after the plant was made, that the plant's own types name as a child
// type: the plant would copy it when a bud first grows into it, so the file carries it too.
TEST(PlantStructureXML, ChildTypeDefinedAfterThePlantIsWritten) {
    Context ctx;
    PlantArchitecture a(&ctx);
    ShootParameters main;
    main.child_shoot_types = {{"side", 1.0f}};
    main.vegetative_bud_break_probability_min = 1.0f;
    main.vegetative_bud_break_time = 2.0f;
    main.max_nodes = 6;
    a.defineShootType("main", main);
    const unsigned p = a.addPlantInstance(vec3(0.0f), 0.0f);
    a.addBaseStemShoot(p, {1, {}, {0.002f, 0.03f, 1.0f, 1.0f}, 0.0f, "main"});
    ShootParameters side;
    side.max_nodes = 3;
    a.defineShootType("side", side);
    EXPECT_EQ(a.listShootTypeLabels(p), std::vector<std::string>{"main"});
    const std::string text = a.getPlantStructureXML({p});
    EXPECT_NE(text.find("<shoot_type label=\"side\">"), std::string::npos);

    Context ctx2;
    PlantArchitecture b(&ctx2);
    const unsigned q = b.readPlantStructureXMLString(text).at(0);
    a.advanceTime(20.0);
    b.advanceTime(20.0);
    EXPECT_GT(a.getShootCount(p), 1u);  // branches of type "side" grew
    EXPECT_EQ(firstDifference(organBytes(b, {q}), organBytes(a, {p})), "");
}

// ---- a plant's own attraction points ---------------------------------------------------

namespace {

// A bean whose trifoliate shoots are pulled toward a leaning stake beside it.
AttractionPoints stake() {
    AttractionPoints a;
    for (int k = 0; k <= 25; ++k) a.points.push_back(vec3(0.12f, 0.0f, 0.1f + 0.02f * float(k)));
    a.halfAngle = 80.0f;
    a.lookAhead = 0.3f;
    a.inertia = 0.3f;
    a.shootTypes = {"trifoliate"};
    return a;
}

// The XML of `text` without its <attraction_points> element.
std::string withoutAttraction(const std::string& text) {
    const auto open = text.find("    <attraction_points>");
    const std::string close = "</attraction_points>\n";
    const auto end = text.find(close, open);
    EXPECT_NE(open, std::string::npos);
    EXPECT_NE(end, std::string::npos);
    if (open == std::string::npos || end == std::string::npos) return text;
    return text.substr(0, open) + text.substr(end + close.size());
}

}  // namespace

// Points given by the API are part of the plant: written, read back, followed after reading.
TEST(PlantStructureXML, OwnAttractionPointsTravelWithThePlant) {
    Built a;
    a.arch.loadPlantModelFromLibrary("bean");
    a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20.0f);
    a.arch.enableAttractionPoints(a.id, stake());
    const std::string text = a.arch.getPlantStructureXML({a.id});
    EXPECT_NE(text.find("<attraction_points>\n      <half_angle>80</half_angle>\n      "
                        "<look_ahead>0.3</look_ahead>\n      <inertia>0.3</inertia>\n      "
                        "<shoot_types>trifoliate</shoot_types>\n      <point>0.12 0 0.1</point>"),
              std::string::npos);

    Context ctx;
    PlantArchitecture b(&ctx);
    std::string warning;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warning = w; };
    const unsigned q = b.readPlantStructureXMLString(text, o).at(0);
    EXPECT_EQ(warning, "");
    ASSERT_TRUE(b.plant(q).attraction.has_value());
    EXPECT_EQ(*b.plant(q).attraction, stake());
    EXPECT_EQ(b.getAttractionPoints(q), stake().points);
    EXPECT_EQ(b.getPlantStructureXML({q}), text);

    // The same file without the element: a plant without points (an older file).
    Context ctx2;
    PlantArchitecture c(&ctx2);
    const unsigned r = c.readPlantStructureXMLString(withoutAttraction(text), o).at(0);
    EXPECT_EQ(warning, "");  // optional: nothing is reported missing
    EXPECT_FALSE(c.plant(r).attraction.has_value());
    EXPECT_TRUE(c.getAttractionPoints(r).empty());
    // A file written before the element existed (the fuzzing seed): no attraction points, and
    // the element is not among the values reported missing.
    const std::string seeds = std::string(PLANTARCH_SOURCE_DIR) + "/fuzz/corpus/plant_xml/";
    {
        Context ctx3;
        PlantArchitecture d(&ctx3);
        std::string old;
        PlantStructureReadOptions keep;
        keep.onWarning = [&](const std::string& w) { old = w; };
        const unsigned o1 =
            d.readPlantStructureXML(seeds + "small_plant_with_parameters.xml", keep).at(0);
        EXPECT_FALSE(d.plant(o1).attraction.has_value());
        EXPECT_EQ(old.find("attraction"), std::string::npos) << old;
        const unsigned o2 =
            d.readPlantStructureXML(seeds + "small_plant_with_attraction_points.xml").at(0);
        ASSERT_TRUE(d.plant(o2).attraction.has_value());
        EXPECT_EQ(d.plant(o2).attraction->points.size(), 3u);
        EXPECT_EQ(d.plant(o2).attraction->shootTypes, std::vector<std::string>{"main"});
    }

    a.arch.advanceTime(25.0);
    b.advanceTime(25.0);
    c.advanceTime(25.0);
    EXPECT_GT(b.getCollisionStats().attracted, 10u);
    EXPECT_EQ(b.getCollisionStats().attracted, a.arch.getCollisionStats().attracted);
    EXPECT_EQ(firstDifference(organBytes(b, {q}), organBytes(a.arch, {a.id})), "");
    EXPECT_EQ(firstDifference(b.getPlantStructureXML({q}), a.arch.getPlantStructureXML({a.id})),
              "");
    // The points made a difference: the plant read without them grew otherwise.
    EXPECT_EQ(c.getCollisionStats().attracted, 0u);
    EXPECT_NE(firstDifference(organBytes(c, {r}), organBytes(a.arch, {a.id})), "");

    // Disabled, the plant is written without them; deleted, they go with it.
    b.disableAttractionPoints(q);
    EXPECT_EQ(b.getPlantStructureXML({q}).find("<attraction_points>"), std::string::npos);
    const unsigned other = b.addPlantInstance(vec3(1, 0, 0), 0.0f);
    b.enableAttractionPoints(q, stake());
    b.deletePlantInstance(q);
    b.resetCollisionStats();
    b.advanceTime(other, 5.0);
    EXPECT_EQ(b.getCollisionStats().attractionQueries, 0u);
}

// Every bad value of <attraction_points> is one error naming file, line, element, value and
// the valid range.
TEST(PlantStructureXML, BadAttractionPointsGiveOneClearError) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 5.0f);
    arch.enableAttractionPoints(id, stake());
    const std::string good = arch.getPlantStructureXML({id});
    EXPECT_EQ(readError(good), "");
    const std::string at = "plant_instance[0].attraction_points.";
    const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
        {"<half_angle>80<", "<half_angle>0<",
         at + "half_angle = 0: out of range (valid: > 0 and < 180)"},
        {"<half_angle>80<", "<half_angle>180<",
         at + "half_angle = 180: out of range (valid: > 0 and < 180)"},
        {"<half_angle>80<", "<half_angle>wide<", at + "half_angle = wide: expected a number"},
        {"<look_ahead>0.3<", "<look_ahead>0<",
         at + "look_ahead = 0: out of range (valid: > 0 and <= 100)"},
        {"<look_ahead>0.3<", "<look_ahead>101<",
         at + "look_ahead = 101: out of range (valid: > 0 and <= 100)"},
        {"<inertia>0.3<", "<inertia>1.5<", at + "inertia = 1.5: out of range (valid: 0 to 1)"},
        {"<inertia>0.3<", "<inertia>-0.1<", at + "inertia = -0.1: out of range (valid: 0 to 1)"},
        {"<shoot_types>trifoliate<", "<shoot_types>trifoliate,unifoliate<",
         at + "shoot_types = trifoliate,unifoliate: a shoot type label is letters, digits, '_' "
              "or '-' (valid: shoot type labels separated by spaces)"},
        {"<point>0.12 0 0.1<", "<point>0.12 0<", at + "point = 0.12 0: expected three numbers"},
        {"<point>0.12 0 0.1<", "<point>0.12 nan 0.1<",
         at + "point = 0.12 nan 0.1: expected three numbers"},
        {"<point>0.12 0 0.1<", "<point>0.12 0 2e6<",
         at + "point = 0.12 0 2e6: out of range (valid: -1000000 to 1000000)"},
        {"<inertia>0.3</inertia>", "<inertia>0.3</inertia><inertia>0.3</inertia>",
         "duplicate element <inertia>"},
        {"<attraction_points>", "<attraction_points ID=\"1\">",
         "unknown attribute 'ID' of <attraction_points>"},
        {"<attraction_points>", "<attraction_points>x", "unexpected text inside"},
    };
    for (const auto& [from, to, message] : cases) {
        SCOPED_TRACE(to);
        const std::string damaged = replaced(good, from, to);
        const std::string e = readError(damaged);
        EXPECT_EQ(e.rfind("plants.xml:" + std::to_string(lineOf(damaged, to)) + ": ", 0), 0u) << e;
        EXPECT_NE(e.find(message), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos);
    }
    const std::string misspelt =
        replaced(replaced(good, "<half_angle>", "<half_angel>"), "</half_angle>", "</half_angel>");
    const std::string e = readError(misspelt);
    EXPECT_EQ(e.rfind("plants.xml:" + std::to_string(lineOf(misspelt, "<half_angel>")) + ": " + at +
                          "half_angel: unknown element <half_angel> in <attraction_points>, "
                          "did you mean <half_angle>?",
                      0),
              0u)
        << e;
}

// The trellis species carry their wires in their files: read back, a plant grows on along
// them exactly as the original does. (The Wye's default wires are above what its shoots reach
// by then; lowered, they catch them.)
TEST(PlantStructureXML, TrellisPlantsFollowTheirWiresAfterReading) {
    struct Case {
        const char* species;
        std::map<std::string, float> parameters;
        float age;
        double days;
        std::size_t points;
    };
    for (const Case& c : {Case{"apple_fruitingwall", {}, 180.0f, 450.0, 32},
                          Case{"grapevine_Wye", {{"catch_wire_height", 1.2f}}, 200.0f, 70.0, 48}}) {
        SCOPED_TRACE(c.species);
        Built a;
        a.arch.loadPlantModelFromLibrary(c.species);
        a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.3f, 0.1f, 0.0f), c.age, c.parameters);
        const std::string text = a.arch.getPlantStructureXML({a.id});
        std::size_t points = 0;
        for (auto at = text.find("<point>"); at != std::string::npos;
             at = text.find("<point>", at + 1))
            ++points;
        EXPECT_EQ(points, c.points);

        Context ctx, ctx2;
        PlantArchitecture b(&ctx), bare(&ctx2);
        const unsigned q = b.readPlantStructureXMLString(text).at(0);
        const unsigned r = bare.readPlantStructureXMLString(withoutAttraction(text)).at(0);
        EXPECT_EQ(b.getAttractionPoints(q), a.arch.getAttractionPoints(a.id));
        a.arch.resetCollisionStats();
        a.arch.advanceTime(c.days);
        b.advanceTime(c.days);
        bare.advanceTime(c.days);
        EXPECT_GT(b.getCollisionStats().attracted, 50u);
        EXPECT_EQ(b.getCollisionStats().attracted, a.arch.getCollisionStats().attracted);
        EXPECT_EQ(firstDifference(organBytes(b, {q}), organBytes(a.arch, {a.id})), "");
        EXPECT_EQ(firstDifference(b.getPlantStructureXML({q}), a.arch.getPlantStructureXML({a.id})),
                  "");
        // Read without its wires, the plant grows otherwise.
        EXPECT_NE(firstDifference(organBytes(bare, {r}), organBytes(a.arch, {a.id})), "");
    }
}

namespace {

// How many of a plant's organs solid obstacles turned (petioles, peduncles, fruit).
std::size_t clearanceTurns(const PlantInstance& p) {
    std::size_t n = 0;
    for (const Shoot& s : p.shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles) {
                n += pt.clearance.angle != 0.0f ? 1 : 0;
                for (const FloralBud& fb : pt.floralBuds) {
                    n += fb.peduncleClearance.angle != 0.0f ? 1 : 0;
                    for (const FlowerOrgan& f : fb.flowers) n += f.clearance.angle != 0.0f ? 1 : 0;
                }
            }
    return n;
}

}  // namespace

// A plant grown against solid obstacles keeps the turns that took its organs out of them: read
// into a Context without the obstacles, it draws the same geometry, and grown on beside the
// same obstacles it stays the original. A strawberry whose fruit rest on the ground (fruit
// adjustment) and a bean against a wall (petioles and peduncles turned out of it).
TEST(PlantStructureXML, ObstacleTurnsTravelWithThePlant) {
    struct Case {
        std::string species;
        vec3 lo, hi;
        bool fruitAdjustment;
        float age;
        bool longStalks;  // fruit stalks long and arched enough for ripe fruit to reach the soil
    };
    const std::vector<Case> cases = {
        {"strawberry", {-2, -2, -0.1f}, {2, 2, 0.0f}, true, 90.0f, true},
        {"bean", {0.1f, -2, -1}, {0.3f, 2, 3}, false, 45.0f, false}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.species);
        Built a;
        const ObjectID obstacle = plantarch::test::addBox(a.ctx, c.lo, c.hi);
        a.arch.setSeed(4);
        a.arch.loadPlantModelFromLibrary(c.species);
        if (c.longStalks) {
            ShootParameters crown = a.arch.getCurrentShootParameters("mainstem");
            crown.phytomer_parameters.peduncle.length = 0.3f;
            crown.phytomer_parameters.peduncle.curvature = -400.0f;
            a.arch.updateCurrentShootParameters("mainstem", crown);
        }
        const SolidObstacleOptions solid{.obstacles = {obstacle},
                                         .avoidanceDistance = 0.1f,
                                         .fruitAdjustment = c.fruitAdjustment};
        a.arch.enableSolidObstacleAvoidance(solid);
        a.id = a.arch.buildPlantInstanceFromLibrary(vec3(0.0f), c.age);
        ASSERT_GT(clearanceTurns(a.arch.plant(a.id)), 2u) << "the obstacle turned nothing";
        const std::string text = a.arch.getPlantStructureXML({a.id});

        Context ctx;
        PlantArchitecture b(&ctx);
        b.setSeed(4);  // steering draws its cone rays from the scene's seed, not the plant's
        const unsigned id = b.readPlantStructureXMLString(text).at(0);
        EXPECT_EQ(clearanceTurns(b.plant(id)), clearanceTurns(a.arch.plant(a.id)));
        EXPECT_EQ(firstDifference(organBytes(b, {id}), organBytes(a.arch, {a.id})), "");
        EXPECT_EQ(firstDifference(b.getPlantStructureXML({id}), text), "");

        // Beside the same obstacle, both grow on alike.
        const ObjectID again = plantarch::test::addBox(ctx, c.lo, c.hi);
        SolidObstacleOptions solidB = solid;
        solidB.obstacles = {again};
        b.enableSolidObstacleAvoidance(solidB);
        a.arch.advanceTime(10.0);
        b.advanceTime(10.0);
        EXPECT_EQ(firstDifference(organBytes(b, {id}), organBytes(a.arch, {a.id})), "");
    }
}
