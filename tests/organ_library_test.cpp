// Tests for plantarch/OrganLibrary.h: the flower and fruit prototype families, their
// parameter table and validation, registration, and the gallery images in docs/images.
//
// Every family is checked against the prototype convention (bounding box from x = 0 to 1,
// finite positions, valid indices, no zero-area triangles), for closed solid parts also
// against edge manifoldness, and for documented parameter effects with measurements written
// here (bounding boxes, connected components, width profiles).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/OrganLibrary.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "plantarch/SpeciesIO.h"

namespace {

using namespace plantarch;
namespace fs = std::filesystem;

// ---- helpers -----------------------------------------------------------------------------

OrganPrototype build(const std::string& family, std::map<std::string, float> params = {},
                     bool open = true, unsigned subdivisions = 8, std::uint64_t seed = 1) {
    FloralPrototypeRequest req;
    req.fruit = floralFamily(family).fruit;
    req.open = open;
    req.parameters = std::move(params);
    req.color = floralFamily(family).defaultColor;
    req.subdivisions = subdivisions;
    Rng rng(seed, 3);
    return buildFloralPrototype(family, req, rng);
}

AABB bounds(const OrganPrototype& proto) {
    AABB box;
    for (const PrototypePart& p : proto)
        for (const vec3& v : p.mesh.positions) box.add(v);
    return box;
}

AABB bounds(const Mesh& m) {
    AABB box;
    for (const vec3& v : m.positions) box.add(v);
    return box;
}

const PrototypePart* part(const OrganPrototype& proto, const std::string& name) {
    for (const PrototypePart& p : proto)
        if (p.material.name == name) return &p;
    return nullptr;
}

std::size_t triangles(const OrganPrototype& proto) {
    std::size_t n = 0;
    for (const PrototypePart& p : proto) n += p.mesh.triangleCount();
    return n;
}

double triangleArea(const Mesh& m, std::size_t t) {
    const glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                     c = m.positions[m.indices[3 * t + 2]];
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// The prototype convention, checked part by part.
void expectConvention(const OrganPrototype& proto, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(proto.empty());
    const AABB box = bounds(proto);
    EXPECT_NEAR(box.min.x, 0.0f, 1e-4f);
    EXPECT_NEAR(box.max.x, 1.0f, 1e-4f);
    std::set<std::string> names;
    for (const PrototypePart& p : proto) {
        SCOPED_TRACE(p.material.name);
        EXPECT_FALSE(p.material.name.empty());
        EXPECT_TRUE(names.insert(p.material.name).second) << "one part per material";
        EXPECT_FALSE(p.mesh.empty());
        EXPECT_NO_THROW(p.mesh.validate());
        EXPECT_EQ(p.mesh.indices.size() % 3, 0u);
        for (const vec3& v : p.mesh.positions)
            ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        for (std::uint32_t i : p.mesh.indices) ASSERT_LT(i, p.mesh.positions.size());
        std::size_t degenerate = 0;
        for (std::size_t t = 0; t < p.mesh.triangleCount(); ++t)
            if (!(triangleArea(p.mesh, t) > 1e-12)) ++degenerate;
        EXPECT_EQ(degenerate, 0u);
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(p.material.color[c], 0.0f);
            EXPECT_LE(p.material.color[c], 1.0f);
        }
    }
}

// Every edge is shared by exactly two triangles that traverse it in opposite directions
// (a closed, consistently oriented 2-manifold), and the enclosed volume is positive.
::testing::AssertionResult closedManifold(const Mesh& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = m.indices[3 * t + e], b = m.indices[3 * t + (e + 1) % 3];
            ++directed[{a, b}];
        }
    for (const auto& [edge, count] : directed) {
        if (count != 1)
            return ::testing::AssertionFailure() << "edge " << edge.first << "-" << edge.second
                                                 << " used " << count << " times in one direction";
        if (!directed.count({edge.second, edge.first}))
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " is a border";
    }
    double volume = 0.0;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                         c = m.positions[m.indices[3 * t + 2]];
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    if (!(volume > 0.0)) return ::testing::AssertionFailure() << "volume " << volume;
    return ::testing::AssertionSuccess();
}

// Connected components of a mesh (vertices joined by triangles).
std::size_t components(const Mesh& m) {
    std::vector<std::uint32_t> parent(m.positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        for (int e = 1; e < 3; ++e) parent[root(m.indices[3 * t + e])] = root(m.indices[3 * t]);
    std::set<std::uint32_t> roots;
    for (std::uint32_t i : m.indices) roots.insert(root(i));
    return roots.size();
}

// Local maxima of a mesh's half-extent along `axis` (1 = y, 2 = z) over bins along x (empty
// bins take the previous bin's value, so use fewer bins than the mesh has rings).
int widthPeaks(const Mesh& m, int axis, int bins) {
    std::vector<float> w(bins, -1.0f);
    const AABB box = bounds(m);
    for (const vec3& v : m.positions) {
        const int b =
            std::clamp(int((v.x - box.min.x) / (box.max.x - box.min.x) * float(bins)), 0, bins - 1);
        w[b] = std::max(w[b], std::abs(v[axis]));
    }
    for (int b = 1; b < bins; ++b)
        if (w[b] < 0.0f) w[b] = w[b - 1];
    int peaks = 0;
    for (int b = 1; b + 1 < bins; ++b) {
        if (!(w[b] > w[b - 1] || (w[b] == w[b - 1] && b > 1 && w[b] > w[b - 2]))) continue;
        int e = b + 1;  // the end of a plateau
        while (e < bins && w[e] == w[b]) ++e;
        if (e < bins && w[e] < w[b]) ++peaks;
        b = e - 1;
    }
    return peaks;
}

bool sameBytes(const OrganPrototype& a, const OrganPrototype& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Mesh &x = a[i].mesh, &y = b[i].mesh;
        if (x.positions.size() != y.positions.size() || x.indices != y.indices ||
            !(a[i].material == b[i].material))
            return false;
        if (std::memcmp(x.positions.data(), y.positions.data(),
                        x.positions.size() * sizeof(vec3)) != 0)
            return false;
    }
    return true;
}

std::vector<std::string> familyNames() {
    std::vector<std::string> names;
    for (const FloralFamilyInfo& f : floralFamilies()) names.push_back(f.name);
    return names;
}

// ---- the table ------------------------------------------------------------------------------

TEST(OrganLibrary, FamilyTableIsWellFormed) {
    const auto& families = floralFamilies();
    ASSERT_GE(families.size(), 18u);
    std::set<std::string> names;
    for (const FloralFamilyInfo& f : families) {
        SCOPED_TRACE(f.name);
        EXPECT_TRUE(names.insert(f.name).second);
        EXPECT_FALSE(f.description.empty());
        EXPECT_FALSE(f.parts.empty());
        EXPECT_EQ(&floralFamily(f.name), &f);
        std::set<std::string> params;
        for (const FloralParameterInfo& p : f.parameters) {
            SCOPED_TRACE(p.name);
            EXPECT_TRUE(params.insert(p.name).second);
            EXPECT_FALSE(p.doc.empty());
            EXPECT_LE(p.min, p.defaultValue);
            EXPECT_LE(p.defaultValue, p.max);
            if (p.integer) {
                EXPECT_EQ(p.defaultValue, std::round(p.defaultValue));
            }
            EXPECT_EQ(f.parameter(p.name), &p);
        }
        EXPECT_EQ(f.parameter("no_such_parameter"), nullptr);
    }
    for (const char* expected :
         {"petal_flower", "papilionaceous_flower", "funnel_flower", "bract_flower", "legume_pod",
          "berry", "berry_cluster", "hollow_berry", "accessory_fruit", "flat_hull", "round_hull",
          "drupe_cluster", "pome", "drupe", "spike", "nodding_panicle", "compact_panicle", "tassel",
          "husked_ear"})
        EXPECT_TRUE(names.count(expected)) << expected;
}

TEST(OrganLibrary, EveryArchitectureHasEveryFamily) {
    std::vector<std::string> functions;
    for (const auto& [name, fn] : floralFamilyFunctions()) {
        EXPECT_TRUE(bool(fn)) << name;
        functions.push_back(name);
    }
    EXPECT_EQ(functions, familyNames());
    Context ctx;
    PlantArchitecture arch(&ctx);
    for (const std::string& name : familyNames()) EXPECT_TRUE(arch.hasFloralPrototype(name));
}

// ---- validation -----------------------------------------------------------------------------

TEST(OrganLibrary, UnknownFamilyIsAnError) {
    try {
        validateFloralParameters("tulip", {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.value(), "tulip");
        EXPECT_NE(e.validRange().find("petal_flower"), std::string::npos);
    }
    EXPECT_THROW(floralFamily("tulip"), Error);
    EXPECT_FALSE(isFloralFamily("tulip"));
    EXPECT_TRUE(isFloralFamily("berry"));
}

TEST(OrganLibrary, UnknownParameterNamesFamilyAndValidNames) {
    try {
        validateFloralParameters("petal_flower", {{"petal_cuont", 5}});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "petal_cuont");
        EXPECT_NE(std::string(e.what()).find("petal_flower"), std::string::npos);
        EXPECT_NE(e.validRange().find("petal_count"), std::string::npos);
    }
}

TEST(OrganLibrary, OutOfRangeValueNamesTheRange) {
    try {
        validateFloralParameters("petal_flower", {{"petal_count", 40}});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "petal_count");
        EXPECT_EQ(e.value(), "40");
        EXPECT_EQ(e.validRange(), "3 to 20");
        EXPECT_NE(std::string(e.what()).find("petal_flower"), std::string::npos);
    }
    EXPECT_THROW(validateFloralParameters("legume_pod", {{"width", -0.1f}}), Error);
    EXPECT_THROW(validateFloralParameters("legume_pod", {{"width", NAN}}), Error);
    EXPECT_THROW(validateFloralParameters("petal_flower", {{"petal_count", 5.5f}}), Error);
    EXPECT_NO_THROW(validateFloralParameters("petal_flower", {{"petal_count", 20}}));
    EXPECT_NO_THROW(validateFloralParameters("petal_flower", {{"petal_count", 3}}));
}

TEST(OrganLibrary, FamilyFunctionsThrowForBadParameters) {
    EXPECT_THROW(build("berry", {{"aspect", 100}}), Error);
    EXPECT_THROW(build("spike", {{"awns", 1}}), Error);
}

// A plant whose fruit come from the library: the registered function is used by the plant
// model, its fruit have the prototype's proportions at the species' scale, and bad shape
// parameters surface as an Error when the fruit is built.
struct LibraryPlant {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant = 0;

    explicit LibraryPlant(const std::map<std::string, float>& fruitParameters) {
        ShootParameters p;
        p.phytomer_parameters.inflorescence.fruit_prototype_function = "berry";
        p.phytomer_parameters.inflorescence.fruit_prototype_parameters = fruitParameters;
        p.phytomer_parameters.inflorescence.fruit_prototype_scale = 0.05f;
        p.phytomer_parameters.inflorescence.flowers_per_peduncle = 1;
        arch.defineShootType("main", p);
        plant = arch.addPlantInstance({0, 0, 0}, 10);
        ShootSpec spec;
        spec.phytomers = 2;
        spec.shootType = "main";
        arch.addBaseStemShoot(plant, spec);
    }
};

TEST(OrganLibrary, PlantModelBuildsLibraryFruit) {
    LibraryPlant good({{"sepal_count", 0}, {"stem_length", 0}});
    EXPECT_EQ(good.arch.addFloralBud(good.plant, 0, 0, FloralStage::Fruit), 1u);
    const std::vector<ObjectID> fruit = good.arch.getPlantObjectIDs(good.plant, OrganKind::Fruit);
    ASSERT_FALSE(fruit.empty());
    AABB box;
    for (ObjectID id : fruit) box.add(good.ctx.objectBoundingBox(id));
    const vec3 e = box.extent();
    EXPECT_NEAR(std::max({e.x, e.y, e.z}), 0.05f, 0.01f);  // a round berry 5 cm across

    // Out-of-range family parameters are rejected when the shoot type is defined.
    try {
        LibraryPlant bad({{"ribs", 99}});
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "main.phytomer.inflorescence.fruit_prototype_parameters.ribs");
        EXPECT_EQ(e.value(), "99");
    }
}

// ---- the convention -------------------------------------------------------------------------

TEST(OrganLibrary, EveryFamilyObeysThePrototypeConvention) {
    for (const FloralFamilyInfo& f : floralFamilies())
        for (unsigned s : {2u, 3u, 6u, 12u})
            for (bool open : {true, false}) {
                if (f.fruit && !open) continue;
                const OrganPrototype p = build(f.name, {}, open, s);
                expectConvention(p,
                                 f.name + (open ? " open" : " closed") + " s=" + std::to_string(s));
                EXPECT_EQ(p.front().material.name, f.parts.front()) << f.name;
                EXPECT_EQ(p.front().material.color, f.defaultColor) << f.name;
                for (const PrototypePart& part : p)
                    EXPECT_NE(std::find(f.parts.begin(), f.parts.end(), part.material.name),
                              f.parts.end())
                        << f.name << " " << part.material.name;
            }
}

TEST(OrganLibrary, TriangleCountGrowsWithSubdivisions) {
    for (const FloralFamilyInfo& f : floralFamilies())
        for (bool open : {true, false}) {
            if (f.fruit && !open) continue;
            std::size_t previous = 0;
            for (unsigned s : {2u, 4u, 8u, 16u}) {
                const std::size_t n = triangles(build(f.name, {}, open, s));
                EXPECT_GT(n, previous) << f.name << (open ? " open" : " closed") << " s=" << s;
                previous = n;
            }
        }
}

TEST(OrganLibrary, SubdivisionsBelowTwoActAsTwo) {
    for (const FloralFamilyInfo& f : floralFamilies())
        EXPECT_TRUE(sameBytes(build(f.name, {}, true, 0), build(f.name, {}, true, 2))) << f.name;
}

TEST(OrganLibrary, SameStreamGivesSameBytes) {
    for (const FloralFamilyInfo& f : floralFamilies())
        for (bool open : {true, false})
            EXPECT_TRUE(sameBytes(build(f.name, {}, open, 6, 99), build(f.name, {}, open, 6, 99)))
                << f.name;
    // Random packing does depend on the stream.
    EXPECT_FALSE(
        sameBytes(build("berry_cluster", {}, true, 6, 1), build("berry_cluster", {}, true, 6, 2)));
}

TEST(OrganLibrary, MainColourComesFromTheRequest) {
    FloralPrototypeRequest req;
    req.color = {0.1f, 0.2f, 0.3f};
    for (const FloralFamilyInfo& f : floralFamilies()) {
        Rng rng(1);
        req.fruit = f.fruit;
        const OrganPrototype p = buildFloralPrototype(f.name, req, rng);
        EXPECT_EQ(p.front().material.color, req.color) << f.name;
    }
}

// Fruit bodies and other solid parts are closed, consistently oriented manifolds.
TEST(OrganLibrary, SolidPartsAreWatertight) {
    const std::vector<std::pair<std::string, std::map<std::string, float>>> cases = {
        {"berry", {}},
        {"berry", {{"ribs", 6}, {"rib_depth", 0.1f}}},
        {"berry", {{"husk", 1}}},
        {"berry_cluster", {}},
        {"hollow_berry", {}},
        {"hollow_berry", {{"blockiness", 0}, {"aspect", 4}, {"tip_curl", 40}}},
        {"accessory_fruit", {}},
        {"pome", {}},
        {"drupe", {}},
        {"round_hull", {}},
        {"flat_hull", {}},
        {"flat_hull", {{"split", 0.7f}}},
        {"legume_pod", {}},
        {"legume_pod", {{"seed_count", 8}, {"curvature", 90}}},
        {"drupe_cluster", {}},
    };
    for (const auto& [family, params] : cases)
        for (unsigned s : {3u, 10u}) {
            const OrganPrototype p = build(family, params, true, s);
            EXPECT_TRUE(closedManifold(p.front().mesh)) << family << " s=" << s;
        }
    EXPECT_TRUE(closedManifold(part(build("flat_hull", {{"split", 0.7f}}), "shell")->mesh));
    EXPECT_TRUE(closedManifold(part(build("husked_ear"), "cob")->mesh));
    EXPECT_TRUE(closedManifold(part(build("accessory_fruit"), "achenes")->mesh));
}

// ---- parameter effects ----------------------------------------------------------------------

TEST(OrganLibrary, PetalCountSetsThePetals) {
    // The petals part holds petal_count identical-resolution sheets.
    for (bool open : {true, false}) {
        const std::size_t five =
            part(build("petal_flower", {{"petal_count", 5}}, open), "petals")->mesh.triangleCount();
        const std::size_t seven =
            part(build("petal_flower", {{"petal_count", 7}}, open), "petals")->mesh.triangleCount();
        EXPECT_EQ(five % 5, 0u);
        EXPECT_EQ(five / 5 * 7, seven);
        EXPECT_EQ(
            components(part(build("petal_flower", {{"petal_count", 7}}, open), "petals")->mesh),
            7u);
    }
    EXPECT_EQ(part(build("petal_flower", {{"sepal_count", 0}}), "sepals")->mesh.triangleCount(),
              part(build("petal_flower", {{"sepal_count", 0}, {"petal_count", 9}}), "sepals")
                  ->mesh.triangleCount());
    EXPECT_EQ(components(part(build("bract_flower", {{"bract_count", 4}}), "bracts")->mesh), 4u);
}

TEST(OrganLibrary, FlowerCentreOnlyWhenOpen) {
    EXPECT_NE(part(build("petal_flower", {}, true), "flower_centre"), nullptr);
    EXPECT_EQ(part(build("petal_flower", {}, false), "flower_centre"), nullptr);
    EXPECT_EQ(part(build("petal_flower", {{"centre_size", 0}, {"stamen_count", 0}}, true),
                   "flower_centre"),
              nullptr);
    // An open funnel is wider than its bud.
    const AABB open = bounds(build("funnel_flower", {}, true));
    const AABB bud = bounds(build("funnel_flower", {}, false));
    EXPECT_GT(open.extent().y, 2.0f * bud.extent().y);
}

TEST(OrganLibrary, PodProportionsFollowWidthAndThickness) {
    for (float width : {0.08f, 0.2f}) {
        const OrganPrototype p = build(
            "legume_pod", {{"width", width}, {"thickness", 0.05f}, {"curvature", 0}, {"hairs", 0}});
        const AABB body = bounds(p.front().mesh);
        EXPECT_NEAR(body.extent().z, width, 0.1f * width);
        EXPECT_NEAR(body.extent().y, 0.05f, 0.01f);
    }
    // Curvature lifts the tip.
    const AABB straight = bounds(build("legume_pod", {{"curvature", 0}}));
    const AABB curved = bounds(build("legume_pod", {{"curvature", 60}}));
    EXPECT_GT(curved.extent().z, straight.extent().z * 1.5f);
}

TEST(OrganLibrary, PodSeedBumpsMatchSeedCount) {
    for (int seeds : {3, 5, 8}) {
        const OrganPrototype p =
            build("legume_pod",
                  {{"seed_count", float(seeds)}, {"curvature", 0}, {"seed_bump", 0.3f}}, true, 12);
        EXPECT_EQ(widthPeaks(p.front().mesh, 1, 40), seeds) << seeds;
    }
    const OrganPrototype smooth =
        build("legume_pod", {{"seed_count", 0}, {"curvature", 0}}, true, 12);
    EXPECT_LE(widthPeaks(smooth.front().mesh, 1, 40), 1);
}

TEST(OrganLibrary, ClustersHaveTheRequestedCounts) {
    for (int n : {1, 12, 60}) {
        const OrganPrototype g = build("berry_cluster", {{"berry_count", float(n)}}, true, 4);
        EXPECT_EQ(components(g.front().mesh), std::size_t(n));
        const OrganPrototype p = build("drupe_cluster", {{"drupe_count", float(n)}}, true, 4);
        EXPECT_EQ(components(p.front().mesh), std::size_t(n));
    }
    const OrganPrototype w = build("spike", {{"spikelet_count", 10}, {"florets", 3}}, true, 4);
    EXPECT_EQ(components(w.front().mesh), 30u);
    EXPECT_EQ(part(build("spike", {{"awn_length", 0}}), "awns"), nullptr);
    EXPECT_NE(part(build("spike", {{"awn_length", 0.5f}}), "awns"), nullptr);
    const OrganPrototype r =
        build("nodding_panicle", {{"branch_count", 6}, {"grains_per_branch", 5}}, true, 4);
    EXPECT_EQ(components(r.front().mesh), 30u);
    const OrganPrototype t = build("accessory_fruit", {{"achene_count", 50}}, true, 4);
    EXPECT_EQ(components(part(t, "achenes")->mesh), 50u);
}

TEST(OrganLibrary, FruitAspectShowsInTheBoundingBox) {
    for (float aspect : {0.8f, 1.0f, 1.5f}) {
        const OrganPrototype p =
            build("berry", {{"aspect", aspect}, {"sepal_count", 0}, {"stem_length", 0}});
        const vec3 e = bounds(p.front().mesh).extent();
        EXPECT_NEAR(e.x / e.y, aspect, 0.05f * aspect);
    }
    const vec3 drupe = bounds(build("drupe", {{"aspect", 1.6f}}).front().mesh).extent();
    EXPECT_NEAR(drupe.x / drupe.y, 1.6f, 0.1f);
}

TEST(OrganLibrary, OptionalPartsAppearWhenAsked) {
    EXPECT_EQ(part(build("berry"), "husk"), nullptr);
    const OrganPrototype husked = build("berry", {{"husk", 1}});
    ASSERT_NE(part(husked, "husk"), nullptr);
    // The lantern encloses the berry.
    const AABB berry = bounds(husked.front().mesh), husk = bounds(part(husked, "husk")->mesh);
    EXPECT_GT(husk.extent().y, berry.extent().y);
    EXPECT_EQ(part(build("flat_hull"), "shell"), nullptr);
    EXPECT_NE(part(build("flat_hull", {{"split", 0.5f}}), "shell"), nullptr);
    EXPECT_EQ(part(build("legume_pod", {{"hairs", 0}}), "hairs"), nullptr);
    EXPECT_NE(part(build("legume_pod", {{"hairs", 1}}), "hairs"), nullptr);
    EXPECT_EQ(part(build("husked_ear", {{"silk_length", 0}}), "silk"), nullptr);
}

// ---- the library species' flowers and fruit -----------------------------------------------

// A flower or fruit as a library species file draws it with a family of this library. The
// species files are the one source of these numbers; the gallery and the family reference
// page show them as the files give them.
struct SpeciesOrgan {
    std::string family;
    bool fruit = false;              ///< the species' fruit (else its flower)
    FloralPrototypeRequest request;  ///< the file's parameters, colour and subdivisions (open)
    std::string scale;               ///< the file's prototype_scale, m, as a distribution
    std::vector<std::string> species;
};

bool sameOrgan(const SpeciesOrgan& a, const SpeciesOrgan& b) {
    return a.family == b.family && a.fruit == b.fruit &&
           a.request.parameters == b.request.parameters && a.request.color == b.request.color &&
           a.request.subdivisions == b.request.subdivisions && a.scale == b.scale;
}

// Every distinct flower and fruit of the species files in species/ that names a family of
// this library, in file order. One drawn alike by several shoot types or species is listed
// once, with every species that draws it.
const std::vector<SpeciesOrgan>& speciesOrgans() {
    static const std::vector<SpeciesOrgan> organs = [] {
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(fs::path(PLANTARCH_SOURCE_DIR) / "species"))
            if (e.path().extension() == ".xml") files.push_back(e.path());
        std::sort(files.begin(), files.end());
        std::vector<SpeciesOrgan> all;
        for (const fs::path& file : files) {
            const SpeciesModel species = readSpeciesFile(file.string());
            for (const auto& [label, type] : species.shootTypes) {
                const InflorescenceParameters& inf = type.phytomer_parameters.inflorescence;
                auto add = [&](bool fruit, const std::string& family,
                               const std::map<std::string, float>& parameters, vec3 color,
                               unsigned subdivisions, const RandomFloat& scale) {
                    if (!isFloralFamily(family)) return;
                    SpeciesOrgan o;
                    o.family = family;
                    o.fruit = fruit;
                    o.request.fruit = fruit;
                    o.request.parameters = parameters;
                    o.request.color = color;
                    o.request.subdivisions = subdivisions;
                    o.scale = scale.describe();
                    o.species.push_back(species.name);
                    auto same = std::find_if(all.begin(), all.end(), [&](const SpeciesOrgan& x) {
                        return sameOrgan(x, o);
                    });
                    if (same == all.end())
                        all.push_back(o);
                    else if (same->species.back() != species.name)
                        same->species.push_back(species.name);
                };
                add(false, inf.flower_prototype_function, inf.flower_prototype_parameters,
                    inf.flower_color, inf.flower_subdivisions, inf.flower_prototype_scale);
                add(true, inf.fruit_prototype_function, inf.fruit_prototype_parameters,
                    inf.fruit_color, inf.fruit_subdivisions, inf.fruit_prototype_scale);
            }
        }
        return all;
    }();
    return organs;
}

std::string speciesList(const SpeciesOrgan& o) {
    std::string s;
    for (const std::string& name : o.species) s += (s.empty() ? "" : ", ") + name;
    return s;
}

// Each flower and fruit the library species draw from a family builds a prototype that
// follows the convention, open and (for flowers) closed, at the species' own resolution,
// with the species' colour on its main part.
TEST(OrganLibrary, SpeciesFlowersAndFruitFollowTheConvention) {
    const std::vector<SpeciesOrgan>& organs = speciesOrgans();
    ASSERT_GE(organs.size(), 20u);
    std::set<std::string> families;
    for (const SpeciesOrgan& o : organs) {
        const std::string what = o.family + " of " + speciesList(o);
        families.insert(o.family);
        for (bool open : {true, false}) {
            if (o.fruit && !open) continue;
            FloralPrototypeRequest req = o.request;
            req.open = open;
            Rng rng(4);
            const OrganPrototype p = buildFloralPrototype(o.family, req, rng);
            expectConvention(p, what + (open ? " open" : " closed"));
            EXPECT_EQ(p.front().material.color, o.request.color) << what;
        }
    }
    EXPECT_GE(families.size(), 15u) << "most families are drawn by some library species";
}

// ---- gallery --------------------------------------------------------------------------------

// How a family is shown: the world directions of the prototype's +x (its axis) and +z. The
// camera looks from -y; flowers face it, fruit hang, cereal heads stand.
struct Pose {
    vec3 axis, up;
};

Pose poseFor(const FloralFamilyInfo& f) {
    const vec3 faceCamera = glm::normalize(vec3(0.0f, -0.55f, 0.85f));
    const vec3 hang = glm::normalize(vec3(0.0f, 0.15f, -1.0f));
    static const std::map<std::string, Pose> poses = {
        {"legume_pod", {{1, 0, 0}, {0, 0, 1}}},      {"husked_ear", {{1, 0, 0}, {0, 0, 1}}},
        {"flat_hull", {{1, 0, 0}, {0, 0, 1}}},       {"spike", {{0, 0, 1}, {0, -1, 0}}},
        {"nodding_panicle", {{0, 0, 1}, {1, 0, 0}}}, {"compact_panicle", {{0, 0, 1}, {0, -1, 0}}},
        {"tassel", {{0, 0, 1}, {0, -1, 0}}},         {"catkin", {hang, {1, 0, 0}}},
    };
    const auto it = poses.find(f.name);
    if (it != poses.end()) return it->second;
    return f.fruit ? Pose{hang, {0, -1, 0}} : Pose{faceCamera, {0, 0, 1}};
}

mat4 poseMatrix(const Pose& pose) {
    const vec3 x = glm::normalize(pose.axis);
    const vec3 z = glm::normalize(pose.up - x * glm::dot(pose.up, x));
    const vec3 y = glm::cross(z, x);
    mat4 m(1.0f);
    m[0] = glm::vec4(x, 0.0f);
    m[1] = glm::vec4(y, 0.0f);
    m[2] = glm::vec4(z, 0.0f);
    return m;
}

struct GalleryItem {
    std::string label;
    OrganPrototype proto;
    int group;  ///< a bud and its open flower share a scale
};

// Variants shown besides the species' organs, to show what the parameters do.
struct Variant {
    std::string family, label;
    std::map<std::string, float> parameters;
    vec3 color;
    bool open = true;
};

const std::vector<Variant>& galleryVariants() {
    static const std::vector<Variant> v = {
        {"flat_hull", "hull split", {{"split", 0.7f}}, {0.46f, 0.54f, 0.34f}},
        {"hollow_berry",
         "horn",
         {{"blockiness", 0.05f},
          {"aspect", 4.5f},
          {"lobes", 3},
          {"lobe_depth", 0.05f},
          {"tip_curl", 35},
          {"stem_length", 0.4f}},
         {0.22f, 0.45f, 0.12f}},
        {"husked_ear", "ear peeled", {{"husk_cover", 0.1f}}, {0.70f, 0.72f, 0.45f}},
        {"tassel", "tassel before anthesis", {}, {0.55f, 0.62f, 0.32f}, false},
        {"berry",
         "single berry",
         {{"aspect", 1.1f}, {"sepal_count", 0}, {"stem_length", 0.3f}},
         {0.45f, 0.62f, 0.25f}},
    };
    return v;
}

std::vector<GalleryItem> galleryItems(const FloralFamilyInfo& f) {
    std::vector<GalleryItem> items;
    int group = 0;
    auto add = [&](const std::string& label, std::map<std::string, float> params, vec3 color,
                   bool open, unsigned subdivisions) {
        FloralPrototypeRequest req{f.fruit, open, std::move(params), color, subdivisions};
        Rng rng(11);
        items.push_back({label, buildFloralPrototype(f.name, req, rng), group});
    };
    int shown = 0;
    for (const SpeciesOrgan& o : speciesOrgans()) {
        if (o.family != f.name) continue;
        const unsigned s = std::max(o.request.subdivisions, 10u);
        const std::string label = speciesList(o);
        // Flowers: the bud next to the open flower (for the first few species).
        if (!f.fruit && shown < 4)
            add(label + " closed", o.request.parameters, o.request.color, false, s);
        add(label, o.request.parameters, o.request.color, true, s);
        ++shown;
        ++group;
    }
    if (shown == 0) {
        if (!f.fruit) add(f.name + " closed", {}, f.defaultColor, false, 12);
        add(f.name, {}, f.defaultColor, true, 12);
        ++group;
    }
    for (const Variant& v : galleryVariants())
        if (v.family == f.name) {
            add(v.label, v.parameters, v.color, v.open, 12);
            ++group;
        }
    return items;
}

// One image per family: its items (closed and open flowers, or fruit) each scaled to fit a
// cell of a grid standing in the x-z plane, seen from -y.
Image renderFamily(const FloralFamilyInfo& f, int width, int height) {
    const mat4 pose = poseMatrix(poseFor(f));
    const std::vector<GalleryItem> items = galleryItems(f);
    const int n = int(items.size());
    const int columns =
        std::max(1, int(std::ceil(std::sqrt(float(n) * float(width) / float(height)))));
    std::vector<AABB> boxes(n);
    std::map<int, float> groupSize;
    for (int k = 0; k < n; ++k) {
        for (const PrototypePart& part : items[k].proto) {
            Mesh m = part.mesh;
            m.transform(pose);
            for (const vec3& v : m.positions) boxes[k].add(v);
        }
        const vec3 e = boxes[k].extent();
        groupSize[items[k].group] = std::max(groupSize[items[k].group], std::max({e.x, e.y, e.z}));
    }
    Context ctx;
    for (int k = 0; k < n; ++k) {
        const vec3 cell{1.2f * float(k % columns), 0.0f, -1.2f * float(k / columns)};
        const mat4 place = glm::translate(mat4(1.0f), cell) *
                           glm::scale(mat4(1.0f), vec3(1.0f / groupSize[items[k].group])) *
                           glm::translate(mat4(1.0f), -boxes[k].center());
        for (const PrototypePart& part : items[k].proto) {
            Mesh m = part.mesh;
            m.transform(place * pose);
            ctx.addObject(m, part.material);
        }
    }
    RenderOptions o;
    o.width = width;
    o.height = height;
    o.samplesPerPixel = 4;
    o.groundPlane = false;
    o.camera.azimuthDeg = -90.0f;
    o.camera.elevationDeg = 10.0f;
    o.camera.fovDeg = 30.0f;
    o.camera.margin = 0.03f;
    o.sunDirection = {-0.3f, -0.7f, 0.65f};
    o.skyZenithColor = o.skyHorizonColor = {0.80f, 0.85f, 0.90f};
    return render(ctx, o);
}

// The family reference page, generated from the family table and the species files.
std::string familyPage() {
    std::ostringstream md;
    md << "# Flower and fruit prototypes\n\n"
          "<!-- Generated by the OrganLibraryDocs.Gallery test (PLANTARCH_WRITE_DOCS_IMAGES=1); "
          "do not edit. -->\n\n"
          "Procedural, parametric flower and fruit families (`plantarch/OrganLibrary.h`). A "
          "species names a family in `flower_prototype_function` / `fruit_prototype_function` "
          "and sets its shape in `flower_prototype_parameters` / `fruit_prototype_parameters`; "
          "unknown names and out-of-range values are errors that name the family, the "
          "parameter and the valid range. Every prototype spans x = 0 to 1 along the organ's "
          "axis from its attachment point (+z up) and is scaled by the species' "
          "`prototype_scale` (m). The first part is coloured by `flower_color` / `fruit_color`; "
          "`subdivisions` sets the mesh resolution. Lengths are fractions of the organ's length "
          "unless a description says otherwise. Each family's picture shows the flowers (closed "
          "and open) and fruit that the library species draw with it, with the values of their "
          "species files listed under it (drawn at a resolution of at least 10), then variants "
          "that show what its parameters do.\n\n"
          "![all families](images/organs-flowers-fruit.png)\n\n";
    for (const FloralFamilyInfo& f : floralFamilies()) {
        md << "## " << f.name << " (" << (f.fruit ? "fruit" : "flower") << ")\n\n"
           << "![" << f.name << "](images/organs/" << f.name << ".png)\n\n"
           << f.description << "\n\nParts: ";
        for (std::size_t i = 0; i < f.parts.size(); ++i)
            md << (i ? ", " : "") << "`" << f.parts[i] << "`" << (i == 0 ? " (main colour)" : "");
        md << ".\n\n| parameter | default | range | description |\n|---|---|---|---|\n";
        for (const FloralParameterInfo& p : f.parameters)
            md << "| `" << p.name << "` | " << p.defaultValue << " | " << p.min << " to " << p.max
               << (p.integer ? " (whole)" : "") << " | " << p.doc << " |\n";
        bool header = false;
        for (const SpeciesOrgan& o : speciesOrgans()) {
            if (o.family != f.name) continue;
            if (!header) md << "\nDrawn by the library species (from their species files):\n\n";
            header = true;
            md << "- " << speciesList(o) << " (" << (o.fruit ? "fruit" : "flower") << "): colour "
               << o.request.color.r << " " << o.request.color.g << " " << o.request.color.b
               << ", subdivisions " << o.request.subdivisions << ", prototype_scale " << o.scale
               << " m";
            for (const auto& [k, v] : o.request.parameters) md << ", " << k << "=" << v;
            md << "\n";
        }
        md << "\n";
    }
    return md.str();
}

// Without PLANTARCH_WRITE_DOCS_IMAGES: the committed family page is the one the family table
// and the species files give now, and every family's picture (drawn small) shows its organs.
// With it: writes docs/images/organs/<family>.png, the contact sheet
// docs/images/organs-flowers-fruit.png and the page.
TEST(OrganLibraryDocs, Gallery) {
    if (!std::getenv("PLANTARCH_WRITE_DOCS_IMAGES")) {
        std::ifstream in(fs::path(PLANTARCH_SOURCE_DIR) / "docs" / "organs-flowers-fruit.md");
        std::stringstream page;
        page << in.rdbuf();
        EXPECT_TRUE(page.str() == familyPage())
            << "docs/organs-flowers-fruit.md is stale: regenerate it with "
               "PLANTARCH_WRITE_DOCS_IMAGES=1 build/plantarch_tests --gtest_filter="
               "OrganLibraryDocs.Gallery";
        for (const FloralFamilyInfo& f : floralFamilies()) {
            SCOPED_TRACE(f.name);
            const Image img = renderFamily(f, 160, 80);
            // Pixels that differ from the background (the corner) by more than a shade.
            std::size_t drawn = 0;
            for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i) {
                int diff = 0;
                for (int c = 0; c < 3; ++c)
                    diff = std::max(diff, std::abs(int(img.rgb[i * 3 + c]) - int(img.rgb[c])));
                drawn += diff > 8 ? 1 : 0;
            }
            EXPECT_GT(drawn, std::size_t(img.width) * img.height / 50);  // at least 2 %
        }
        return;
    }
    const fs::path dir = fs::path(PLANTARCH_SOURCE_DIR) / "docs" / "images";
    fs::create_directories(dir / "organs");
    // Family images 640 x 320; the sheet holds them at half size, four to a row.
    const int w = 640, h = 320, tileW = w / 2, tileH = h / 2, columns = 4;
    const auto& families = floralFamilies();
    const int rows = int((families.size() + columns - 1) / columns);
    Image sheet(tileW * columns, tileH * rows);
    std::fill(sheet.rgb.begin(), sheet.rgb.end(), std::uint8_t(255));
    for (std::size_t i = 0; i < families.size(); ++i) {
        const Image img = renderFamily(families[i], w, h);
        writePNG(img, (dir / "organs" / (families[i].name + ".png")).string());
        const int ox = int(i % columns) * tileW, oy = int(i / columns) * tileH;
        for (int y = 0; y < tileH; ++y)
            for (int x = 0; x < tileW; ++x)
                for (int c = 0; c < 3; ++c) {
                    int sum = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx)
                            sum += img.rgb[(std::size_t(2 * y + dy) * w + 2 * x + dx) * 3 + c];
                    sheet.rgb[(std::size_t(oy + y) * sheet.width + ox + x) * 3 + c] =
                        std::uint8_t((sum + 2) / 4);
                }
    }
    writePNG(sheet, (dir / "organs-flowers-fruit.png").string());
    std::ofstream(dir.parent_path() / "organs-flowers-fruit.md") << familyPage();
}

}  // namespace
