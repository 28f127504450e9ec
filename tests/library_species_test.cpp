// Every species file in the library: it loads, and a plant built at the youngest, usual and
// oldest recommended ages (seeds 42, 1 and 2) is sane (finite, non-empty geometry; height and
// leaves plausible).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

// Every library species is pure data: its rules are node rules, no named C++ function.
namespace {

// Calls f(arch, plant) for every library species grown to its recommended age, one at a time.
template <class F>
void forEachLibraryPlant(F&& f) {
    for (const std::string& name : listSpecies()) {
        SCOPED_TRACE(name);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary(name);
        f(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), loadSpecies(name).recommendedAge));
    }
}

}  // namespace

TEST(LibrarySpecies, EverySpeciesIsPureData) {
    std::size_t withRules = 0;
    for (const std::string& name : listSpecies()) {
        SCOPED_TRACE(name);
        const SpeciesModel model = loadSpecies(name);
        bool rules = false;
        for (const auto& [label, type] : model.shootTypes) {
            EXPECT_EQ(type.phytomer_parameters.phytomer_creation_function, "") << label;
            EXPECT_EQ(type.phytomer_parameters.phytomer_callback_function, "") << label;
            rules = rules || !type.phytomer_parameters.node_rules.empty();
        }
        withRules += rules ? 1 : 0;
    }
    EXPECT_EQ(withRules, 22u);  // the species whose growth needs a node rule
}

TEST(LibrarySpecies, EveryFileBuildsASanePlantAtThreeAgesAndSeeds) {
    const std::vector<std::string> names = listSpecies();
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const SpeciesModel model = loadSpecies(name);
        EXPECT_EQ(model.name, name);
        EXPECT_GT(model.recommendedAge, 0.0f);
        for (std::uint64_t seed : {42, 1, 2}) {
            float lastStem = -1.0f;
            for (float age :
                 {model.recommendedAgeMin, model.recommendedAge, model.recommendedAgeMax}) {
                SCOPED_TRACE("age " + std::to_string(age) + " seed " + std::to_string(seed));
                Context ctx;
                PlantArchitecture arch(&ctx);
                arch.setSeed(seed);
                arch.loadPlantModelFromLibrary(name);
                const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
                ASSERT_GT(ctx.triangleCount(), 0u);
                bool finite = true;
                ctx.forEachObject([&](const ObjectView& v) {
                    for (const vec3& q : v.positions)
                        finite = finite && std::isfinite(q.x) && std::isfinite(q.y) &&
                                 std::isfinite(q.z);
                });
                EXPECT_TRUE(finite);
                const float height = arch.getPlantHeight(p);
                EXPECT_GT(height, 0.0f);
                const float maxHeight = model.maxHeight > 0.0f ? model.maxHeight : 10.0f;
                EXPECT_LE(height, maxHeight);
                // Stems do not shrink (the whole plant may: fruit weigh their stalks down).
                const float stem = arch.getPlantStemHeight(p);
                EXPECT_GE(stem, lastStem - 0.05f * maxHeight);
                lastStem = stem;
                if (age >= model.recommendedAge) {
                    EXPECT_GT(arch.getPlantLeafCount(p) +
                                  arch.getPlantObjectIDs(p, OrganKind::Fruit).size(),
                              0u);
                }
                // Every object is labelled as the plant's organ.
                for (ObjectID id : arch.getAllPlantObjectIDs(p))
                    EXPECT_EQ(ctx.objectDataString(id, "plant_name"), name);
            }
        }
    }
}

// Every library plant's shoots curve as the specification's gravitropism says: between two
// internodes the zenith angle changes by -s (1 - cos z) L C plus the random walk's change
// (z of the previous internode from the vertical, s = 1 below the horizontal and 0.5 above,
// L the new internode's full length, C the shoot's curvature), clamped to 0-180 degrees.
// (L is the length before a node rule rescales the internode; the difference is far below
// the 0.05 degrees allowed.)
TEST(LibrarySpecies, ShootsCurveAsGravitropismSays) {
    const double deg = 3.14159265358979323846 / 180.0;
    std::size_t curvedSpecies = 0;
    forEachLibraryPlant([&](const PlantArchitecture& arch, unsigned p) {
        // Attraction points (trellis wires) steer shoots on purpose; those plants are checked
        // by the collision tests instead.
        if (!arch.getAttractionPoints(p).empty()) return;
        std::size_t turned = 0;
        for (const Shoot& s : arch.plant(p).shoots) {
            if (s.removed) continue;
            for (std::size_t k = 1; k < s.phytomers.size(); ++k) {
                const Internode& a = s.phytomers[k - 1].internode;
                const Internode& b = s.phytomers[k].internode;
                const double za = std::acos(std::clamp(double(a.guide.z), -1.0, 1.0)) / deg;
                const double zb = std::acos(std::clamp(double(b.guide.z), -1.0, 1.0)) / deg;
                const double sfac = za > 90.0 + 1e-3 ? 1.0 : 0.5;
                const double turn = sfac * (1.0 - std::cos(za * deg)) * double(b.length) *
                                    double(s.gravitropicCurvature);
                const double expected = std::clamp(za - turn + double(b.walkZenith), 0.0, 180.0);
                EXPECT_NEAR(zb, expected, 0.05) << "shoot " << s.id << " node " << k;
                turned += std::abs(turn) > 0.1 ? 1 : 0;
            }
        }
        curvedSpecies += turned > 0 ? 1 : 0;
    });
    EXPECT_GE(curvedSpecies, 15u);  // not vacuous: most species have shoots that bend
}

// A compound leaf is one organ with one size: its tip leaflet has the size drawn for the leaf
// and each pair below it leaflet_scale times the size of the pair above, in every species.
TEST(LibrarySpecies, ALeafsLeafletsShareOneSizeDraw) {
    std::size_t compound = 0;
    forEachLibraryPlant([&](const PlantArchitecture& arch, unsigned p) {
        for (const Shoot& s : arch.plant(p).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles) {
                    std::map<int, float> byIndex;
                    for (const LeafOrgan& l : pt.leaves) byIndex[l.leafletIndex] = l.scale;
                    const bool odd = byIndex.count(0) > 0;  // a tip leaflet, or a tip pair
                    if (byIndex.size() < (odd ? 3u : 4u)) continue;
                    const float tip = odd ? byIndex.at(0) : byIndex.at(1);
                    if (!(tip > 0.0f)) continue;  // a leaf a rule scaled to nothing
                    ++compound;
                    const float ratio = odd ? byIndex.at(-1) / tip : byIndex.at(-2) / tip;
                    for (const auto& [index, scale] : byIndex) {
                        const int steps = odd ? std::abs(index) : std::abs(index) - 1;
                        EXPECT_NEAR(scale, tip * std::pow(ratio, float(steps)), 1e-5f * tip)
                            << "shoot " << s.id << " leaflet " << index;
                    }
                }
    });
    EXPECT_GT(compound, 100u);  // not vacuous: the library has compound leaves
}
