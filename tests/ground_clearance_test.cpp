// Ground clearance (docs/growth.md): no leaf, flower or fruit of a plant goes below its ground
// level, the z of its base.

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "plant_geometry_bytes.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::organBytes;

namespace {

constexpr float kInf = std::numeric_limits<float>::max();

// The lowest vertex of the plant's organs of these kinds, m (kInf when it has none).
float lowest(const PlantArchitecture& arch, const Context& ctx, unsigned plant,
             std::initializer_list<OrganKind> kinds) {
    float z = kInf;
    for (OrganKind kind : kinds)
        for (ObjectID id : arch.getPlantObjectIDs(plant, kind))
            for (const vec3& q : ctx.object(id).positions) z = std::min(z, q.z);
    return z;
}

constexpr std::initializer_list<OrganKind> kSideOrgans = {OrganKind::Leaf, OrganKind::FlowerClosed,
                                                          OrganKind::FlowerOpen, OrganKind::Fruit};

}  // namespace

// Every library species at its default age and at a third, two thirds and one and a half
// times it (where the species lives that long), seeds 1 to 3: no leaf, flower or fruit vertex
// more than 1 mm below the plant's base.
TEST(GroundClearance, EveryLibraryPlantKeepsItsLeavesFlowersAndFruitAboveTheGround) {
    std::string table = "\nspecies              age seed  side organs  petioles  internodes (mm)";
    std::size_t below = 0;
    std::vector<std::pair<std::string, float>> plants;
    for (const std::string& name : listSpecies()) {
        const SpeciesModel model = loadSpecies(name);
        for (float f : {1.0f / 3.0f, 2.0f / 3.0f, 1.0f, 1.5f}) {
            const float age = std::round(model.recommendedAge * f);
            if (age <= model.phenology.max_age) plants.emplace_back(name, age);
        }
    }
    for (const auto& [name, age] : plants) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            SCOPED_TRACE(name + " at " + std::to_string(int(age)) + " days, seed " +
                         std::to_string(seed));
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary(name);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
            const float side = lowest(arch, ctx, p, kSideOrgans);
            const float petioles = lowest(arch, ctx, p, {OrganKind::Petiole, OrganKind::Peduncle});
            const float stems = lowest(arch, ctx, p, {OrganKind::Internode});
            char row[160];
            std::snprintf(row, sizeof row, "\n%-18s %6.0f %4d %11.1f %9.1f %11.1f", name.c_str(),
                          double(age), int(seed), double(side) * 1e3, double(petioles) * 1e3,
                          double(stems) * 1e3);
            table += row;
            EXPECT_GE(side, -1e-3f);
            below += side < -1e-3f ? 1 : 0;
        }
    }
    std::printf("%s\n%zu plants with a side organ below the ground\n", table.c_str(), below);
}

namespace {

struct Grown {
    std::unique_ptr<Context> ctx = std::make_unique<Context>();
    std::unique_ptr<PlantArchitecture> arch = std::make_unique<PlantArchitecture>(ctx.get());
    unsigned plant = 0;
};

// A cowpea of seed 1 at `base`, grown to 50 days in steps of `steps` (one call when empty).
Grown cowpea(vec3 base = vec3(0.0f), const std::vector<double>& steps = {}, bool ground = true) {
    Grown g;
    g.arch->setSeed(1);
    g.arch->setGroundClearance(ground);
    g.arch->loadPlantModelFromLibrary("cowpea");
    g.plant = g.arch->buildPlantInstanceFromLibrary(base, steps.empty() ? 50.0f : 0.0f);
    for (double d : steps) g.arch->advanceTime(g.plant, d);
    return g;
}

float lowestSide(const Grown& g) {
    return lowest(*g.arch, *g.ctx, g.plant, kSideOrgans);
}

std::size_t turns(const PlantInstance& p) {
    std::size_t n = 0;
    auto floral = [&](const FloralBud& fb) {
        n += fb.peduncleClearance.angle != 0.0f ? 1 : 0;
        for (const FlowerOrgan& fl : fb.flowers) n += fl.clearance.angle != 0.0f ? 1 : 0;
    };
    for (const Shoot& s : p.shoots) {
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles) {
                n += pt.clearance.angle != 0.0f ? 1 : 0;
                for (const FloralBud& fb : pt.floralBuds) floral(fb);
            }
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
    }
    return n;
}

}  // namespace

// On by default; off, the cowpea's leaves reach 5.8 cm below its base. Only organs that would
// go below are turned: a plant whose organs all stay above is the same to the byte either way.
TEST(GroundClearance, OnByDefaultAndOffOnRequest) {
    {
        Context ctx;
        PlantArchitecture arch(&ctx);
        EXPECT_TRUE(arch.getGroundClearance());
    }
    const Grown on = cowpea(), off = cowpea(vec3(0.0f), {}, false);
    EXPECT_TRUE(on.arch->getGroundClearance(on.plant));
    EXPECT_FALSE(off.arch->getGroundClearance(off.plant));
    EXPECT_GE(lowestSide(on), -1e-3f);
    EXPECT_LT(lowestSide(off), -0.05f);
    EXPECT_GT(turns(on.arch->plant(on.plant)), 0u);
    EXPECT_EQ(turns(off.arch->plant(off.plant)), 0u);

    std::string first;
    for (bool ground : {true, false}) {  // tomato's lowest leaf is 3 cm above the ground
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(3);
        arch.setGroundClearance(ground);
        arch.loadPlantModelFromLibrary("tomato");
        const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 50.0f);
        EXPECT_GT(lowest(arch, ctx, p, kSideOrgans), 0.02f);
        EXPECT_EQ(turns(arch.plant(p)), 0u);
        if (ground)
            first = organBytes(arch, {p});
        else
            EXPECT_EQ(organBytes(arch, {p}), first);
    }
}

// Setting it on a grown plant turns its organs (and redraws it) at once; setting it back gives
// the plant it was, to the byte.
TEST(GroundClearance, SettingItRedoesTheTurnsNow) {
    Grown g = cowpea();
    const std::string before = organBytes(*g.arch, {g.plant});
    g.arch->setGroundClearance(g.plant, false);
    EXPECT_FALSE(g.arch->getGroundClearance(g.plant));
    EXPECT_TRUE(g.arch->getGroundClearance());  // the default for new plants is unchanged
    EXPECT_LT(lowestSide(g), -0.05f);
    EXPECT_EQ(organBytes(*g.arch, {g.plant}), organBytes(*cowpea(vec3(0.0f), {}, false).arch, {0}));
    g.arch->setGroundClearance(true);  // every plant, and the default
    EXPECT_TRUE(g.arch->getGroundClearance(g.plant));
    EXPECT_EQ(organBytes(*g.arch, {g.plant}), before);
}

// The turns follow the plant's shape, not the step size: 50 days at once, in 50 daily steps
// and in uneven steps give the same geometry and state.
TEST(GroundClearance, StepSizeChangesNothing) {
    const Grown once = cowpea();
    ASSERT_GT(turns(once.arch->plant(once.plant)), 0u);
    const std::string bytes = organBytes(*once.arch, {once.plant});
    const std::string state = once.arch->getPlantString(once.plant, {.significantDigits = 0});
    for (const std::vector<double>& steps :
         {std::vector<double>(50, 1.0), std::vector<double>{7.0, 13.5, 0.25, 29.25},
          std::vector<double>(200, 0.25)}) {
        SCOPED_TRACE(std::to_string(steps.size()) + " steps");
        const Grown split = cowpea(vec3(0.0f), steps);
        EXPECT_EQ(organBytes(*split.arch, {split.plant}), bytes);
        EXPECT_EQ(split.arch->getPlantString(split.plant, {.significantDigits = 0}), state);
    }
}

// Each plant keeps its organs above its own base: plants at different heights in one scene,
// and a canopy on raised ground. A plant raised by h is the plant at 0 raised by h.
TEST(GroundClearance, EachPlantUsesItsOwnBase) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(1);
    arch.loadPlantModelFromLibrary("cowpea");
    const std::vector<float> heights = {0.3f, -0.2f, 0.0f, 1.5f};
    std::vector<unsigned> plants;
    for (float z : heights) plants.push_back(arch.buildPlantInstanceFromLibrary({0, 0, z}, 50.0f));
    for (std::size_t i = 0; i < plants.size(); ++i)
        EXPECT_GE(lowest(arch, ctx, plants[i], kSideOrgans), heights[i] - 1e-3f) << heights[i];

    const Grown flat = cowpea(), raised = cowpea({0.0f, 0.0f, 0.25f});
    const float shift = lowestSide(raised) - lowestSide(flat);
    EXPECT_NEAR(shift, 0.25f, 1e-5f);
    EXPECT_EQ(turns(raised.arch->plant(raised.plant)), turns(flat.arch->plant(flat.plant)));

    for (bool ground : {true, false}) {
        Context c;
        PlantArchitecture canopy(&c);
        canopy.setSeed(2);
        canopy.setGroundClearance(ground);
        canopy.loadPlantModelFromLibrary("cowpea");
        float worst = 1e30f;
        for (unsigned p :
             canopy.buildPlantCanopyFromLibrary({0, 0, 0.4f}, {0.5f, 0.5f}, {3, 2}, 50))
            worst = std::min(worst, lowest(canopy, c, p, kSideOrgans) - 0.4f);
        if (ground)
            EXPECT_GE(worst, -1e-3f);
        else
            EXPECT_LT(worst, -0.02f);  // not vacuous: without it the canopy's leaves go below
    }
}

// The same canopy, to the byte, on one thread and on several.
TEST(GroundClearance, CanopyIsTheSameForAnyThreadCount) {
    auto build = [](int threads) {
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(5);
        arch.loadPlantModelFromLibrary("cowpea");
        const std::vector<unsigned> plants =
            arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.4f, 0.4f}, {3, 2}, 50);
        omp_set_num_threads(saved);
        std::size_t turned = 0;
        for (unsigned p : plants) turned += turns(arch.plant(p));
        EXPECT_GT(turned, 0u);
        return organBytes(arch, plants);
    };
    const std::string one = build(1);
    EXPECT_EQ(build(2), one);
    EXPECT_EQ(build(4), one);
}

// The setting and the turns are plant state: written to plant structure files and read back,
// the plant is the same now and after more growth; a file without the setting (written before
// it existed) reads as on.
TEST(GroundClearance, PlantFilesKeepTheSettingAndTheTurns) {
    for (bool ground : {true, false}) {
        SCOPED_TRACE(ground ? "on" : "off");
        Grown g = cowpea(vec3(0.0f), {30.0}, ground);
        const std::string xml = g.arch->getPlantStructureXML({g.plant});
        EXPECT_NE(xml.find(ground ? "<ground_clearance>true</ground_clearance>"
                                  : "<ground_clearance>false</ground_clearance>"),
                  std::string::npos);
        Context ctx;
        PlantArchitecture read(&ctx);  // its default stays on
        const unsigned q = read.readPlantStructureXMLString(xml).at(0);
        EXPECT_EQ(read.getGroundClearance(q), ground);
        EXPECT_EQ(organBytes(read, {q}), organBytes(*g.arch, {g.plant}));
        g.arch->advanceTime(20.0);
        read.advanceTime(20.0);
        EXPECT_EQ(read.getPlantStructureXML({q}), g.arch->getPlantStructureXML({g.plant}));
        EXPECT_EQ(ground, lowestSide(g) >= -1e-3f);
    }
    Grown g = cowpea(vec3(0.0f), {}, false);
    std::string xml = g.arch->getPlantStructureXML({g.plant});
    const std::string element = "<ground_clearance>false</ground_clearance>";
    const auto at = xml.find(element);
    ASSERT_NE(at, std::string::npos);
    xml.erase(at, element.size());
    Context ctx;
    PlantArchitecture read(&ctx);
    std::vector<std::string> warnings;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warnings.push_back(w); };
    const unsigned q = read.readPlantStructureXMLString(xml, o).at(0);
    EXPECT_TRUE(read.getGroundClearance(q));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("ground_clearance"), std::string::npos) << warnings[0];
    // Read as it was written (the turns are the file's); the next growth step turns its leaves.
    EXPECT_LT(lowest(read, ctx, q, kSideOrgans), -0.05f);
    read.advanceTime(0.0);
    EXPECT_GE(lowest(read, ctx, q, kSideOrgans), -1e-3f);
    // Absent, the setting is the reading PlantArchitecture's (as for plant strings).
    Context other;
    PlantArchitecture off(&other);
    off.setGroundClearance(false);
    EXPECT_FALSE(off.getGroundClearance(off.readPlantStructureXMLString(xml, o).at(0)));
    off.loadPlantModelFromLibrary("cowpea");
    EXPECT_FALSE(off.getGroundClearance(off.generatePlantFromString(g.arch->getPlantString(0))));
}

// Stems are not turned, and a stem that meets the ground lies on it: no node of a library plant
// is below its base, and a runner's axis rests one radius above the ground.
TEST(GroundClearance, StemsLieOnTheGroundNotUnderIt) {
    for (const char* species : {"puncturevine", "bindweed"})
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            SCOPED_TRACE(std::string(species) + " seed " + std::to_string(seed));
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary(species);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 45.0f);
            float node = 1e30f;
            for (const Shoot& s : arch.plant(p).shoots)
                for (unsigned k = 0; k < s.phytomers.size(); ++k)
                    node = std::min(node, arch.getNodePosition(p, s.id, k).z);
            EXPECT_GE(node, -1e-5f);
            EXPECT_GE(lowest(arch, ctx, p, {OrganKind::Internode}), -2e-3f);  // tube radii
        }
}

// --no-ground-clearance on build, canopy and grow; the setting travels in plant files.
TEST(GroundClearance, CommandLineFlag) {
    const std::string dir = ::testing::TempDir() + "plantarch_ground_clearance";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    auto lowestIn = [](const std::string& xml) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        const unsigned p = arch.readPlantStructureXML(xml).at(0);
        return std::pair{arch.getGroundClearance(p), lowest(arch, ctx, p, kSideOrgans)};
    };
    ASSERT_EQ(cli::run("build cowpea --age 50 --seed 1 -o " + dir + "/on.xml").status, 0);
    ASSERT_EQ(
        cli::run("build cowpea --age 50 --seed 1 --no-ground-clearance -o " + dir + "/off.xml")
            .status,
        0);
    ASSERT_EQ(cli::run("canopy cowpea --count 1x1 --age 50 --seed 1 --no-ground-clearance -o " +
                       dir + "/canopy.xml")
                  .status,
              0);
    ASSERT_EQ(
        cli::run("grow " + dir + "/on.xml --days 0 --no-ground-clearance -o " + dir + "/grown.xml")
            .status,
        0);
    const auto on = lowestIn(dir + "/on.xml"), off = lowestIn(dir + "/off.xml");
    EXPECT_TRUE(on.first);
    EXPECT_GE(on.second, -1e-3f);
    EXPECT_FALSE(off.first);
    EXPECT_LT(off.second, -0.05f);
    EXPECT_FALSE(lowestIn(dir + "/canopy.xml").first);
    EXPECT_LT(lowestIn(dir + "/canopy.xml").second, -0.02f);
    EXPECT_FALSE(lowestIn(dir + "/grown.xml").first);
    EXPECT_LT(lowestIn(dir + "/grown.xml").second, -0.05f);
    std::filesystem::remove_all(dir);
}
