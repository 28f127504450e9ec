// Organs of zero size (a fruit just set, a flower not yet drawn, a leaf or internode of zero
// length) have no geometry: no Context object and no triangles, while they keep their place in
// the plant's state. Every library plant is checked for triangles of (near) zero area, which
// inflate files and trouble ray tracers. And a leaf's size, its scale, is its length along the
// blade however the blade curls.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "plant_geometry_bytes.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// Whether a triangle has zero area: under 1e-12 m^2 (a square micrometre) and degenerate in
// shape, its area under 1e-3 of its longest edge squared (corners that coincide or lie on a
// line; a well-shaped triangle has at least a tenth of that edge squared). The shape condition
// keeps out the small but well-formed triangles of a newborn organ: a phytomer made at the
// last instant of growth has its leaves at 1 % of their size (a rice blade 1.5 mm long), and
// the tip triangles of such a blade have 1e-12 m^2 or less. Computed in double from the float
// corners.
bool zeroArea(vec3 a, vec3 b, vec3 c) {
    const glm::dvec3 u = glm::dvec3(b) - glm::dvec3(a), v = glm::dvec3(c) - glm::dvec3(a),
                     w = glm::dvec3(c) - glm::dvec3(b);
    const double area = 0.5 * glm::length(glm::cross(u, v));
    const double edge2 = std::max({glm::dot(u, u), glm::dot(v, v), glm::dot(w, w)});
    return area < 1e-12 && area <= 1e-3 * edge2;
}

}  // namespace

TEST(OrganSizes, NoLibraryPlantHasATriangleOfZeroArea) {
    std::string report;
    std::size_t plants = 0;
    for (const std::string& name : listSpecies()) {
        const SpeciesModel model = loadSpecies(name);
        // The recommended range and the ages plants are compared at besides the picture age:
        // a third, two thirds and one and a half times it (where the species lives that long).
        std::set<float> ages = {model.recommendedAgeMin, model.recommendedAge,
                                model.recommendedAgeMax};
        for (float f : {1.0f / 3.0f, 2.0f / 3.0f, 1.5f}) {
            const float age = std::round(model.recommendedAge * f);
            if (age <= model.phenology.max_age) ages.insert(age);
        }
        for (float age : ages)
            for (std::uint64_t seed = 1; seed <= 3; ++seed) {
                Context ctx;
                PlantArchitecture arch(&ctx);
                arch.setSeed(seed);
                arch.loadPlantModelFromLibrary(name);
                const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
                ++plants;
                std::map<std::string, std::size_t> zero, total;
                for (ObjectID id : arch.getAllPlantObjectIDs(p)) {
                    const ObjectView v = ctx.object(id);
                    const std::string organ = ctx.objectDataString(id, "organ").value_or("?");
                    for (std::size_t t = 0; t + 2 < v.indices.size(); t += 3) {
                        ++total[organ];
                        if (zeroArea(v.positions[v.indices[t]], v.positions[v.indices[t + 1]],
                                     v.positions[v.indices[t + 2]]))
                            ++zero[organ];
                    }
                }
                if (zero.empty()) continue;
                std::ostringstream line;
                line << "\n  " << name << " at " << age << " days, seed " << seed << ":";
                for (const auto& [organ, n] : zero)
                    line << " " << organ << " " << n << " of " << total[organ];
                report += line.str();
            }
    }
    EXPECT_GT(plants, 0u);
    EXPECT_TRUE(report.empty()) << "triangles of zero area:" << report;
}

namespace {

// `xml` with the first fruit-stage bud made a fruit that sets at `age` (the plant's age):
// fruit age and growth 0. Empty when the document has no fruit.
std::string withFruitJustSet(std::string xml, const std::string& age) {
    const std::size_t bud = xml.find("<stage>fruit</stage>");
    if (bud == std::string::npos) return "";
    auto set = [&](const std::string& element, const std::string& value) {
        const std::size_t open = xml.find("<" + element + ">", bud);
        const std::size_t from = open + element.size() + 2;
        xml.replace(from, xml.find('<', from) - from, value);
    };
    set("fruit_age", "0");
    set("fruit_growth", "0");
    set("stage_time", age);
    return xml;
}

struct FruitObjects {
    std::size_t grown = 0;    // fruit of size > 0
    std::size_t ungrown = 0;  // fruit of size 0
    std::size_t ungrownWithObjects = 0;
    std::size_t objects = 0;  // object slots of grown fruit that hold a live object
};

FruitObjects fruitObjects(const PlantArchitecture& arch, const Context& ctx, unsigned p) {
    FruitObjects out;
    auto visit = [&](const FloralBud& fb) {
        if (fb.stage != FloralStage::Fruit) return;
        for (const FlowerOrgan& fl : fb.flowers) {
            if (hasSize(currentFloralSize(fb, fl))) {
                ++out.grown;
                for (ObjectID id : fl.objects) out.objects += ctx.doesObjectExist(id) ? 1 : 0;
            } else {
                ++out.ungrown;
                if (!fl.objects.empty()) ++out.ungrownWithObjects;
            }
        }
    };
    for (const Shoot& s : arch.plant(p).shoots) {
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) visit(fb);
        for (const FloralBud& fb : s.terminalFloralBuds) visit(fb);
    }
    return out;
}

double objectsArea(const Context& ctx, const std::vector<ObjectID>& ids, double* smallest) {
    double total = 0.0;
    *smallest = 1e300;
    for (ObjectID id : ids) {
        const double a = ctx.objectArea(id);
        total += a;
        *smallest = std::min(*smallest, a);
    }
    return total;
}

}  // namespace

// A fruit at the moment it sets has size 0: no Context object, not among the fruit objects,
// while it keeps its place in the state (plant XML and plant strings give it back as it was).
// Grown on, it gets its objects as soon as it has a size, the same for any split of the time.
TEST(OrganSizes, AFruitThatSetsHasNoGeometryUntilItGrows) {
    Context ctxA;
    PlantArchitecture a(&ctxA);
    a.loadPlantModelFromLibrary("bean");
    const unsigned built = a.buildPlantInstanceFromLibrary(vec3(0.0f), 90.0f);
    const std::string xml = withFruitJustSet(a.getPlantStructureXML({built}), "90");
    ASSERT_FALSE(xml.empty()) << "bean at 90 days has no fruit";

    Context ctx;
    PlantArchitecture b(&ctx);
    b.loadPlantModelFromLibrary("bean");  // the shoot types plant strings are read with
    const unsigned p = b.readPlantStructureXMLString(xml).at(0);
    const FruitObjects before = fruitObjects(b, ctx, p);
    ASSERT_GT(before.ungrown, 0u) << "the edited fruit did not read back at size 0";
    ASSERT_GT(before.grown, 0u);
    EXPECT_EQ(before.ungrownWithObjects, 0u);
    // The fruit objects are those of the grown fruit, every one with an area.
    const std::vector<ObjectID> fruit = b.getPlantObjectIDs(p, OrganKind::Fruit);
    EXPECT_EQ(fruit.size(), before.objects);
    double smallest = 0.0;
    objectsArea(ctx, fruit, &smallest);
    EXPECT_GT(smallest, 0.0);

    // The state is kept whole: the same document and the same exact plant string again.
    EXPECT_EQ(b.getPlantStructureXML({p}), xml);
    PlantStringOptions exact;
    exact.significantDigits = 0;
    const std::string text = b.getPlantString(p, exact);
    const unsigned q = b.generatePlantFromString(text);
    EXPECT_EQ(b.getPlantString(q, exact), text);
    EXPECT_EQ(fruitObjects(b, ctx, q).ungrownWithObjects, 0u);
    EXPECT_EQ(b.getPlantObjectIDs(q, OrganKind::Fruit).size(), fruit.size());
    b.deletePlantInstance(q);

    // A day on (in one step here, in two halves in a copy), the fruit has grown and has its
    // objects, with an area.
    Context ctxC;
    PlantArchitecture c(&ctxC);
    const unsigned r = c.readPlantStructureXMLString(xml).at(0);
    b.advanceTime(1.0);
    c.advanceTime(0.5);
    c.advanceTime(0.5);
    const FruitObjects after = fruitObjects(b, ctx, p);
    EXPECT_EQ(after.ungrown, 0u);
    EXPECT_EQ(after.grown, before.grown + before.ungrown);
    const std::vector<ObjectID> grown = b.getPlantObjectIDs(p, OrganKind::Fruit);
    EXPECT_GT(grown.size(), fruit.size());
    EXPECT_EQ(grown.size(), after.objects);
    objectsArea(ctx, grown, &smallest);
    EXPECT_GT(smallest, 0.0);
    EXPECT_EQ(plantarch::testing::firstDifference(plantarch::testing::organBytes(b, {p}),
                                                  plantarch::testing::organBytes(c, {r})),
              "");
}

// A leaf's scale is its length along the blade: a curled, buckled, wavy grass blade of scale
// 0.4 m placed on a plant has a midrib 0.4 m long (within the 1 % its chords may lose), though
// it reaches less far. Its prototype is built here again from the same constant values (no
// random field, so the same mesh), which gives the midrib's vertices: those on y = 0 of the
// flat blade, in the order of their x.
TEST(OrganSizes, AGrassBladesScaleIsItsLengthAlongTheMidrib) {
    ShootParameters type;
    type.phytomer_parameters.internode.max_vegetative_buds_per_petiole = 0;
    type.phytomer_parameters.internode.max_floral_buds_per_petiole = 0;
    LeafParameters& leaf = type.phytomer_parameters.leaf;
    leaf.prototype_scale = 0.4f;
    LeafPrototype& p = leaf.prototype;
    p.shape = LeafShape::Linear;
    p.leaf_aspect_ratio = 0.1f;
    p.base_width = 0.5f;
    p.midrib_fold_fraction = 0.3f;
    p.longitudinal_curvature = -0.4f;
    p.lateral_curvature = -0.3f;
    p.wave_period = 0.1f;
    p.wave_amplitude = 0.1f;
    p.leaf_buckle_length = 0.5f;
    p.leaf_buckle_angle = 45.0f;
    p.subdivisions = 40;
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.defineShootType("grass", type);
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 0.0f);
    arch.addBaseStemShoot(plant, {1, {}, {0.002f, 0.02f, 1.0f, 1.0f}, 0.0f, "grass"});
    const std::vector<ObjectID> leaves = arch.getPlantObjectIDs(plant, OrganKind::Leaf);
    ASSERT_EQ(leaves.size(), 1u);
    const ObjectView placed = ctx.object(leaves[0]);

    Rng rng(1);
    const RealizedLeafShape shape = realizeLeafShape(p, rng);
    RealizedLeafShape flatShape = shape;
    flatShape.deformation = {};
    const Mesh proto = buildLeafMesh(shape), flat = buildLeafMesh(flatShape);
    ASSERT_EQ(placed.positions.size(), proto.positions.size());
    std::vector<std::pair<float, std::size_t>> midrib;
    for (std::size_t i = 0; i < flat.positions.size(); ++i)
        if (std::abs(flat.positions[i].y) < 1e-7f) midrib.emplace_back(flat.positions[i].x, i);
    std::sort(midrib.begin(), midrib.end());
    ASSERT_GT(midrib.size(), 20u);
    double length = 0.0;
    for (std::size_t i = 1; i < midrib.size(); ++i)
        length += glm::length(glm::dvec3(placed.positions[midrib[i].second]) -
                              glm::dvec3(placed.positions[midrib[i - 1].second]));
    EXPECT_NEAR(length, 0.4, 0.004);
    const double reach = glm::length(glm::dvec3(placed.positions[midrib.back().second]) -
                                     glm::dvec3(placed.positions[midrib.front().second]));
    EXPECT_LT(reach, 0.9 * 0.4);  // curled: its tip is nearer its base than 0.4 m
}
