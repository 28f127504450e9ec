// Plant strings: the documented grammar, exact string -> plant -> string round trips for
// every library species at three ages, the structure kept, and clear errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "collision_scenes.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::firstDifference;

namespace {

struct Counts {
    unsigned shoots = 0, internodes = 0, petioles = 0, leaves = 0, floral = 0, flowers = 0;
    bool operator==(const Counts&) const = default;
};

// What a plant string holds: drawn shoots, their organs, visible flowers and fruit.
Counts countVisible(const PlantInstance& p) {
    Counts c;
    auto floral = [&](const FloralBud& fb) {
        if (fb.stage == FloralStage::Bud || fb.stage == FloralStage::Removed) return;
        ++c.floral;
        c.flowers += unsigned(fb.flowers.size());
    };
    for (const Shoot& s : p.shoots) {
        if (s.removed || s.phytomers.empty()) continue;
        ++c.shoots;
        for (const Phytomer& ph : s.phytomers) {
            ++c.internodes;
            for (const Petiole& pt : ph.petioles) {
                ++c.petioles;
                for (const LeafOrgan& l : pt.leaves) c.leaves += l.removed ? 0 : 1;
                for (const FloralBud& fb : pt.floralBuds) floral(fb);
            }
        }
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
    }
    return c;
}

std::string stringError(const std::string& text) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    try {
        arch.generatePlantFromString(text);
    } catch (const Error& e) {
        EXPECT_TRUE(arch.getAllPlantIDs().empty());
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PlantString, HandBuiltPlantGivesTheDocumentedString) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters sp;
    sp.phytomer_parameters.internode.pitch = 0.0f;
    sp.phytomer_parameters.internode.phyllotactic_angle = 180.0f;
    sp.phytomer_parameters.petiole.pitch = 45.0f;
    sp.phytomer_parameters.petiole.length = 0.04f;
    sp.phytomer_parameters.petiole.radius = 0.001f;
    sp.phytomer_parameters.leaf.prototype_scale = 0.06f;
    sp.phytomer_parameters.leaf.pitch = 10.0f;
    sp.phytomer_parameters.internode.max_floral_buds_per_petiole = 0;
    arch.defineShootType("stem", sp);
    const unsigned p = arch.addPlantInstance(vec3(0.5f, 0, 0), 10.0f);
    arch.addBaseStemShoot(p, {2, {}, {0.002f, 0.03f, 1.0f, 1.0f}, 0.0f, "stem"});
    EXPECT_EQ(arch.getPlantString(p),
              "@(0.5,0,0,10)Sstem(1,0,0){"
              "I(0.03,0.002,0,0,0,0,1)[P(0.04,0.001,45,0,0)L0(0.06,10,0,0,1,0)]"
              "I(0.03,0.002,0,180,0,0,1)[P(0.04,0.001,45,0,0)L0(0.06,10,0,0,1,0)]}");
    const unsigned q = arch.generatePlantFromString(arch.getPlantString(p));
    EXPECT_EQ(arch.getPlantString(q), arch.getPlantString(p));
    // Same organs in the same places (this plant's values are exact at 4 digits).
    EXPECT_EQ(arch.getNodePosition(q, 0, 1), arch.getNodePosition(p, 0, 1) + vec3(0.0f));
    EXPECT_EQ(arch.getPlantLeafArea(q), arch.getPlantLeafArea(p));
}

TEST(PlantString, EverySpeciesAtThreeAgesRoundTripsExactly) {
    for (const std::string& name : listSpecies()) {
        const SpeciesModel model = loadSpecies(name);
        for (float age : {model.recommendedAgeMin, model.recommendedAge, model.recommendedAgeMax}) {
            SCOPED_TRACE(name + " at " + std::to_string(age) + " days");
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.loadPlantModelFromLibrary(name);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
            for (int digits : {3, 0}) {
                SCOPED_TRACE("digits " + std::to_string(digits));
                PlantStringOptions o;
                o.significantDigits = digits;
                const std::string s = arch.getPlantString(p, o);
                std::string warning;
                PlantStructureReadOptions r;
                r.onWarning = [&](const std::string& w) { warning = w; };
                const unsigned q = arch.generatePlantFromString(s, r);
                EXPECT_EQ(warning, "");
                EXPECT_EQ(firstDifference(arch.getPlantString(q, o), s), "");
                EXPECT_EQ(countVisible(arch.plant(q)), countVisible(arch.plant(p)));
                // The shape survives: leaf area and height within the rounding.
                const float tolerance = digits == 3 ? 0.01f : 0.001f;
                EXPECT_NEAR(arch.getPlantLeafArea(q), arch.getPlantLeafArea(p),
                            tolerance * arch.getPlantLeafArea(p) + 1e-9f);
                EXPECT_NEAR(arch.getPlantHeight(q), arch.getPlantHeight(p),
                            tolerance * arch.getPlantHeight(p) + 1e-4f);
                arch.deletePlantInstance(q);
            }
        }
    }
}

namespace {

// Every drawn object of a plant as bytes (organ label, vertex positions, UVs, triangles,
// colour), sorted: the plant's geometry whatever order its objects were made in.
std::vector<std::string> drawnObjects(PlantArchitecture& arch, unsigned plant) {
    const Context& ctx = arch.context();
    std::vector<std::string> out;
    for (ObjectID id : arch.getAllPlantObjectIDs(plant)) {
        const ObjectView v = ctx.object(id);
        std::string b = ctx.objectDataString(id, "organ").value_or("?");
        b.append(reinterpret_cast<const char*>(v.positions.data()), v.positions.size_bytes());
        b.append(reinterpret_cast<const char*>(v.uvs.data()), v.uvs.size_bytes());
        b.append(reinterpret_cast<const char*>(v.indices.data()), v.indices.size_bytes());
        const vec3 c = ctx.material(v.material).color;
        b.append(reinterpret_cast<const char*>(&c), sizeof c);
        out.push_back(std::move(b));
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

// A plant string written exactly (digits 0) and read back draws the same geometry to the bit
// (every object's organ, vertices, UVs, triangles and colour) and has the same height, and
// writes the same string again: every library species, at its youngest, picture and oldest
// ages, seeds 1 to 10 and 46. What the string must say for that: the nodes of internodes still
// elongating (young plants), roll references turned by trellis wires (apple_fruitingwall,
// grapevine_Wye), dead terminal buds and bare petioles left out without moving the organs next
// to them (walnut, seed 46 at 1000 days once came back 21 mm shorter), ears drawn from another
// shoot type than the stem's (maize). One test per species, so ctest runs them in parallel.
class ExactPlantString : public ::testing::TestWithParam<std::string> {};

TEST_P(ExactPlantString, GivesTheSameGeometryAtThreeAgesOverElevenSeeds) {
    const std::string& species = GetParam();
    const SpeciesModel model = loadSpecies(species);
    for (float age : {model.recommendedAgeMin, model.recommendedAge, model.recommendedAgeMax})
        for (std::uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 46}) {
            SCOPED_TRACE(species + " age " + std::to_string(age) + " seed " + std::to_string(seed));
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary(species);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
            PlantStringOptions exact;
            exact.significantDigits = 0;
            const std::string text = arch.getPlantString(p, exact);
            const unsigned q = arch.generatePlantFromString(text);
            EXPECT_EQ(firstDifference(arch.getPlantString(q, exact), text), "");
            const std::vector<std::string> a = drawnObjects(arch, p), b = drawnObjects(arch, q);
            EXPECT_EQ(a.size(), b.size());
            EXPECT_TRUE(a == b) << "the geometry differs";
            EXPECT_EQ(arch.getPlantHeight(q), arch.getPlantHeight(p));
        }
}

INSTANTIATE_TEST_SUITE_P(PlantString, ExactPlantString, ::testing::ValuesIn(listSpecies()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             return info.param;
                         });

namespace {

// The exact string of plant `p` reads back to the same geometry and height, and gives the same
// string again; returns the string.
std::string expectExactRoundTrip(PlantArchitecture& arch, unsigned p) {
    PlantStringOptions exact;
    exact.significantDigits = 0;
    const std::string text = arch.getPlantString(p, exact);
    const unsigned q = arch.generatePlantFromString(text);
    EXPECT_EQ(firstDifference(arch.getPlantString(q, exact), text), "");
    EXPECT_TRUE(drawnObjects(arch, p) == drawnObjects(arch, q)) << "the geometry differs";
    EXPECT_EQ(arch.getPlantHeight(q), arch.getPlantHeight(p));
    arch.deletePlantInstance(q);
    return text;
}

}  // namespace

// Plants that collision avoidance steered keep their shape in exact strings too: roll
// references and petioles turned clear of a wall, internode axes turned along a ceiling seen
// late, fruit and stalks turned out of the ground, petiole azimuths steered by soft avoidance.
// Each case must also write the group it is about (else it tests nothing).
TEST(PlantString, ExactStringsOfSteeredPlantsGiveTheSameGeometry) {
    using plantarch::test::addBox;
    for (std::uint64_t seed : {1, 2, 3}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        auto contains = [](const std::string& text, const char* group) {
            return text.find(group) != std::string::npos;
        };
        {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary("bean");
            const ObjectID wall = addBox(ctx, {0.1f, -1, 0}, {0.2f, 1, 1});
            arch.enableSolidObstacleAvoidance({.obstacles = {wall}, .avoidanceDistance = 0.2f});
            const std::string s =
                expectExactRoundTrip(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), 50.0f));
            EXPECT_TRUE(contains(s, ")r(") && contains(s, ")c(")) << "bean by a wall";
        }
        {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary("bean");
            const ObjectID ceiling = addBox(ctx, {-1, -1, 0.15f}, {1, 1, 0.4f});
            arch.enableSolidObstacleAvoidance(
                {.obstacles = {ceiling}, .avoidanceDistance = 0.002f});
            const std::string s =
                expectExactRoundTrip(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f));
            EXPECT_TRUE(contains(s, ")d(")) << "bean under a ceiling";
        }
        {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary("strawberry");
            // Stalks long and arched enough for ripe fruit to reach the soil.
            ShootParameters crown = arch.getCurrentShootParameters("mainstem");
            crown.phytomer_parameters.peduncle.length = 0.3f;
            crown.phytomer_parameters.peduncle.curvature = -400.0f;
            arch.updateCurrentShootParameters("mainstem", crown);
            const ObjectID ground = addBox(ctx, {-1, -1, -0.1f}, {1, 1, 0.0f});
            arch.enableSolidObstacleAvoidance(
                {.obstacles = {ground}, .avoidanceDistance = 0.1f, .fruitAdjustment = true});
            const std::string s =
                expectExactRoundTrip(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), 90.0f));
            EXPECT_TRUE(contains(s, ")c(")) << "strawberry on the ground";
        }
        {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary("tomato");
            SoftCollisionOptions soft;
            soft.steerPetioles = true;
            soft.steerPeduncles = true;
            arch.enableSoftCollisionAvoidance(soft);
            const unsigned a = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 1.0f);
            const unsigned b = arch.buildPlantInstanceFromLibrary(vec3(0.15f, 0, 0), 1.0f);
            arch.advanceTime(70.0);
            for (unsigned p : {a, b})
                EXPECT_TRUE(contains(expectExactRoundTrip(arch, p), ")a(")) << "tomatoes";
        }
    }
}

// A shoot type with unique_prototypes 0 draws every leaf in a shape of its own, chosen by the
// leaf's ID: exact strings give those IDs (the reader numbers leaves shoot by shoot, growth
// numbered them as they grew).
TEST(PlantString, ExactStringsKeepLeavesOfTheirOwnShape) {
    for (std::uint64_t seed : {1, 2, 3}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(seed);
        arch.loadPlantModelFromLibrary("bean");
        for (const std::string& label : arch.listShootTypeLabels()) {
            ShootParameters t = arch.getCurrentShootParameters(label);
            t.phytomer_parameters.leaf.prototype.unique_prototypes = 0;
            arch.updateCurrentShootParameters(label, t);
        }
        const std::string s =
            expectExactRoundTrip(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), 50.0f));
        EXPECT_NE(s.find(")i("), std::string::npos);
    }
}

TEST(PlantString, MalformedStringsGiveOneClearError) {
    const std::string good =
        "@(0,0,0,5)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,0,1,"
        "0)]}";
    EXPECT_EQ(stringError(good), "");
    EXPECT_EQ(stringError(""), "plant string, character 1: expected '@' (valid: '@')");
    EXPECT_NE(
        stringError("@(0,0,0,5)Sunifoliate(1,0,0){}").find("a shoot needs at least one internode"),
        std::string::npos);
    EXPECT_NE(
        stringError("@(0,0,0,5)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)").find("expected '}'"),
        std::string::npos);
    EXPECT_NE(stringError("@(0,0,x,5)").find("character 7 = @(0,0,x,5): expected a number"),
              std::string::npos);
    EXPECT_NE(stringError("@(0,0,0,-5)").find("negative plant age"), std::string::npos);
    EXPECT_NE(stringError("@(0,0,0,5)S(1,0,0){}").find("expected a shoot type label"),
              std::string::npos);
    EXPECT_NE(stringError(good + "x").find("text after the plant's base stem"), std::string::npos);
    EXPECT_NE(stringError("@(0,0,0,5)Sunifoliate(0,0,0){I(0.01,0.001,0,0,0,0,1)}")
                  .find("length close to 1"),
              std::string::npos);
    EXPECT_NE(stringError("@(0,0,0,5)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,"
                          "0)Fz(1,1,1,1,1)]}")
                  .find("flower stage letter"),
              std::string::npos);
    EXPECT_NE(
        stringError("@(0,0,0,5)Sunifoliate(1,0,0){I(1e9,0.001,0,0,0,0,1)}").find("out of range"),
        std::string::npos);
    // A plant's age may be as large as a plant structure file's plant_age (found by
    // fuzz_plant_xml: a file's plant of 5.6e8 days wrote a string that did not read back).
    EXPECT_EQ(stringError("@(0,0,0,2e9)"),
              "plant string, character 9 = @(0,0,0,2e9): number out of range (valid: -1e9 to 1e9)");
    // Nesting deeper than 1000 shoots is refused (appended shoots nest in their parent).
    std::string deep = "@(0,0,0,5)";
    for (int i = 0; i < 1200; ++i) deep += "Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)";
    EXPECT_NE(stringError(deep).find("shoots nested too deep"), std::string::npos);

    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f);
    EXPECT_THROW(arch.getPlantString(p, PlantStringOptions{7}), Error);
    EXPECT_THROW(arch.getPlantString(p, PlantStringOptions{-1}), Error);
}

// The tagged groups of exact strings: read into the state they give, and checked.
TEST(PlantString, AnAgeAsLargeAsAPlantFileAllowsRoundTrips) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id =
        arch.generatePlantFromString("@(0,0,0,5.5e8)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)}");
    EXPECT_EQ(arch.getPlantAge(id), 5.5e8);
    const std::string s = arch.getPlantString(id);
    const unsigned again = arch.generatePlantFromString(s);
    EXPECT_EQ(arch.getPlantString(again), s);
}

// Found by fuzz_plant_xml: a young petiole's bend rate (its curvature over its growth
// fraction; 988732 / 0.31 in the file found) passed the string's 1e6 limit on numbers.
TEST(PlantString, AYoungPetiolesLargeBendRateRoundTrips) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.generatePlantFromString(
        "@(0,0,0,5)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)[P(0.001,0.0001,40,3.2e+06,0)]}");
    const std::string s = arch.getPlantString(id);
    EXPECT_NE(s.find("3.2e+06"), std::string::npos) << s;
    EXPECT_EQ(arch.getPlantString(arch.generatePlantFromString(s)), s);
    EXPECT_NE(stringError("@(0,0,0,5)Sunifoliate(1,0,0){I(0.01,0.001,0,0,0,0,1)[P(0.001,0.0001,40,"
                          "1e39,0)]}")
                  .find("expected a number"),
              std::string::npos);
}

TEST(PlantString, ExactGroupsAreReadAndChecked) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string head = "@(0,0,0,5)Sunifoliate(1,0,0){";
    // An elongating internode: full length and fraction grown.
    const unsigned p = arch.generatePlantFromString(head + "I(0.01,0.001,0,0,0,0,1)e(0.04,0.25)}");
    const Phytomer& ph = arch.plant(p).shoots[0].phytomers[0];
    EXPECT_EQ(ph.internode.length, 0.04f);
    EXPECT_EQ(ph.internodeFraction, 0.25f);
    EXPECT_EQ(arch.getNodePosition(p, 0, 0), vec3(0.0f, 0.0f, 0.04f * 0.25f));
    PlantStringOptions exact;
    exact.significantDigits = 0;
    EXPECT_EQ(arch.getPlantString(p, exact), head + "I(0.01,0.001,0,0,0,0,1)e(0.04,0.25)}");
    EXPECT_EQ(arch.getPlantString(p), head + "I(0.01,0.001,0,0,0,0,1)}");  // 4 digits: none
    EXPECT_NE(stringError(head + "I(0.02,0.001,0,0,0,0,1)e(0.04,0.25)}")
                  .find("full length times the fraction grown"),
              std::string::npos);
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)e(0.04)}").find("expected ','"),
              std::string::npos);
    // A roll reference other than the one carried from the internode before.
    const std::string rolled = head + "I(0.01,0.001,0,0,0,0,1)I(0.01,0.001,0,0,0,0,1)r(0,1,0)}";
    const unsigned q = arch.generatePlantFromString(rolled);
    EXPECT_EQ(arch.plant(q).shoots[0].phytomers[1].internode.rollReference, vec3(0, 1, 0));
    EXPECT_EQ(arch.getPlantString(q, exact), rolled);
    const unsigned carried = arch.generatePlantFromString(
        head + "I(0.01,0.001,0,0,0,0,1)I(0.01,0.001,0,0,0,0,1)r(1,0,0)}");
    EXPECT_EQ(arch.getPlantString(carried, exact),
              head + "I(0.01,0.001,0,0,0,0,1)I(0.01,0.001,0,0,0,0,1)}");
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)r(0,1,0)}").find("first internode"),
              std::string::npos);
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)I(0.01,0.001,0,0,0,0,1)r(0,0,0)}")
                  .find("length close to 1"),
              std::string::npos);
    // An internode axis, a petiole azimuth and turns out of obstacles.
    const std::string turned = head +
                               "I(0.01,0.001,0,0,0,0,1)d(0,0.6,0.8)[P(0.02,0.001,40,0,0)a(90)c(0,"
                               "0,1,30)L0(0.05,0,0,0,1,0)Ff(0.01,0.001,0,0,0)c(1,0,0,-20)f(1,0,0,"
                               "0,0.01,0,0)c(0,1,0,45)]}";
    const unsigned t = arch.generatePlantFromString(turned);
    const Phytomer& tp = arch.plant(t).shoots[0].phytomers[0];
    EXPECT_EQ(tp.internode.direction, vec3(0.0f, 0.6f, 0.8f));
    EXPECT_EQ(tp.petioles[0].azimuth, 90.0f);
    EXPECT_EQ(tp.petioles[0].clearance, (OrganTurn{vec3(0, 0, 1), 30.0f}));
    EXPECT_EQ(tp.petioles[0].floralBuds.at(0).peduncleClearance,
              (OrganTurn{vec3(1, 0, 0), -20.0f}));
    EXPECT_EQ(tp.petioles[0].floralBuds[0].flowers.at(0).clearance,
              (OrganTurn{vec3(0, 1, 0), 45.0f}));
    EXPECT_EQ(arch.getPlantString(t, exact), turned);
    // Values the reader derives anyway are not written again; other digits write no groups.
    const unsigned plain = arch.generatePlantFromString(
        head + "I(0.01,0.001,0,0,0,0,1)d(0,0,1)[P(0.02,0.001,40,0,0)a(0)c(0,0,1,0)]}");
    EXPECT_EQ(arch.getPlantString(plain, exact),
              head + "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)]}");
    EXPECT_EQ(arch.getPlantString(t), head +
                                          "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,"
                                          "0,1,0)Ff(0.01,0.001,0,0,0)f(1,0,0,0,0.01,0,0)]}");
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)c(0,0,0,30)]}")
                  .find("length close to 1"),
              std::string::npos);
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)c(0,0,1)]}")
                  .find("expected ','"),
              std::string::npos);
    // Leaf IDs: given ones kept, the others numbered above them; each ID once.
    const unsigned ids = arch.generatePlantFromString(
        head +
        "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,0,1,0)i(7)L0(0.05,0,0,0,"
        "1,0)]}");
    const Petiole& idPetiole = arch.plant(ids).shoots[0].phytomers[0].petioles[0];
    EXPECT_EQ(idPetiole.leaves[0].leafID, 7);
    EXPECT_EQ(idPetiole.leaves[1].leafID, 8);
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,0,1,0)i("
                                 "7)L0(0.05,0,0,0,1,0)i(7)]}")
                  .find("a leaf ID given twice"),
              std::string::npos);
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,0,1,0)i("
                                 "-1)]}")
                  .find("expected a leaf ID"),
              std::string::npos);
    // Out of the grammar's order: a roll reference after the axis.
    EXPECT_NE(stringError(head + "I(0.01,0.001,0,0,0,0,1)I(0.01,0.001,0,0,0,0,1)d(0,0,1)r(0,1,0)}")
                  .find("expected '}'"),
              std::string::npos);
}

TEST(PlantString, UnknownShootTypeUsesDefaultParametersWithAWarning) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    std::string warning;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warning = w; };
    const unsigned p = arch.generatePlantFromString(
        "@(0,0,0,5)Sother(1,0,0){I(0.01,0.001,0,0,0,0,1)[P(0.02,0.001,40,0,0)L0(0.05,0,0,0,1,0)]}",
        o);
    EXPECT_EQ(warning, "plant string: shoot type other: plantarch's default parameters");
    EXPECT_EQ(arch.getPlantObjectIDs(p, OrganKind::Leaf).size(), 1u);
}

// Fuzz finding: a phytomer built by another shoot type than its shoot's (possible in a file)
// kept its type in the string; before, the string named only the shoot's type and the
// phytomer's leaf variants could be out of range for it.
TEST(PlantString, PhytomerOfAnotherShootTypeKeepsItsType) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters plain, varied;
    varied.phytomer_parameters.leaf.prototype.unique_prototypes = 4;
    varied.phytomer_parameters.leaf.prototype.shape = LeafShape::Cordate;
    arch.defineShootType("plain", plain);
    arch.defineShootType("varied", varied);
    const unsigned p = arch.addPlantInstance(vec3(0.0f), 1.0f);
    arch.addBaseStemShoot(p, {2, {}, {0.002f, 0.03f, 1.0f, 1.0f}, 0.0f, "plain"});
    std::string xml = arch.getPlantStructureXML({p});
    const std::string from = "<parameters_label>plain</parameters_label>";
    xml.replace(xml.rfind(from), from.size(), "<parameters_label>varied</parameters_label>");
    const std::string variant = "<variant>0</variant>";
    xml.replace(xml.rfind(variant), variant.size(), "<variant>3</variant>");
    const unsigned q = arch.readPlantStructureXMLString(xml).at(0);
    const std::string s = arch.getPlantString(q);
    EXPECT_NE(s.find("Ivaried("), std::string::npos) << s;
    const unsigned r = arch.generatePlantFromString(s);
    EXPECT_EQ(arch.getPlantString(r), s);
    EXPECT_EQ(arch.plant(r).shoots[0].phytomers[1].parametersLabel, "varied");
    EXPECT_EQ(arch.getPlantLeafArea(r), arch.getPlantLeafArea(q));
}
