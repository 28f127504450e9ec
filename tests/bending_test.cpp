// Shoots bending under load (plantarch/Bending.h, docs/measured-plants.md): the rod chain
// against the analytic cantilever, small and large deflection, loads from fruit, stiffness,
// determinism, the plant file round trip, pulls and hostile inputs.

#include "plantarch/Bending.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "error_of.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

constexpr double kG = 9.80665;

// A straight horizontal shoot along +x from the origin: `n` internodes of `length` / n, radius
// `radius`, no leaves, with these mechanics.
struct Cantilever {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant = 0;
    double L, r;
    MechanicsParameters m;

    Cantilever(unsigned n, double length, double radius, MechanicsParameters mech)
        : L(length), r(radius), m(mech) {
        ShootParameters sp;
        sp.phytomer_parameters.internode.pitch = 0.0f;
        sp.phytomer_parameters.internode.phyllotactic_angle = 0.0f;
        arch.defineShootType("stem", sp);
        arch.setGroundClearance(false);  // a shoot along the ground stays straight
        plant = arch.addPlantInstance({0, 0, 0}, 0.0f);
        ShootSpec spec;
        spec.phytomers = n;
        spec.baseRotation.pitch = 90.0f;
        spec.size.internodeRadius = float(radius);
        spec.size.internodeLengthMax = float(length / n);
        spec.shootType = "stem";
        arch.addBaseStemShoot(plant, spec);
        arch.removeShootLeaves(plant, 0);
        PhenologyParameters ph = arch.plant(plant).phenology;
        ph.mechanics = mech;
        arch.setPlantPhenologicalThresholds(plant, ph);
    }
    unsigned tip() const { return unsigned(arch.plant(plant).shoots[0].phytomers.size()) - 1; }
    double EI() const { return m.elastic_modulus * std::numbers::pi / 4.0 * std::pow(r, 4); }
    vec3 tipPosition() const { return bentNodePositions(arch, plant, 0).back(); }
};

MechanicsParameters mechanics(double E, double stemDensity) {
    MechanicsParameters m;
    m.enabled = true;
    m.elastic_modulus = float(E);
    m.stem_density = float(stemDensity);
    m.leaf_mass_per_area = 0.0f;
    m.fruit_density = 0.0f;
    return m;
}

}  // namespace

TEST(Bending, StraightShootStartsHorizontal) {
    Cantilever c(40, 1.0, 0.01, mechanics(1e10, 0.0));
    const vec3 tip = c.tipPosition();
    EXPECT_NEAR(tip.x, 1.0f, 1e-5f);
    EXPECT_NEAR(tip.y, 0.0f, 1e-5f);
    EXPECT_NEAR(tip.z, 0.0f, 1e-5f);
}

// Uniform load (its own weight): tip deflection w L^4 / (8 E I), within 1%.
TEST(Bending, SmallDeflectionUniformLoad) {
    Cantilever c(50, 1.0, 0.01, mechanics(1e10, 1000.0));
    bendPlant(c.arch, c.plant);
    const double w = 1000.0 * kG * std::numbers::pi * c.r * c.r;  // N/m
    const double expected = w * std::pow(c.L, 4) / (8.0 * c.EI());
    const vec3 tip = c.tipPosition();
    EXPECT_NEAR(-tip.z, expected, 0.01 * expected) << "tip drop " << -tip.z;
    EXPECT_NEAR(tip.y, 0.0f, 1e-6f);
}

// Tip load (a pull at the last node of a weightless shoot): P L^3 / (3 E I), within 1%.
TEST(Bending, SmallDeflectionTipLoad) {
    Cantilever c(50, 1.0, 0.01, mechanics(1e10, 0.0));
    const double P = 0.01 * 3.0 * c.EI() / std::pow(c.L, 3);  // a drop of 1% of L
    const PullResult r = pullNode(c.arch, c.plant, 0, c.tip(), {0.0f, 0.0f, -float(P)});
    const double expected = P * std::pow(c.L, 3) / (3.0 * c.EI());
    EXPECT_NEAR(-r.displacement.z, expected, 0.01 * expected);
    EXPECT_NEAR(-c.tipPosition().z, expected, 0.01 * expected);
    // The reactions: the ground holds the pull and its moment P L about the base.
    EXPECT_NEAR(r.baseForce.z, P, 1e-6 * P);
    EXPECT_NEAR(r.groundForce.z, P, 1e-6 * P);
    EXPECT_NEAR(std::abs(r.baseMoment.y), P * (c.L - expected * expected / c.L), 0.01 * P);
    EXPECT_EQ(r.nodeReaction, -r.force);
}

// Large deflection under a tip load against the elastica of Bisshopp and Drucker (K. E.
// Bisshopp, D. C. Drucker, "Large deflection of cantilever beams", Quarterly of Applied
// Mathematics 3 (1945) 272-275), whose table gives, for alpha = P L^2 / (E I):
//   alpha = 1: deflection across the beam 0.3017 L, tip at 0.9436 L along it;
//   alpha = 3: 0.6033 L and 0.7456 L;  alpha = 10: 0.8106 L and 0.4450 L.
// (Recomputed by shooting on E I theta'' = -P cos theta: 0.30172, 0.94357; 0.60325, 0.74558;
// 0.81061, 0.44500.) Within 2%.
TEST(Bending, LargeDeflectionMatchesElastica) {
    struct Row {
        double alpha, across, along;
    };
    for (const Row& row :
         {Row{1.0, 0.3017, 0.9436}, Row{3.0, 0.6033, 0.7456}, Row{10.0, 0.8106, 0.4450}}) {
        Cantilever c(100, 1.0, 0.01, mechanics(1e10, 0.0));
        const double P = row.alpha * c.EI() / (c.L * c.L);
        const PullResult r = pullNode(c.arch, c.plant, 0, c.tip(), {0.0f, 0.0f, -float(P)});
        EXPECT_NEAR(-r.position.z / c.L, row.across, 0.02 * row.across) << "alpha " << row.alpha;
        EXPECT_NEAR(r.position.x / c.L, row.along, 0.02 * row.along) << "alpha " << row.alpha;
    }
}

// A prescribed displacement moves the node by it, with the force of the straight cantilever's
// stiffness 3 E I / L^3 (small displacement), within 1%.
TEST(Bending, DisplacedNodeTakesTheCantileverStiffness) {
    Cantilever c(50, 1.0, 0.01, mechanics(1e10, 0.0));
    const vec3 d{0.0f, 0.002f, 0.0f};  // sideways
    const PullResult r = displaceNode(c.arch, c.plant, 0, c.tip(), d);
    EXPECT_NEAR(r.displacement.y, d.y, 1e-6f);
    EXPECT_NEAR(c.tipPosition().y, d.y, 1e-6f);
    const double k = 3.0 * c.EI() / std::pow(c.L, 3);
    EXPECT_NEAR(r.force.y, k * d.y, 0.01 * k * d.y);
    EXPECT_NEAR(r.nodeReaction.y, -k * d.y, 0.01 * k * d.y);
    EXPECT_NEAR(r.baseForce.y, -r.force.y, 1e-6 * k);
    // Across the shoot only: along it the node goes where bending takes it (here slightly
    // back, the arc's shortening).
    EXPECT_LT(r.displacement.x, 0.0f);
    EXPECT_GT(r.displacement.x, -1e-5f);
    // Farther than the shoot reaches.
    const Error e = errorOf([&] { displaceNode(c.arch, c.plant, 0, c.tip(), {0, 0, -3.0f}); });
    EXPECT_EQ(e.parameter(), "displacement");
}

// A library plant in fruit: fruit weigh its shoots down further; stiffer wood bends less.
TEST(Bending, FruitDroopAndStiffness) {
    auto droop = [](float fruitDensity, float modulus) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("tomato");
        const unsigned id = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 80.0f);
        PhenologyParameters ph = arch.plant(id).phenology;
        ph.mechanics.enabled = false;
        ph.mechanics.elastic_modulus = modulus;
        ph.mechanics.fruit_density = fruitDensity;
        arch.setPlantPhenologicalThresholds(id, ph);
        std::vector<std::vector<vec3>> rest;  // every shoot's nodes before bending
        for (const Shoot& s : arch.plant(id).shoots)
            rest.push_back(bentNodePositions(arch, id, s.id));
        bendPlant(arch, id);
        // How far every node dropped below its rest place, summed.
        double drop = 0.0;
        const PlantInstance& p = arch.plant(id);
        for (const Shoot& s : p.shoots) {
            if (s.removed || s.phytomers.empty()) continue;
            const std::vector<vec3> bent = bentNodePositions(arch, id, s.id);
            for (std::size_t k = 1; k < bent.size(); ++k) {
                EXPECT_EQ(arch.getNodePosition(id, s.id, unsigned(k - 1)), bent[k]);
                drop += rest[s.id][k].z - bent[k].z;
            }
        }
        return drop;
    };
    const double withFruit = droop(1000.0f, 2e8f);
    const double noFruit = droop(0.0f, 2e8f);
    const double stiffer = droop(1000.0f, 2e9f);
    EXPECT_GT(noFruit, 0.0);
    EXPECT_GT(withFruit, 1.01 * noFruit);
    EXPECT_LT(stiffer, 0.5 * withFruit);
}

namespace {

// A small canopy grown with its shoots bending after every step, on `threads` threads: the
// plant file and every drawn vertex.
struct Canopy {
    std::string xml, vertices;
    bool operator==(const Canopy&) const = default;
};

Canopy bentCanopy(int threads, std::optional<bool> enabled) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    PhenologyParameters ph = arch.plant(arch.addPlantInstance({9, 9, 0}, 0)).phenology;
    arch.deletePlantInstance(arch.getAllPlantIDs().back());
    if (enabled) {  // else the species' mechanics, at their defaults (off)
        ph.mechanics.enabled = *enabled;
        ph.mechanics.elastic_modulus = 3e8f;
    }
    arch.setDefaultPhenology(ph);
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {2, 1}, 15.0f);
    arch.advanceTime(3.0f);
    omp_set_num_threads(before);
    Canopy out{arch.getPlantStructureXML(ids), {}};
    ctx.forEachObject([&](const ObjectView& v) {
        out.vertices.append(reinterpret_cast<const char*>(v.positions.data()),
                            v.positions.size() * sizeof(vec3));
    });
    return out;
}

}  // namespace

TEST(Bending, SameBytesOnAnyThreadCount) {
    const Canopy one = bentCanopy(1, true);
    EXPECT_NE(one.xml.find("<bend>"), std::string::npos);
    EXPECT_TRUE(one == bentCanopy(4, true));
}

TEST(Bending, DisabledLeavesThePlantUnchanged) {
    const Canopy off = bentCanopy(2, false);
    EXPECT_EQ(off.xml.find("<bend>"), std::string::npos);
    // The same as with the phenology the species gives (mechanics at their defaults: off).
    // (The library's plants, checked byte for byte by SpeciesChecksum, are the same too.)
    // (Its plant file differs only in the mechanics parameters it holds.)
    EXPECT_TRUE(off.vertices == bentCanopy(2, std::nullopt).vertices);
}

TEST(Bending, PlantFileKeepsTheBentShape) {
    Cantilever c(20, 1.0, 0.005, mechanics(1e9, 1000.0));
    bendPlant(c.arch, c.plant);
    const vec3 tip = c.tipPosition();
    ASSERT_LT(tip.z, -0.01f);
    const std::string xml = c.arch.getPlantStructureXML({c.plant});
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    arch2.defineShootType("stem", ShootParameters{});
    const std::vector<unsigned> ids = arch2.readPlantStructureXMLString(xml);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_EQ(bentNodePositions(arch2, ids[0], 0), bentNodePositions(c.arch, c.plant, 0));
    EXPECT_EQ(arch2.getPlantStructureXML(ids), xml);
    // Straightened, it is back at rest.
    straightenPlant(arch2, ids[0]);
    EXPECT_NEAR(bentNodePositions(arch2, ids[0], 0).back().z, 0.0f, 1e-5f);
}

TEST(Bending, HostileInputsAreOneLineErrors) {
    Cantilever c(10, 1.0, 0.01, mechanics(1e10, 0.0));
    const float nan = std::nanf("");
    const Error e1 = errorOf([&] { pullNode(c.arch, c.plant, 0, 3, {nan, 0, 0}); });
    EXPECT_EQ(e1.parameter(), "force");
    const Error e2 = errorOf([&] { pullNode(c.arch, c.plant, 0, 10, {0, 0, -1}); });
    EXPECT_EQ(e2.parameter(), "node");
    EXPECT_EQ(e2.validRange(), "0 to 9");
    const Error e3 = errorOf([&] { pullNode(c.arch, c.plant, 4, 0, {0, 0, -1}); });
    EXPECT_EQ(e3.parameter(), "shoot");
    EXPECT_EQ(e3.validRange(), "a shoot ID of the plant, 0 to 0 (not pruned)");
    const Error e4 = errorOf([&] { pullNode(c.arch, c.plant, 0, 3, {0, 0, 1e30f}); });
    EXPECT_EQ(e4.parameter(), "force");
    const Error e5 = errorOf([&] { displaceNode(c.arch, c.plant, 0, 3, {0, 0, INFINITY}); });
    EXPECT_EQ(e5.parameter(), "displacement");
    errorOf([&] { pullNode(c.arch, 99, 0, 0, {0, 0, -1}); });
    PhenologyParameters ph = c.arch.plant(c.plant).phenology;
    ph.mechanics.elastic_modulus = -1.0f;
    const Error e6 = errorOf([&] { c.arch.setPlantPhenologicalThresholds(c.plant, ph); });
    EXPECT_NE(e6.parameter().find("mechanics.elastic_modulus"), std::string::npos);
    for (const Error& e : {e1, e2, e3, e4, e5, e6})
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    // Nothing changed: the shoot is still straight.
    EXPECT_NEAR(c.tipPosition().z, 0.0f, 1e-6f);
}
