// Plant IDs shared by every PlantArchitecture of a Context, copies of plants, water sprouts,
// seasons ended and begun by hand, ground clipping and organs left without geometry.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "error_of.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStructureIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

// Every vertex of the plant's objects, object by object in ID order.
std::vector<vec3> vertices(const PlantArchitecture& arch, unsigned plant) {
    std::vector<vec3> out;
    for (ObjectID id : arch.getAllPlantObjectIDs(plant))
        for (const vec3& p : arch.context().object(id).positions) out.push_back(p);
    return out;
}

float lowestLeaf(const PlantArchitecture& arch, unsigned plant) {
    float z = 1e9f;
    for (ObjectID id : arch.getPlantObjectIDs(plant, OrganKind::Leaf))
        for (const vec3& p : arch.context().object(id).positions) z = std::min(z, p.z);
    return z;
}

std::set<int> labelledPlants(const Context& ctx) {
    std::set<int> ids;
    for (ObjectID id = 0; id < ctx.objectIDLimit(); ++id)
        if (ctx.doesObjectExist(id))
            if (const auto v = ctx.objectDataInt(id, "plantID")) ids.insert(int(*v));
    return ids;
}

unsigned buildBean(PlantArchitecture& arch, vec3 base = vec3(0.0f), float age = 30.0f) {
    arch.loadPlantModelFromLibrary("bean");
    return arch.buildPlantInstanceFromLibrary(base, age);
}

}  // namespace

// Two PlantArchitectures on one Context (a bean and a maize) number their plants from one
// counter, so labels never merge; IDs are not handed out again after a deletion; and each
// architecture's plants keep the random streams they would have alone.
TEST(PlantIDs, UniquePerContextWhicheverArchitectureMadeThePlant) {
    Context ctx;
    PlantArchitecture beans(&ctx), maize(&ctx);
    const unsigned bean = buildBean(beans);
    maize.loadPlantModelFromLibrary("maize");
    const unsigned corn = maize.buildPlantInstanceFromLibrary(vec3(1, 0, 0), 20.0f);
    EXPECT_NE(bean, corn);
    EXPECT_EQ(labelledPlants(ctx), (std::set<int>{int(bean), int(corn)}));

    beans.deletePlantInstance(bean);
    const unsigned again = buildBean(beans);
    EXPECT_NE(again, bean);
    EXPECT_NE(again, corn);
    const std::vector<unsigned> canopy =
        maize.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.5f, 0.5f), {2, 1}, 10.0f);
    for (unsigned id : canopy) {
        EXPECT_NE(id, again);
        EXPECT_NE(id, corn);
    }
    EXPECT_EQ(labelledPlants(ctx).size(), 4u);

    // The maize plant grew from the same random numbers as a maize alone in a Context.
    Context alone;
    PlantArchitecture solo(&alone);
    solo.loadPlantModelFromLibrary("maize");
    const unsigned only = solo.buildPlantInstanceFromLibrary(vec3(1, 0, 0), 20.0f);
    EXPECT_EQ(maize.plantStream(corn), solo.plantStream(only));
    EXPECT_EQ(maize.getPlantString(corn), solo.getPlantString(only));
    EXPECT_EQ(vertices(maize, corn), vertices(solo, only));
}

TEST(PlantIDs, KeptThroughContextClear) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned first = buildBean(arch, vec3(0.0f), 5.0f);
    ctx.clear();
    PlantArchitecture other(&ctx);
    EXPECT_NE(buildBean(other, vec3(0.0f), 5.0f), first);
}

// The largest distance between corresponding vertices of two vertex lists of one size.
static float worstDistance(const std::vector<vec3>& a, const std::vector<vec3>& b) {
    EXPECT_EQ(a.size(), b.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        worst = std::max(worst, glm::length(a[i] - b[i]));
    return worst;
}

// A copy at the same place, turned by nothing and at the same age is the same geometry (to
// float rounding: its organs are placed afresh); a copy turned about the vertical is the plant
// turned about its base and moved. Leaves are compared vertex by vertex; a tube's rings may
// start at another angle about its axis, so tubes are compared by area and extent.
TEST(DuplicatePlant, SameGeometryTurnedAndMoved) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const vec3 base(0.3f, -0.2f, 0.1f);
    const unsigned plant = buildBean(arch, base, 35.0f);
    const std::vector<vec3> source = vertices(arch, plant);
    ASSERT_FALSE(source.empty());

    const unsigned same = arch.duplicatePlantInstance(plant, base, AxisRotation{}, 35.0f);
    EXPECT_NE(same, plant);
    EXPECT_LT(worstDistance(vertices(arch, same), source), 1e-6f);
    EXPECT_EQ(arch.getPlantName(same), "bean");

    const vec3 there(2.0f, 1.0f, 0.1f);
    const unsigned turned =
        arch.duplicatePlantInstance(plant, there, AxisRotation{0.0f, 90.0f, 0.0f}, 35.0f);
    auto leafVertices = [&](unsigned id) {
        std::vector<vec3> out;
        for (ObjectID o : arch.getPlantObjectIDs(id, OrganKind::Leaf))
            for (const vec3& p : ctx.object(o).positions) out.push_back(p);
        return out;
    };
    // Yaw 90 about the vertical: (x, y) -> (-y, x) about the base.
    std::vector<vec3> want;
    for (const vec3& p : leafVertices(plant)) {
        const vec3 d = p - base;
        want.push_back(there + vec3(-d.y, d.x, d.z));
    }
    ASSERT_FALSE(want.empty());
    // Tube rings around a vertical stem start from a fixed world direction, which the turn
    // does not carry: the organs they bear sit up to about a millimetre apart.
    EXPECT_LT(worstDistance(leafVertices(turned), want), 1.5e-3f);
    EXPECT_NEAR(arch.getPlantLeafArea(turned), arch.getPlantLeafArea(plant), 1e-5f);
    for (OrganKind kind : {OrganKind::Internode, OrganKind::Petiole}) {
        const auto a = arch.getPlantObjectIDs(plant, kind),
                   b = arch.getPlantObjectIDs(turned, kind);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            EXPECT_NEAR(ctx.objectArea(a[i]), ctx.objectArea(b[i]), 1e-3 * ctx.objectArea(a[i]));
            const AABB ba = ctx.objectBoundingBox(a[i]), bb = ctx.objectBoundingBox(b[i]);
            EXPECT_NEAR(ba.max.z - ba.min.z, bb.max.z - bb.min.z, 1.5e-3f);
        }
    }
}

// At another age every scheduled time moves with the plant's clock: the copy's next events
// are as far ahead of it as the source's are of the source.
TEST(DuplicatePlant, ScheduledEventsMoveWithItsClock) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 30.0f);
    const unsigned young = arch.duplicatePlantInstance(plant, vec3(1, 0, 0), AxisRotation{}, 12.0f);
    const PlantInstance& a = arch.plant(plant);
    const PlantInstance& b = arch.plant(young);
    EXPECT_EQ(b.age, 12.0);
    ASSERT_EQ(a.shoots.size(), b.shoots.size());
    int scheduled = 0;
    for (std::size_t i = 0; i < a.shoots.size(); ++i) {
        const double ta = a.shoots[i].nextPhytomerTime, tb = b.shoots[i].nextPhytomerTime;
        if (ta < 0.0) {
            EXPECT_LT(tb, 0.0);
            continue;
        }
        ++scheduled;
        EXPECT_NEAR(tb - b.age, ta - a.age, 1e-9);
        for (std::size_t k = 0; k < a.shoots[i].phytomers.size(); ++k)
            EXPECT_NEAR(a.shoots[i].phytomers[k].birth - b.shoots[i].phytomers[k].birth, 18.0,
                        1e-9);
    }
    EXPECT_GT(scheduled, 0);
    // It grows on, from random numbers of its own.
    arch.advanceTime(young, 10.0);
    EXPECT_EQ(arch.getPlantAge(young), 22.0f);
    EXPECT_NE(arch.plantStream(young), arch.plantStream(plant));
}

TEST(DuplicatePlant, RefusesBadArguments) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 10.0f);
    EXPECT_EQ(
        errorOf([&] { arch.duplicatePlantInstance(plant, vec3(0.0f), {}, -1.0f); }).parameter(),
        "age");
    EXPECT_EQ(
        errorOf([&] { arch.duplicatePlantInstance(plant, vec3(NAN, 0, 0), {}, 1.0f); }).parameter(),
        "base_position");
    EXPECT_EQ(errorOf([&] {
                  arch.duplicatePlantInstance(plant, vec3(0.0f), {INFINITY, 0, 0}, 1.0f);
              }).parameter(),
              "rotation");
    errorOf([&] { arch.duplicatePlantInstance(plant + 100, vec3(0.0f), {}, 1.0f); });
    EXPECT_EQ(arch.getAllPlantIDs().size(), 1u);  // nothing half made
}

TEST(PlantBasePosition, MovesStateAndGeometry) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 20.0f);
    const std::vector<vec3> before = vertices(arch, plant);
    arch.setPlantBasePosition(plant, vec3(0.5f, 0.25f, 0.0f));
    // Leaves to float rounding; tube rings may start at another angle (see above).
    std::vector<vec3> leaves;
    for (ObjectID o : arch.getPlantObjectIDs(plant, OrganKind::Leaf))
        for (const vec3& p : ctx.object(o).positions) leaves.push_back(p);
    std::vector<vec3> wanted;
    {
        Context ref;
        PlantArchitecture again(&ref);
        const unsigned p = buildBean(again, vec3(0.5f, 0.25f, 0.0f), 20.0f);
        for (ObjectID o : again.getPlantObjectIDs(p, OrganKind::Leaf))
            for (const vec3& q : ref.object(o).positions) wanted.push_back(q);
    }
    EXPECT_LT(worstDistance(leaves, wanted), 2e-5f);
    EXPECT_EQ(vertices(arch, plant).size(), before.size());
    EXPECT_EQ(arch.getPlantBasePosition(plant), vec3(0.5f, 0.25f, 0.0f));
}

// A water sprout placed by hand starts upright from the node that holds the point asked for,
// without using that node's axillary buds.
TEST(EpicormicShoots, PlacedByHandStartUpright) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 30.0f);
    // The shoot with the most nodes.
    unsigned parent = 0;
    for (unsigned s = 1; s < arch.getShootCount(plant); ++s)
        if (arch.getShootNodeCount(plant, s) > arch.getShootNodeCount(plant, parent)) parent = s;
    const unsigned n = arch.getShootNodeCount(plant, parent);
    ASSERT_GE(n, 4u);
    ShootSpec spec;
    spec.shootType = "trifoliate";
    spec.phytomers = 2;
    const std::vector<VegetativeBud> buds =
        arch.plant(plant).shoots[parent].phytomers[1].petioles[0].vegetativeBuds;
    const unsigned sprout = arch.addEpicormicShoot(plant, parent, 2.0f / float(n), spec);
    const Shoot& s = arch.plant(plant).shoots[sprout];
    EXPECT_EQ(s.parent, int(parent));
    EXPECT_EQ(s.parentNode, 1);
    EXPECT_EQ(s.rank, arch.plant(plant).shoots[parent].rank + 1);
    EXPECT_NEAR(s.phytomers[0].internode.guide.z, 1.0f, 1e-5f);
    const std::vector<VegetativeBud>& now =
        arch.plant(plant).shoots[parent].phytomers[1].petioles[0].vegetativeBuds;
    ASSERT_EQ(now.size(), buds.size());
    for (std::size_t b = 0; b < buds.size(); ++b) EXPECT_EQ(now[b].state, buds[b].state);

    EXPECT_EQ(errorOf([&] { arch.addEpicormicShoot(plant, 0, 0.0f, spec); }).parameter(),
              "position");
    EXPECT_EQ(errorOf([&] { arch.addEpicormicShoot(plant, 0, 1.5f, spec); }).parameter(),
              "position");
    spec.shootType = "no_such_type";
    EXPECT_EQ(errorOf([&] { arch.addEpicormicShoot(plant, 0, 0.5f, spec); }).parameter(),
              "shoot_type_label");
}

// Enabled on a plant, water sprouts appear as it grows (more with a higher rate), the same
// ones for the same seed, and the setting survives a plant structure file.
TEST(EpicormicShoots, GrowWithThePlantDeterministically) {
    auto grow = [](float rate) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        const unsigned plant = buildBean(arch, vec3(0.0f), 20.0f);
        if (rate > 0.0f) arch.enableEpicormicChildShoots(plant, "trifoliate", rate);
        const unsigned before = arch.getShootCount(plant);
        arch.advanceTime(plant, 15.0);
        return std::make_pair(arch.getShootCount(plant) - before, arch.getPlantString(plant));
    };
    const auto none = grow(0.0f);
    const auto many = grow(20.0f);
    EXPECT_GT(many.first, none.first + 3);
    EXPECT_EQ(grow(20.0f), many);

    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 20.0f);
    arch.enableEpicormicChildShoots(plant, "trifoliate", 2.0f);
    const std::string xml = arch.getPlantStructureXML({plant});
    EXPECT_NE(xml.find("<epicormic_shoots>"), std::string::npos);
    const std::vector<unsigned> read = arch.readPlantStructureXMLString(xml);
    ASSERT_EQ(read.size(), 1u);
    ASSERT_TRUE(arch.plant(read[0]).epicormic.has_value());
    EXPECT_EQ(arch.plant(read[0]).epicormic->shootType, "trifoliate");
    EXPECT_EQ(arch.plant(read[0]).epicormic->probability, 2.0f);

    // A file naming a sprout type nobody defines is refused when read, not when it sprouts.
    std::string bad = xml;
    const std::string label = "<shoot_type_label>trifoliate</shoot_type_label>";
    bad.replace(bad.find(label, bad.find("<epicormic_shoots>")), label.size(),
                "<shoot_type_label>nowhere</shoot_type_label>");
    const std::size_t plants = arch.getAllPlantIDs().size();
    const Error e = errorOf([&] { arch.readPlantStructureXMLString(bad); });
    EXPECT_NE(e.parameter().find("epicormic_shoots"), std::string::npos) << e.what();
    EXPECT_EQ(arch.getAllPlantIDs().size(), plants);

    EXPECT_EQ(
        errorOf([&] { arch.enableEpicormicChildShoots(plant, "trifoliate", -1.0f); }).parameter(),
        "probability");
    EXPECT_EQ(errorOf([&] { arch.enableEpicormicChildShoots(plant, "nope", 1.0f); }).parameter(),
              "shoot_type_label");
    arch.enableEpicormicChildShoots(plant, "trifoliate", 0.0f);
    EXPECT_FALSE(arch.plant(plant).epicormic.has_value());
}

// Ending the season by hand drops the leaves of a deciduous plant and stops it; beginning one
// lets it grow again.
TEST(Seasons, DormancyByHand) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 25.0f);
    ASSERT_FALSE(arch.isPlantDormant(plant));
    ASSERT_GT(arch.getPlantLeafCount(plant), 0u);
    arch.makePlantDormant(plant);
    EXPECT_TRUE(arch.isPlantDormant(plant));
    EXPECT_EQ(arch.getPlantLeafCount(plant), 0u);
    EXPECT_TRUE(arch.getPlantObjectIDs(plant, OrganKind::Leaf).empty());
    const std::string dormant = arch.getPlantString(plant);
    arch.makePlantDormant(plant);  // already dormant: nothing changes
    EXPECT_EQ(arch.getPlantString(plant), dormant);

    arch.breakPlantDormancy(plant);
    EXPECT_FALSE(arch.isPlantDormant(plant));
    unsigned nodes = 0;
    for (unsigned s = 0; s < arch.getShootCount(plant); ++s)
        nodes += arch.getShootNodeCount(plant, s);
    arch.advanceTime(plant, 10.0);
    unsigned later = 0;
    for (unsigned s = 0; s < arch.getShootCount(plant); ++s)
        later += arch.getShootNodeCount(plant, s);
    EXPECT_GT(later, nodes);
}

// Clipping at a height above the plant's base: no leaf reaches below it afterwards, the
// leaves above it are untouched, and growth keeps clipping.
TEST(GroundClipping, LeavesBelowTheHeightFallOff) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 35.0f);
    const unsigned leaves = arch.getPlantLeafCount(plant);
    const float height = 0.5f * arch.getPlantHeight(plant);
    ASSERT_LT(lowestLeaf(arch, plant), height);
    EXPECT_FALSE(arch.getGroundClipping().has_value());
    arch.enableGroundClipping(height);
    EXPECT_EQ(arch.getGroundClipping(), height);
    EXPECT_LT(arch.getPlantLeafCount(plant), leaves);
    EXPECT_GT(arch.getPlantLeafCount(plant), 0u);
    EXPECT_GE(lowestLeaf(arch, plant), height);
    arch.advanceTime(plant, 10.0);
    EXPECT_GE(lowestLeaf(arch, plant), height);
    arch.disableGroundClipping();
    EXPECT_FALSE(arch.getGroundClipping().has_value());
    EXPECT_EQ(errorOf([&] { arch.enableGroundClipping(NAN); }).parameter(), "height");
}

// Without internode geometry the plant is the same plant: every other object is where it was.
TEST(OrganGeometry, LeftOutKindsChangeNothingElse) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned plant = buildBean(arch, vec3(0.0f), 30.0f);
    auto leafVertices = [&] {
        std::vector<vec3> out;
        for (ObjectID id : arch.getPlantObjectIDs(plant, OrganKind::Leaf))
            for (const vec3& p : ctx.object(id).positions) out.push_back(p);
        return out;
    };
    const std::vector<vec3> leaves = leafVertices();
    ASSERT_FALSE(arch.getPlantObjectIDs(plant, OrganKind::Internode).empty());
    arch.setOrganGeometry(OrganKind::Internode, false);
    arch.setOrganGeometry(OrganKind::Petiole, false);
    EXPECT_FALSE(arch.getOrganGeometry(OrganKind::Internode));
    EXPECT_TRUE(arch.getPlantObjectIDs(plant, OrganKind::Internode).empty());
    EXPECT_TRUE(arch.getPlantObjectIDs(plant, OrganKind::Petiole).empty());
    EXPECT_EQ(leafVertices(), leaves);
    // Plants added later and grown plants follow the setting.
    const unsigned second = arch.buildPlantInstanceFromLibrary(vec3(1, 0, 0), 30.0f);
    EXPECT_TRUE(arch.getPlantObjectIDs(second, OrganKind::Internode).empty());
    arch.advanceTime(5.0);
    EXPECT_TRUE(arch.getPlantObjectIDs(plant, OrganKind::Internode).empty());
    arch.setOrganGeometry(OrganKind::Internode, true);
    EXPECT_FALSE(arch.getPlantObjectIDs(plant, OrganKind::Internode).empty());
}

TEST(LeafArea, SummedOverPlants) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned a = buildBean(arch, vec3(0.0f), 20.0f);
    const unsigned b = arch.buildPlantInstanceFromLibrary(vec3(1, 0, 0), 30.0f);
    EXPECT_NEAR(arch.sumPlantLeafArea({a, b}), arch.getPlantLeafArea(a) + arch.getPlantLeafArea(b),
                1e-6f);
    errorOf([&] { arch.sumPlantLeafArea({a, b + 50}); });
}
