// Leaf angle distributions (docs/measured-plants.md, "Leaf angle distributions"): species files
// declare them, leaves draw their poses from them, plant files keep the poses, the histogram
// queries measure them, and the light model sees the extinction coefficient they imply.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "error_of.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/Light.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

constexpr double kPi = std::numbers::pi;
const std::vector<std::uint32_t> kSquare{0, 1, 2, 0, 2, 3};

// A herb with flat leaves (no fold, curl or wave: every triangle of a leaf has its mean
// normal), 30 on one stem at 40 days, with the leaf angles put at @ANGLES@.
const std::string kSpecies = R"(<?xml version="1.0" encoding="UTF-8"?>
<plantarch_species format="1">
  <name>flat_herb</name>
  <phenology>
    <max_age>1000</max_age>
    <leaf_angles>@ANGLES@
    </leaf_angles>
  </phenology>
  <shoot_type label="main">
    <max_nodes>30</max_nodes>
    <phyllochron_min>1</phyllochron_min>
    <elongation_rate_max>0.5</elongation_rate_max>
    <internode_length_max>0.03</internode_length_max>
    <vegetative_bud_break_probability_max>0</vegetative_bud_break_probability_max>
    <phytomer>
      <petiole>
        <pitch>50</pitch>
        <length>0.04</length>
      </petiole>
      <leaf>
        <prototype_scale>0.05</prototype_scale>
        <prototype>
          <shape>elliptic</shape>
          <leaf_aspect_ratio>0.5</leaf_aspect_ratio>
        </prototype>
      </leaf>
    </phytomer>
  </shoot_type>
  <build>
    <base_stem id="stem" type="main" nodes="1"/>
  </build>
</plantarch_species>
)";

std::string speciesWith(const std::string& angles) {
    std::string s = kSpecies;
    s.replace(s.find("@ANGLES@"), 8, angles);
    return s;
}

// A canopy of `n` x `n` plants of the species with these leaf angles, grown 40 days.
std::vector<unsigned> canopy(PlantArchitecture& arch, const std::string& angles, int n = 10) {
    arch.setSeed(2026);
    arch.loadPlantModel(readSpeciesString(speciesWith(angles), "flat_herb.xml"));
    CanopyOptions o;
    o.count = glm::ivec2(n);
    o.spacing = vec2(0.5f);
    return arch.buildPlantCanopyFromLibrary(o, 40.0f);
}

// Each leaf's area (one side): the weights of the histogram's sample.
std::vector<double> leafAreas(const PlantArchitecture& arch, const std::vector<unsigned>& plants) {
    std::vector<double> out;
    for (unsigned p : plants)
        for (ObjectID id : arch.getPlantObjectIDs(p, OrganKind::Leaf))
            out.push_back(arch.context().objectArea(id));
    return out;
}

// Kish's effective sample size of weighted draws: (sum w)^2 / sum w^2.
double effectiveSize(const std::vector<double>& w) {
    double s = 0.0, s2 = 0.0;
    for (double v : w) {
        s += v;
        s2 += v * v;
    }
    return s2 > 0.0 ? s * s / s2 : 0.0;
}

struct Family {
    const char* name;
    std::string xml;
};

const std::vector<Family> kFamilies = {
    {"planophile", "<inclination>planophile</inclination>"},
    {"erectophile", "<inclination>erectophile</inclination>"},
    {"plagiophile", "<inclination>plagiophile</inclination>"},
    {"extremophile", "<inclination>extremophile</inclination>"},
    {"spherical", "<inclination>spherical</inclination>"},
    {"uniform", "<inclination>uniform</inclination>"},
    {"ellipsoidal x 3", "<inclination>ellipsoidal</inclination><ellipsoidal_x>3</ellipsoidal_x>"},
    {"ellipsoidal x 0.5",
     "<inclination>ellipsoidal</inclination><ellipsoidal_x>0.5</ellipsoidal_x>"},
    {"beta mu nu",
     "<inclination>beta</inclination><beta_mu>2.77</beta_mu><beta_nu>1.172</beta_nu>"},
    {"beta mean sd",
     "<inclination>beta</inclination><beta_mean>40</beta_mean><beta_sd>15</beta_sd>"},
    {"histogram",
     "<inclination>histogram</inclination><histogram><bin to=\"20\">1</bin><bin "
     "to=\"50\">0</bin><bin to=\"70\">2</bin><bin to=\"90\">1</bin></histogram>"},
};

}  // namespace

// A built canopy's leaf area by inclination, measured on its triangles, is each family's
// distribution within sampling error: the Kolmogorov-Smirnov distance between the measured
// and the expected cumulative shares (on 0.5 degree steps) stays under the test's critical
// value at the 0.1 % level, 1.949 / sqrt(n), with n the leaves' effective number (the leaves
// weigh by their area, so n is Kish's (sum a)^2 / sum a^2, a little under the leaf count).
TEST(LeafAngle, ACanopysHistogramFollowsEachFamily) {
    std::vector<double> edges;
    for (int i = 0; i <= 180; ++i) edges.push_back(0.5 * i);
    for (const Family& f : kFamilies) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        const std::vector<unsigned> plants = canopy(arch, f.xml);
        const LeafInclinationHistogram h = leafInclinationHistogram(arch, plants, edges);
        LeafAngleParameters p = arch.plant(plants[0]).phenology.leaf_angles;
        const std::vector<double> expected = leafInclinationFractions(p, edges);
        const double n = effectiveSize(leafAreas(arch, plants));
        double measured = 0.0, target = 0.0, d = 0.0;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            measured += h.fractions[i];
            target += expected[i];
            d = std::max(d, std::abs(measured - target));
        }
        const double critical = 1.949 / std::sqrt(n);
        double mean = 0.0;
        for (std::size_t i = 0; i < expected.size(); ++i)
            mean += expected[i] * 0.5 * (edges[i] + edges[i + 1]);
        std::printf(
            "%-18s %4zu leaves (effective %.0f): KS %.4f (critical %.4f), mean %.2f "
            "(expected %.2f)\n",
            f.name, leafAreas(arch, plants).size(), n, d, critical, h.meanInclination, mean);
        EXPECT_GT(n, 2000.0) << f.name;
        EXPECT_NEAR(measured, 1.0, 1e-9) << f.name;
        EXPECT_LT(d, critical) << f.name;
        EXPECT_NEAR(h.meanInclination, meanLeafInclination(arch, plants), 1e-9);
    }
}

// The expected shares are the families' textbook ones: de Wit's and the spherical in closed
// form, the ellipsoidal with x = 1 the spherical, the beta with mu = nu = 1 the uniform.
TEST(LeafAngle, TheExpectedSharesAreTheTextbookOnes) {
    auto closed = [](const char* family, double a, double b) {
        a *= kPi / 180.0;
        b *= kPi / 180.0;
        const std::string f = family;
        if (f == "planophile")
            return 2.0 / kPi * ((b - a) + (std::sin(2 * b) - std::sin(2 * a)) / 2);
        if (f == "erectophile")
            return 2.0 / kPi * ((b - a) - (std::sin(2 * b) - std::sin(2 * a)) / 2);
        if (f == "plagiophile")
            return 2.0 / kPi * ((b - a) - (std::sin(4 * b) - std::sin(4 * a)) / 4);
        if (f == "extremophile")
            return 2.0 / kPi * ((b - a) + (std::sin(4 * b) - std::sin(4 * a)) / 4);
        if (f == "spherical") return std::cos(a) - std::cos(b);
        return 2.0 / kPi * (b - a);
    };
    const std::vector<double> edges = defaultInclinationEdges();
    using D = LeafInclinationDistribution;
    for (const auto& [family, value] :
         {std::pair{"planophile", D::Planophile}, std::pair{"erectophile", D::Erectophile},
          std::pair{"plagiophile", D::Plagiophile}, std::pair{"extremophile", D::Extremophile},
          std::pair{"spherical", D::Spherical}, std::pair{"uniform", D::Uniform}}) {
        LeafAngleParameters p;
        p.inclination = value;
        const std::vector<double> shares = leafInclinationFractions(p);
        for (std::size_t i = 0; i + 1 < edges.size(); ++i)
            EXPECT_NEAR(shares[i], closed(family, edges[i], edges[i + 1]), 1e-9)
                << family << " bin " << i;
    }
    LeafAngleParameters sphere;
    sphere.inclination = D::Spherical;
    LeafAngleParameters ellipsoid;
    ellipsoid.inclination = D::Ellipsoidal;
    ellipsoid.ellipsoidal_x = 1.0f;
    LeafAngleParameters uniform;
    uniform.inclination = D::Uniform;
    LeafAngleParameters beta;
    beta.inclination = D::Beta;
    const auto a = leafInclinationFractions(sphere), b = leafInclinationFractions(ellipsoid),
               c = leafInclinationFractions(uniform), d = leafInclinationFractions(beta);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i], b[i], 1e-9);
        EXPECT_NEAR(c[i], d[i], 1e-9);
    }
    // beta_mean and beta_sd give the beta with that mean (Goel and Strebel's planophile:
    // mu 2.770, nu 1.172, mean 26.76 degrees).
    LeafAngleParameters moments;
    moments.inclination = D::Beta;
    moments.beta_mean = 26.76f;
    moments.beta_sd = 18.51f;
    std::vector<double> fine;
    for (int i = 0; i <= 900; ++i) fine.push_back(0.1 * i);
    const auto shares = leafInclinationFractions(moments, fine);
    double mean = 0.0, total = 0.0;
    for (std::size_t i = 0; i < shares.size(); ++i) {
        mean += shares[i] * 0.5 * (fine[i] + fine[i + 1]);
        total += shares[i];
    }
    EXPECT_NEAR(total, 1.0, 1e-9);
    EXPECT_NEAR(mean, 26.76, 0.01);
}

// The histogram query on known poses: a plant's leaves given inclinations 5, 15, ... 85 by
// hand (their angle targets edited in its plant file) put each leaf's whole area in its bin.
TEST(LeafAngle, TheHistogramOfKnownPosesIsTheirAreasByBin) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::vector<unsigned> plants = canopy(arch, "<inclination>uniform</inclination>", 1);
    std::string xml = arch.getPlantStructureXML(plants);
    // Leaf k (in file order) stands at 5 + 10 (k mod 9) degrees.
    const std::regex target(R"(<angle_target>\s*<inclination>[^<]*</inclination>)");
    std::string edited;
    int k = 0;
    auto begin = std::sregex_iterator(xml.begin(), xml.end(), target);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        edited += xml.substr(last, std::size_t(it->position()) - last);
        edited +=
            "<angle_target><inclination>" + std::to_string(5 + 10 * (k++ % 9)) + "</inclination>";
        last = std::size_t(it->position() + it->length());
    }
    edited += xml.substr(last);
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    const std::vector<unsigned> read = arch2.readPlantStructureXMLString(edited);
    ASSERT_EQ(read.size(), 1u);
    // Expected: each leaf's area in the bin of its pose.
    std::vector<double> area(9, 0.0);
    double total = 0.0, weighted = 0.0;
    int index = 0;
    for (const Shoot& s : arch2.plant(read[0]).shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const LeafOrgan& l : pt.leaves) {
                    ASSERT_TRUE(l.angleTarget);
                    EXPECT_EQ(l.angleTarget->inclination, float(5 + 10 * (index++ % 9)));
                    double a = 0.0;
                    for (ObjectID id : l.objects) a += ctx2.objectArea(id);
                    area[std::size_t(l.angleTarget->inclination / 10)] += a;
                    total += a;
                    weighted += a * l.angleTarget->inclination;
                }
    EXPECT_EQ(index, k);
    ASSERT_GE(index, 27);
    const LeafInclinationHistogram h = leafInclinationHistogram(arch2, read[0]);
    ASSERT_EQ(h.fractions.size(), 9u);
    EXPECT_NEAR(h.leafArea, total, 1e-6 * total);
    for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(h.fractions[i], area[i] / total, 1e-4) << i;
    EXPECT_NEAR(h.meanInclination, weighted / total, 0.01);
    // Bins of the caller's choosing: 0-40 and 40-90 (5 to 35 degrees, and 45 to 85).
    const LeafInclinationHistogram two = leafInclinationHistogram(arch2, read[0], {0, 40, 90});
    EXPECT_NEAR(two.fractions[0], (area[0] + area[1] + area[2] + area[3]) / total, 1e-4);
    EXPECT_NEAR(two.fractions[0] + two.fractions[1], 1.0, 1e-9);
    // Bad edges: one line naming them.
    const Error e = errorOf([&] { leafInclinationHistogram(arch2, read[0], {0, 50, 40}); });
    EXPECT_EQ(e.parameter(), "edges[2]");
    EXPECT_THROW(leafInclinationHistogram(arch2, read[0], {10}), Error);
    EXPECT_THROW(leafInclinationHistogram(arch2, read[0], {0, 91}), Error);
    EXPECT_THROW(leafInclinationHistogram(arch2, 999u), Error);
}

// The poses are state: a plant file keeps them, and reading it back gives the same geometry;
// the same seed builds the same bytes; growing on keeps every pose as it was drawn, even as
// the stem below moves.
TEST(LeafAngle, PlantFilesKeepThePosesAndGrowthKeepsThem) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::vector<unsigned> plants =
        canopy(arch,
               "<inclination>erectophile</inclination><azimuth>von_mises</azimuth>"
               "<azimuth_mean>90</azimuth_mean><azimuth_concentration>2</azimuth_concentration>",
               1);
    const std::string xml = arch.getPlantStructureXML(plants);
    EXPECT_NE(xml.find("<angle_target>"), std::string::npos);
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    const std::vector<unsigned> read = arch2.readPlantStructureXMLString(xml);
    EXPECT_EQ(arch2.getPlantStructureXML(read), xml);
    const LeafInclinationHistogram a = leafInclinationHistogram(arch, plants[0]),
                                   b = leafInclinationHistogram(arch2, read[0]);
    for (std::size_t i = 0; i < a.fractions.size(); ++i)
        EXPECT_NEAR(a.fractions[i], b.fractions[i], 1e-9);

    // Same seed, same bytes.
    Context ctx3;
    PlantArchitecture arch3(&ctx3);
    const std::vector<unsigned> again =
        canopy(arch3,
               "<inclination>erectophile</inclination><azimuth>von_mises</azimuth>"
               "<azimuth_mean>90</azimuth_mean><azimuth_concentration>2</azimuth_concentration>",
               1);
    EXPECT_EQ(arch3.getPlantStructureXML(again), xml);

    // Every leaf's blade normal is its target, and stays it as the plant grows on.
    auto check = [](const PlantArchitecture& a, unsigned plant) {
        int leaves = 0;
        for (const Shoot& s : a.plant(plant).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) {
                        if (l.objects.empty()) continue;
                        const ObjectView o = a.context().object(l.objects[0]);
                        glm::dvec3 sum(0.0);
                        for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3)
                            sum += glm::cross(glm::dvec3(o.positions[o.indices[t + 1]] -
                                                         o.positions[o.indices[t]]),
                                              glm::dvec3(o.positions[o.indices[t + 2]] -
                                                         o.positions[o.indices[t]]));
                        // The blade's plane square to the target (either side of it).
                        const LeafAngleTarget& pose = *l.angleTarget;
                        const double i = pose.inclination * kPi / 180,
                                     az = pose.azimuth * kPi / 180;
                        const glm::dvec3 want(std::sin(i) * std::sin(az),
                                              std::sin(i) * std::cos(az), std::cos(i));
                        const double cosine = std::abs(glm::dot(glm::normalize(sum), want));
                        EXPECT_LT(std::acos(std::min(1.0, cosine)) * 180 / kPi, 0.05);
                        ++leaves;
                    }
        return leaves;
    };
    EXPECT_GE(check(arch, plants[0]), 27);
    arch.advanceTime(plants[0], 20.0f);
    EXPECT_GE(check(arch, plants[0]), 27);
}

// A species file states its distribution; bad values are one line naming the file, the line,
// the parameter and its valid range.
TEST(LeafAngle, SpeciesFilesDeclareAndCheckTheDistribution) {
    const SpeciesModel m = readSpeciesString(
        speciesWith("<inclination>ellipsoidal</inclination><ellipsoidal_x>2.5</ellipsoidal_x>"),
        "ok.xml");
    EXPECT_EQ(m.phenology.leaf_angles.inclination, LeafInclinationDistribution::Ellipsoidal);
    EXPECT_EQ(m.phenology.leaf_angles.ellipsoidal_x, 2.5f);
    // Written and read back.
    const SpeciesModel again = readSpeciesString(writeSpeciesString(m), "again.xml");
    EXPECT_TRUE(again.phenology.leaf_angles == m.phenology.leaf_angles);

    struct Bad {
        std::string angles, parameter;
    };
    for (const Bad& bad : std::vector<Bad>{
             {"<inclination>oblique</inclination>", "phenology.leaf_angles.inclination"},
             {"<ellipsoidal_x>0</ellipsoidal_x>", "phenology.leaf_angles.ellipsoidal_x"},
             {"<ellipsoidal_x>nan</ellipsoidal_x>", "phenology.leaf_angles.ellipsoidal_x"},
             {"<beta_mu>1e9</beta_mu>", "phenology.leaf_angles.beta_mu"},
             {"<beta_mean>40</beta_mean><beta_sd>45</beta_sd>", "phenology.leaf_angles.beta_sd"},
             {"<beta_mean>40</beta_mean>", "phenology.leaf_angles.beta_sd"},
             {"<histogram><bin to=\"95\">1</bin></histogram>",
              "phenology.leaf_angles.histogram.95"},
             {"<histogram><bin to=\"ten\">1</bin></histogram>",
              "phenology.leaf_angles.histogram.ten"},
             {"<histogram><bin to=\"10\">1</bin><bin to=\"10.0\">1</bin></histogram>",
              "phenology.leaf_angles.histogram.10.0"},
             {"<histogram><bin to=\"10\">-1</bin></histogram>",
              "phenology.leaf_angles.histogram.10"},
             {"<inclination>histogram</inclination>", "phenology.leaf_angles.histogram"},
             {"<azimuth_concentration>-1</azimuth_concentration>",
              "phenology.leaf_angles.azimuth_concentration"},
         }) {
        const Error e = errorOf([&] { readSpeciesString(speciesWith(bad.angles), "bad.xml"); });
        EXPECT_EQ(e.file(), "bad.xml") << bad.angles;
        EXPECT_GE(e.line(), 6) << bad.angles << ": " << e.what();
        EXPECT_LE(e.line(), 8) << bad.angles << ": " << e.what();
        EXPECT_EQ(e.parameter(), bad.parameter) << bad.angles << ": " << e.what();
        EXPECT_FALSE(e.validRange().empty()) << bad.angles;
    }
}

// `none`, the default, draws nothing: no leaf has a target and a plant file has no
// angle_target element. (That plants of `none` keep their geometry to the byte is what
// SpeciesChecksum.* checks for every library species.)
TEST(LeafAngle, NoneDrawsNothing) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::vector<unsigned> plants = canopy(arch, "", 2);
    for (unsigned p : plants)
        for (const Shoot& s : arch.plant(p).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) EXPECT_FALSE(l.angleTarget);
    EXPECT_EQ(arch.getPlantStructureXML(plants).find("<angle_target>"), std::string::npos);
    // The same plants drawn with a distribution differ only from their first leaf's draw on.
    LeafAngleParameters none;
    EXPECT_EQ(leafInclinationFractions(none), std::vector<double>(9, 0.0));
    Rng rng(1);
    EXPECT_THROW(drawLeafAngle(none, rng), Error);
}

// The light model reproduces the extinction coefficient of the distribution: a turbid layer of
// small square leaves (1 cm, LAI 2, 20 per cm³... placed at random, poses drawn from the
// distribution with uniform azimuths) lets exp(-k LAI) of a beam reach the ground, with
// k = G / cos(zenith): 0.5 / cos(zenith) for spherical leaves and Campbell's
// sqrt(x^2 + tan^2 zenith) / (x + 1.774 (x + 1.182)^-0.733) for ellipsoidal ones. The ground is
// 6400 squares of 1.5 cm under the layer's middle, one ray each, so the share lit has a
// binomial standard error s = sqrt(p (1 - p) / 6400) and k = -ln(p) / LAI one of s / (p LAI):
// k must lie within 4 of them, plus 2 % for Campbell's approximation of the exact G.
TEST(LeafAngle, TheLightModelSeesTheExtinctionCoefficient) {
    LeafAngleParameters spherical;
    spherical.inclination = LeafInclinationDistribution::Spherical;
    LeafAngleParameters flat;
    flat.inclination = LeafInclinationDistribution::Ellipsoidal;
    flat.ellipsoidal_x = 3.0f;
    const double zenith = 30.0, t = zenith * kPi / 180.0;
    const double x = 3.0;
    const double campbell =
        std::sqrt(x * x + std::tan(t) * std::tan(t)) / (x + 1.774 * std::pow(x + 1.182, -0.733));
    // The exact G of each matches the formulas.
    EXPECT_NEAR(leafProjection(spherical, zenith), 0.5, 1e-4);
    EXPECT_NEAR(leafProjection(flat, zenith) / std::cos(t), campbell, 0.02 * campbell);

    for (const auto& [p, k, slack] : {std::tuple{spherical, 0.5 / std::cos(t), 0.0},
                                      std::tuple{flat, campbell, 0.02 * campbell}}) {
        const float half = 1.0f, height = 0.2f, side = 0.01f;
        const double lai = 2.0;
        const int leaves = int(lai * 4 * half * half / (side * side));
        Context ctx;
        Rng rng(11);
        for (int i = 0; i < leaves; ++i) {
            const vec3 c(rng.uniform(-half, half), rng.uniform(-half, half),
                         0.05f + rng.uniform(0, height));
            const LeafAngleTarget pose = drawLeafAngle(p, rng);
            const float inc = pose.inclination * float(kPi / 180),
                        az = pose.azimuth * float(kPi / 180);
            const vec3 n(std::sin(inc) * std::sin(az), std::sin(inc) * std::cos(az), std::cos(inc));
            const vec3 helper = std::abs(n.z) < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0);
            const vec3 u = glm::normalize(glm::cross(helper, n)) * (side / 2);
            const vec3 v = glm::cross(n, u);
            const std::vector<vec3> corners{c - u - v, c + u - v, c + u + v, c - u + v};
            const ObjectID id = ctx.addObject(corners, {}, kSquare);
            ctx.setObjectData(id, "organ", std::string("leaf"));
        }
        // The ground under the middle, far enough in that a ray to the sun stays in the layer.
        const int cells = 80;
        const float reach = 0.6f, cell = 2 * reach / cells;
        std::vector<ObjectID> ground;
        for (int i = 0; i < cells; ++i)
            for (int j = 0; j < cells; ++j) {
                const vec3 c(-reach + (i + 0.5f) * cell, -reach + (j + 0.5f) * cell, 0.0f);
                const float h = 0.25f * cell;
                const std::vector<vec3> corners{c + vec3(-h, -h, 0), c + vec3(h, -h, 0),
                                                c + vec3(h, h, 0), c + vec3(-h, h, 0)};
                const ObjectID id = ctx.addObject(corners, {}, kSquare);
                ctx.setObjectData(id, "organ", std::string("ground"));
                ground.push_back(id);
            }
        LightOptions o;
        o.scatteringOrders = 0;
        o.directRays = 1;
        o.diffuseRays = 1;
        o.samplesPerObject = 1;
        const LightModel model(ctx, o);
        SkyLight sky;
        sky.sun.elevation = 90.0 - zenith;
        sky.sun.azimuth = 200.0;
        sky.directNormal = 1000.0;
        const LightResult r = model.compute(sky);
        double lit = 0.0;
        int n = 0;
        ObjectID last = kNoObject;
        for (std::size_t i = 0; i < model.triangleCount(); ++i) {
            const ObjectID id = model.objects()[i];
            if (id == last || id < ground.front()) continue;  // one sample per ground square
            last = id;
            lit += r.sunlit[i];
            ++n;
        }
        ASSERT_EQ(n, cells * cells);
        const double gap = lit / n, measured = -std::log(gap) / lai;
        const double se = std::sqrt(gap * (1 - gap) / n) / (gap * lai);
        std::printf("k at zenith %.0f: measured %.4f, expected %.4f (se %.4f)\n", zenith, measured,
                    k, se);
        EXPECT_NEAR(measured, k, 4 * se + slack);
    }
}

// docs/measured-plants.md's species file example is a valid distribution, and its shares are
// its bins' weights.
TEST(LeafAngle, TheDocsExampleIsValid) {
    std::ifstream in(std::string(PLANTARCH_SOURCE_DIR) + "/docs/measured-plants.md");
    std::stringstream page;
    page << in.rdbuf();
    const std::string doc = page.str();
    const std::size_t section = doc.find("## Leaf angle distributions");
    ASSERT_NE(section, std::string::npos);
    const std::size_t block = doc.find("```xml", section);
    ASSERT_NE(block, std::string::npos);
    const std::size_t open = doc.find("<leaf_angles>", block),
                      close = doc.find("</leaf_angles>", block);
    ASSERT_NE(open, std::string::npos);
    ASSERT_NE(close, std::string::npos);
    const std::string angles = doc.substr(open + 13, close - open - 13);
    const SpeciesModel m = readSpeciesString(speciesWith(angles), "docs example");
    const LeafAngleParameters& p = m.phenology.leaf_angles;
    EXPECT_EQ(p.inclination, LeafInclinationDistribution::Histogram);
    EXPECT_EQ(p.azimuth, LeafAzimuthDistribution::VonMises);
    const std::vector<double> shares = leafInclinationFractions(p, {0, 15, 30, 45, 60, 90});
    const std::vector<double> weights{1, 3, 4, 3, 1};
    for (std::size_t i = 0; i < weights.size(); ++i)
        EXPECT_NEAR(shares[i], weights[i] / 12.0, 1e-9) << i;
}
