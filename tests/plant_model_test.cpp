// Plant model: manual building, orientation conventions and labels, checked by measuring the
// generated geometry.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/math.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

float angleBetween(vec3 a, vec3 b) {
    return degrees(
        std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

// Azimuth (degrees, 0..360) of a horizontal direction.
float azimuthOf(vec3 v) {
    float a = degrees(std::atan2(v.y, v.x));
    return a < 0 ? a + 360.0f : a;
}

float azimuthDifference(float a, float b) {
    float d = std::fmod(b - a + 720.0f, 360.0f);
    return d;
}

// A straight, vertical shoot type: no zig-zag, no curvature, no random values.
ShootParameters straightShoot() {
    ShootParameters s;
    s.phytomer_parameters.internode.pitch = 0.0f;
    s.phytomer_parameters.internode.phyllotactic_angle = 180.0f;
    s.phytomer_parameters.internode.radial_subdivisions = 12;
    s.phytomer_parameters.petiole.pitch = 90.0f;
    s.phytomer_parameters.petiole.length = 0.05f;
    s.phytomer_parameters.petiole.radius = 0.002f;
    s.phytomer_parameters.petiole.taper = 1.0f;
    s.phytomer_parameters.leaf.prototype_scale = 0.04f;
    s.max_nodes = 20;
    s.insertion_angle_tip = 35.0f;
    s.insertion_angle_decay_rate = 0.0f;
    return s;
}

struct Fixture {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant = 0;

    explicit Fixture(const ShootParameters& p, unsigned nodes = 4) {
        arch.defineShootType("main", p);
        plant = arch.addPlantInstance({0, 0, 0}, 10);
        ShootSpec spec;
        spec.phytomers = nodes;
        spec.size.internodeRadius = 0.003f;
        spec.size.internodeLengthMax = 0.04f;
        spec.shootType = "main";
        arch.addBaseStemShoot(plant, spec);
    }

    const Shoot& shoot(unsigned id = 0) const { return arch.plant(plant).shoots[id]; }

    // Mean vertex position of an object.
    vec3 centroid(ObjectID id) const {
        vec3 c(0.0f);
        const auto v = ctx.object(id);
        for (const vec3& p : v.positions) c += p;
        return c / float(v.positions.size());
    }

    // Direction of a petiole from its node: centroid minus node, made horizontal.
    vec3 petioleDirection(unsigned node, unsigned petiole) const {
        const ObjectID id = shoot().phytomers[node].petioles[petiole].object;
        vec3 d = centroid(id) - arch.getNodePosition(plant, 0, node);
        d.z = 0.0f;
        return d;
    }
};

}  // namespace

TEST(PlantModel, AlternatePhyllotaxisPutsSuccessivePetioles180Apart) {
    Fixture f(straightShoot(), 5);
    for (unsigned k = 0; k + 1 < 5; ++k) {
        const float d = azimuthDifference(azimuthOf(f.petioleDirection(k, 0)),
                                          azimuthOf(f.petioleDirection(k + 1, 0)));
        EXPECT_NEAR(d, 180.0f, 0.5f) << "node " << k;
    }
}

TEST(PlantModel, OppositePhyllotaxisPutsTwoPetioles180ApartAtOneNode) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.petiole.petioles_per_internode = 2;
    p.phytomer_parameters.internode.phyllotactic_angle = 0.0f;
    Fixture f(p, 3);
    for (unsigned k = 0; k < 3; ++k) {
        ASSERT_EQ(f.shoot().phytomers[k].petioles.size(), 2u);
        const float d = azimuthDifference(azimuthOf(f.petioleDirection(k, 0)),
                                          azimuthOf(f.petioleDirection(k, 1)));
        EXPECT_NEAR(d, 180.0f, 0.5f);
    }
    // Phyllotactic angle 0: every node has its pair on the same sides.
    EXPECT_NEAR(angleBetween(f.petioleDirection(0, 0), f.petioleDirection(2, 0)), 0.0f, 0.5f);
}

TEST(PlantModel, DecussateOppositeTurns90PerNode) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.petiole.petioles_per_internode = 2;
    p.phytomer_parameters.internode.phyllotactic_angle = 90.0f;
    Fixture f(p, 3);
    EXPECT_NEAR(angleBetween(f.petioleDirection(0, 0), f.petioleDirection(1, 0)), 90.0f, 0.5f);
}

TEST(PlantModel, SpiralPhyllotaxisAdvancesBy137_5) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.internode.phyllotactic_angle = 137.5f;
    Fixture f(p, 6);
    for (unsigned k = 0; k + 1 < 6; ++k) {
        const float d = azimuthDifference(azimuthOf(f.petioleDirection(k, 0)),
                                          azimuthOf(f.petioleDirection(k + 1, 0)));
        EXPECT_NEAR(d, 137.5f, 0.5f) << "node " << k;
    }
}

TEST(PlantModel, PetiolePitchIsMeasuredFromTheInternodeAxis) {
    for (float pitch : {30.0f, 60.0f, 90.0f, 120.0f}) {
        ShootParameters p = straightShoot();
        p.phytomer_parameters.petiole.pitch = pitch;
        Fixture f(p, 2);
        const ObjectID id = f.shoot().phytomers[0].petioles[0].object;
        // Axis of a straight tube: from its first ring's centre to its last ring's centre
        // (each ring stores sides + 1 vertices, the seam twice).
        const auto v = f.ctx.object(id);
        const unsigned sides = p.phytomer_parameters.petiole.radial_subdivisions;
        vec3 first(0.0f), last(0.0f);
        for (unsigned k = 0; k < sides; ++k) {
            first += v.positions[k];
            last += v.positions[v.positions.size() - 1 - sides + k];
        }
        const vec3 axis = (last - first) / float(sides);
        EXPECT_NEAR(angleBetween(axis, vec3(0, 0, 1)), pitch, 1.0f) << "pitch " << pitch;
    }
}

TEST(PlantModel, LeafPitchIsMeasuredFromThePetioleAxis) {
    for (float pitch : {-30.0f, 0.0f, 25.0f, 45.0f}) {
        ShootParameters p = straightShoot();
        p.phytomer_parameters.leaf.pitch = pitch;
        Fixture f(p, 2);
        const Petiole& pt = f.shoot().phytomers[0].petioles[0];
        const ObjectID leaf = pt.leaves[0].objects[0];
        const vec3 petioleDir = glm::normalize(f.petioleDirection(0, 0));  // horizontal
        // The leaf tip is its vertex farthest from its base (the petiole tip).
        const auto view = f.ctx.object(leaf);
        const vec3 node = f.arch.getNodePosition(f.plant, 0, 0);
        vec3 base = node + petioleDir * 10.0f;
        float best = 1e9f;
        for (const vec3& v : view.positions) {  // base: leaf vertex nearest the node
            const float d = glm::length(v - node);
            if (d < best) best = d, base = v;
        }
        vec3 tip = base;
        float far = 0.0f;
        for (const vec3& v : view.positions)
            if (glm::length(v - base) > far) far = glm::length(v - base), tip = v;
        const vec3 leafAxis = glm::normalize(tip - base);
        const float elevation = degrees(std::asin(leafAxis.z));
        EXPECT_NEAR(elevation, pitch, 1.0f) << "pitch " << pitch;
        EXPECT_NEAR(glm::dot(glm::normalize(vec3(leafAxis.x, leafAxis.y, 0)), petioleDir), 1.0f,
                    1e-3f);
    }
}

TEST(PlantModel, AChildShootPlacedByHandStartsAtTheGivenPitch) {
    // The type's insertion angle (35 at the tip) belongs to shoots growing from buds; a shoot
    // placed by hand starts at spec.baseRotation.pitch from the parent's axis.
    for (float angle : {0.0f, 20.0f, 45.0f, 70.0f}) {
        ShootParameters p = straightShoot();
        Fixture f(p, 3);
        ShootSpec child;
        child.phytomers = 2;
        child.size.internodeRadius = 0.002f;
        child.size.internodeLengthMax = 0.03f;
        child.shootType = "main";
        child.baseRotation.pitch = angle;
        const unsigned c = f.arch.addChildShoot(f.plant, 0u, 2u, child);
        const vec3 start = f.arch.getNodePosition(f.plant, 0, 2);
        const vec3 first = f.arch.getNodePosition(f.plant, c, 0);
        EXPECT_NEAR(angleBetween(first - start, vec3(0, 0, 1)), angle, 0.5f);
        EXPECT_NEAR(f.arch.plant(f.plant).shoots[c].insertionAngle, angle, 1e-4f);
        // The child leaves on the side of the petiole it grows from.
        if (angle > 0.0f) {
            EXPECT_GT(glm::dot(vec3(first - start), f.petioleDirection(2, 0)), 0.0f);
        }
        EXPECT_EQ(f.arch.getShootRank(f.plant, c), 1u);
        EXPECT_EQ(f.arch.getShootParent(f.plant, c), 0);
    }
}

TEST(PlantModel, AChildShootPlacedByHandIgnoresTheInsertionAngleDecay) {
    ShootParameters p = straightShoot();
    p.insertion_angle_tip = 30.0f;
    p.insertion_angle_decay_rate = 25.0f;
    Fixture f(p, 5);
    ShootSpec child;
    child.size.internodeRadius = 0.002f;
    child.size.internodeLengthMax = 0.03f;
    child.shootType = "main";
    child.baseRotation.pitch = 40.0f;
    for (unsigned node : {4u, 3u, 0u}) {
        const unsigned c = f.arch.addChildShoot(f.plant, 0u, node, child);
        EXPECT_NEAR(f.arch.plant(f.plant).shoots[c].insertionAngle, 40.0f, 1e-4f);
    }
}

TEST(PlantModel, TubeLengthsAndRadiiMatchState) {
    Fixture f(straightShoot(), 3);
    float z = 0.0f;
    for (const Phytomer& ph : f.shoot().phytomers) {
        const AABB box = f.ctx.objectBoundingBox(ph.internode.object);
        EXPECT_NEAR(box.min.z, z, 1e-5f);
        EXPECT_NEAR(box.max.z - box.min.z, ph.internode.length, 1e-5f);
        z += ph.internode.length;
        float rmax = 0.0f;
        for (const vec3& v : f.ctx.object(ph.internode.object).positions)
            rmax = std::max(rmax, std::hypot(v.x, v.y));
        EXPECT_NEAR(rmax, ph.internode.radius, 1e-6f);
    }
    EXPECT_NEAR(f.arch.getPlantStemHeight(f.plant), 3 * 0.04f, 1e-5f);
    // A petiole is as long as its state says (straight: tip minus base).
    const Petiole& pt = f.shoot().phytomers[0].petioles[0];
    const AABB pbox = f.ctx.objectBoundingBox(pt.object);
    EXPECT_NEAR(std::max(pbox.extent().x, pbox.extent().y), pt.length, 0.003f);
}

TEST(PlantModel, ScaleFractionsShrinkOrgans) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.internode.pitch = 0.0f;
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.defineShootType("main", p);
    const unsigned plant = arch.addPlantInstance({1, 2, 0}, 0);
    const unsigned s =
        arch.addBaseStemShoot(plant, {2, {}, {0.002f, 0.05f, 0.5f, 0.25f}, 0.0f, "main"});
    EXPECT_NEAR(arch.getPlantStemHeight(plant), 2 * 0.025f, 1e-5f);
    const float fullArea = float(0.04 * 0.04) * 2;  // upper bound check below uses ratios
    (void)fullArea;
    const Phytomer& ph = arch.plant(plant).shoots[s].phytomers[0];
    const LeafOrgan& leaf = ph.petioles[0].leaves[0];
    const AABB box = ctx.objectBoundingBox(leaf.objects[0]);
    EXPECT_NEAR(std::max(box.extent().x, box.extent().y), leaf.scale * 0.25f, 1e-4f);
    EXPECT_EQ(arch.getPlantBasePosition(plant), vec3(1, 2, 0));
}

// A leaf's area is its prototype's area times its scale squared, with areas known without
// the code: an OBJ leaf that is a 1 x 0.5 rectangle (area 0.5) at scale 0.08 covers
// 0.5 * 0.08^2 = 0.0032 m^2; an elliptic procedural leaf of aspect 0.5 is convex and fills
// its 1 x 0.5 box from tip to base and side to side, so it covers more than the rhombus through
// those four points (0.25) and less than the box (0.5).
TEST(PlantModel, LeafAreaIsPrototypeAreaTimesScaleSquared) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("plantarch_leafarea_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string obj = (dir / "rectangle.obj").string();
    std::ofstream(obj) << "v 0 -0.25 0\nv 1 -0.25 0\nv 1 0.25 0\nv 0 0.25 0\nf 1 2 3\nf 1 3 4\n";
    for (bool fromOBJ : {true, false}) {
        SCOPED_TRACE(fromOBJ ? "OBJ rectangle" : "elliptic outline");
        ShootParameters p = straightShoot();
        p.phytomer_parameters.leaf.prototype_scale = 0.08f;
        if (fromOBJ) {
            p.phytomer_parameters.leaf.prototype.OBJ_model_file = obj;
        } else {
            p.phytomer_parameters.leaf.prototype.shape = LeafShape::Elliptic;
            p.phytomer_parameters.leaf.prototype.leaf_aspect_ratio = 0.5f;
        }
        Fixture f(p, 3);
        ASSERT_EQ(f.arch.getPlantLeafCount(f.plant), 3u);
        const double area = f.arch.getPlantLeafArea(f.plant), scale2 = 3 * 0.08 * 0.08;
        if (fromOBJ) {
            EXPECT_NEAR(area, 0.5 * scale2, 1e-6 * scale2);
        } else {
            EXPECT_GT(area, 0.25 * scale2);
            EXPECT_LT(area, 0.5 * scale2);
        }
        // The query is the sum of the leaf objects' areas.
        double sum = 0.0;
        for (ObjectID id : f.arch.getPlantObjectIDs(f.plant, OrganKind::Leaf))
            sum += f.ctx.objectArea(id);
        EXPECT_NEAR(f.arch.getPlantLeafArea(f.plant), sum, 1e-9);
    }
    std::filesystem::remove_all(dir);
}

TEST(PlantModel, CompoundLeafOddCountTipLeafletAndPairs) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.leaf.leaves_per_petiole = 5;
    p.phytomer_parameters.leaf.leaflet_offset = 0.25f;
    p.phytomer_parameters.leaf.leaflet_scale = 0.8f;
    p.phytomer_parameters.leaf.pitch = 20.0f;
    Fixture f(p, 1);
    const Petiole& pt = f.shoot().phytomers[0].petioles[0];
    ASSERT_EQ(pt.leaves.size(), 5u);
    EXPECT_EQ(f.arch.getPlantLeafCount(f.plant), 5u);
    std::map<int, const LeafOrgan*> byIndex;
    for (const LeafOrgan& l : pt.leaves) byIndex[l.leafletIndex] = &l;
    ASSERT_EQ(byIndex.size(), 5u);
    EXPECT_TRUE(byIndex.count(0) && byIndex.count(-1) && byIndex.count(1) && byIndex.count(-2) &&
                byIndex.count(2));
    EXPECT_FLOAT_EQ(byIndex[0]->position, 1.0f);
    EXPECT_FLOAT_EQ(byIndex[1]->position, 0.75f);
    EXPECT_FLOAT_EQ(byIndex[-2]->position, 0.5f);
    EXPECT_EQ(byIndex[0]->pitch, 0.0f);  // the tip leaflet is unrotated
    EXPECT_EQ(byIndex[1]->pitch, 20.0f);
    // Areas scale with the square of leaflet_scale per pair.
    const double tip = f.ctx.objectArea(byIndex[0]->objects[0]);
    EXPECT_NEAR(f.ctx.objectArea(byIndex[1]->objects[0]) / tip, 0.8 * 0.8, 1e-4);
    EXPECT_NEAR(f.ctx.objectArea(byIndex[-2]->objects[0]) / tip, std::pow(0.8, 4), 1e-4);
    // Pair members sit on opposite sides of the rachis.
    const vec3 node = f.arch.getNodePosition(f.plant, 0, 0);
    const vec3 rachis = glm::normalize(f.petioleDirection(0, 0));
    const vec3 sideways = glm::cross(vec3(0, 0, 1), rachis);
    const float left = glm::dot(f.centroid(byIndex[-1]->objects[0]) - node, sideways);
    const float right = glm::dot(f.centroid(byIndex[1]->objects[0]) - node, sideways);
    EXPECT_GT(left * -right, 0.0f);
    // The tip leaflet continues the rachis.
    EXPECT_NEAR(glm::dot(f.centroid(byIndex[0]->objects[0]) - node, sideways), 0.0f, 1e-3f);
}

TEST(PlantModel, CompoundLeafEvenCountHasTwoTipLeaflets) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.leaf.leaves_per_petiole = 4;
    p.phytomer_parameters.leaf.leaflet_offset = 0.3f;
    p.phytomer_parameters.leaf.leaflet_scale = 0.5f;
    Fixture f(p, 1);
    const Petiole& pt = f.shoot().phytomers[0].petioles[0];
    ASSERT_EQ(pt.leaves.size(), 4u);
    int atTip = 0;
    for (const LeafOrgan& l : pt.leaves) {
        EXPECT_NE(l.leafletIndex, 0);
        if (l.position == 1.0f) {
            ++atTip;
            EXPECT_EQ(std::abs(l.leafletIndex), 1);
        } else {
            EXPECT_FLOAT_EQ(l.position, 0.7f);
        }
    }
    EXPECT_EQ(atTip, 2);
}

TEST(PlantModel, ObjectIDsAreStableAcrossRegeneration) {
    Fixture f(straightShoot(), 3);
    const auto before = f.arch.getAllPlantObjectIDs(f.plant);
    const std::size_t triangles = f.ctx.triangleCount();
    f.arch.updateGeometry(f.plant);
    EXPECT_EQ(f.arch.getAllPlantObjectIDs(f.plant), before);
    EXPECT_EQ(f.ctx.triangleCount(), triangles);
    // Adding a phytomer keeps every existing organ's object.
    f.arch.appendPhytomerToShoot(f.plant, 0, f.arch.shootType("main").phytomer_parameters,
                                 {0.003f, 0.04f, 1.0f, 1.0f});
    const auto after = f.arch.getAllPlantObjectIDs(f.plant);
    for (ObjectID id : before) EXPECT_TRUE(std::count(after.begin(), after.end(), id)) << id;
    EXPECT_GT(after.size(), before.size());
}

TEST(PlantModel, ObjectsCarrySegmentationLabels) {
    Fixture f(straightShoot(), 2);
    f.arch.addFloralBud(f.plant, 0, 1, FloralStage::FlowerOpen);
    std::map<std::string, int> organs;
    for (ObjectID id : f.arch.getAllPlantObjectIDs(f.plant)) {
        EXPECT_EQ(f.ctx.objectDataInt(id, "plantID"), int(f.plant));
        EXPECT_EQ(f.ctx.objectDataInt(id, "shootID"), 0);
        EXPECT_EQ(f.ctx.objectDataInt(id, "rank"), 0);
        EXPECT_TRUE(f.ctx.objectDataFloat(id, "age").has_value());
        const auto organ = f.ctx.objectDataString(id, "organ");
        ASSERT_TRUE(organ.has_value());
        organs[*organ]++;
        if (*organ == "leaf") {
            EXPECT_TRUE(f.ctx.objectDataInt(id, "leafID").has_value());
        }
    }
    EXPECT_EQ(organs["internode"], 2);
    EXPECT_EQ(organs["petiole"], 2);
    EXPECT_EQ(organs["leaf"], 2);
    EXPECT_EQ(organs["peduncle"], 1);
    EXPECT_GE(organs["flower_open"], 1);
    EXPECT_EQ(f.arch.getPlantObjectIDs(f.plant, OrganKind::FlowerOpen).size(),
              size_t(organs["flower_open"]));
}

TEST(PlantModel, ObjectQueryByOrganKindPartitionsThePlantsObjects) {
    Fixture f(straightShoot(), 4);
    f.arch.addFloralBud(f.plant, 0, 0, FloralStage::Fruit);
    f.arch.addFloralBud(f.plant, 0, 1, FloralStage::FlowerOpen);
    f.arch.addFloralBud(f.plant, 0, 2, FloralStage::FlowerClosed);
    const OrganKind kinds[] = {OrganKind::Internode, OrganKind::Petiole,      OrganKind::Leaf,
                               OrganKind::Peduncle,  OrganKind::FlowerClosed, OrganKind::FlowerOpen,
                               OrganKind::Fruit};
    std::vector<ObjectID> all;
    for (OrganKind kind : kinds) {
        const std::vector<ObjectID> ids = f.arch.getPlantObjectIDs(f.plant, kind);
        EXPECT_FALSE(ids.empty()) << organName(kind);
        for (ObjectID id : ids) EXPECT_EQ(f.ctx.objectDataString(id, "organ"), organName(kind));
        all.insert(all.end(), ids.begin(), ids.end());
    }
    EXPECT_EQ(f.arch.getPlantObjectIDs(f.plant, OrganKind::Internode).size(), 4u);
    EXPECT_EQ(f.arch.getPlantObjectIDs(f.plant, OrganKind::Peduncle).size(), 3u);
    std::sort(all.begin(), all.end());
    EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());  // no object twice
    EXPECT_EQ(all, f.arch.getAllPlantObjectIDs(f.plant));
    EXPECT_EQ(all.size(), f.ctx.objectCount());
    EXPECT_THROW(f.arch.getPlantObjectIDs(f.plant + 1, OrganKind::Leaf), Error);
}

TEST(PlantModel, FlowersTurnIntoFruitAndHarvestRemovesThem) {
    ShootParameters p = straightShoot();
    p.phytomer_parameters.inflorescence.flowers_per_peduncle = 3;
    p.phytomer_parameters.inflorescence.flower_offset = 0.3f;
    p.phytomer_parameters.inflorescence.fruit_prototype_scale = 0.03f;
    Fixture f(p, 2);
    EXPECT_EQ(f.arch.addFloralBud(f.plant, 0, 0, FloralStage::Fruit), 3u);
    EXPECT_FALSE(f.arch.getPlantObjectIDs(f.plant, OrganKind::Fruit).empty());
    for (ObjectID id : f.arch.getPlantObjectIDs(f.plant, OrganKind::Fruit))
        EXPECT_EQ(f.ctx.objectDataString(id, "organ"), "fruit");
    EXPECT_EQ(f.arch.harvestPlant(f.plant), 3u);
    EXPECT_TRUE(f.arch.getPlantObjectIDs(f.plant, OrganKind::Fruit).empty());
}

TEST(PlantModel, PruneBranchRemovesNodesAndDescendants) {
    Fixture f(straightShoot(), 5);
    ShootSpec child;
    child.phytomers = 2;
    child.size.internodeRadius = 0.002f;
    child.size.internodeLengthMax = 0.03f;
    child.shootType = "main";
    const unsigned low = f.arch.addChildShoot(f.plant, 0u, 1u, child);
    const unsigned high = f.arch.addChildShoot(f.plant, 0u, 3u, child);
    const unsigned grand = f.arch.addChildShoot(f.plant, high, 0u, child);
    EXPECT_EQ(f.arch.getShootDescendants(f.plant, 0), (std::vector<unsigned>{low, high, grand}));
    EXPECT_EQ(f.arch.getShootPathToRoot(f.plant, grand), (std::vector<unsigned>{grand, high, 0}));
    const std::size_t before = f.ctx.objectCount();
    f.arch.pruneBranch(f.plant, 0, 3);
    EXPECT_EQ(f.arch.getShootNodeCount(f.plant, 0), 3u);
    EXPECT_EQ(f.arch.getShootChildren(f.plant, 0), (std::vector<unsigned>{low}));
    EXPECT_EQ(f.arch.getShootCount(f.plant), 2u);
    EXPECT_LT(f.ctx.objectCount(), before);
    EXPECT_THROW(f.arch.getShootNodeCount(f.plant, high), Error);
    EXPECT_EQ(f.arch.getTerminalShoots(f.plant), (std::vector<unsigned>{low}));
    // Every remaining object belongs to the plant's live organs.
    EXPECT_EQ(f.arch.getAllPlantObjectIDs(f.plant).size(), f.ctx.objectCount());
}

TEST(PlantModel, AppendShootContinuesFromTheTip) {
    Fixture f(straightShoot(), 2);
    ShootSpec spec;
    spec.phytomers = 2;
    spec.size.internodeRadius = 0.002f;
    spec.size.internodeLengthMax = 0.02f;
    spec.shootType = "main";
    const unsigned s = f.arch.appendShoot(f.plant, 0u, spec);
    EXPECT_EQ(f.arch.getShootRank(f.plant, s), 0u);
    const vec3 tip = f.arch.getNodePosition(f.plant, 0, 1);
    EXPECT_NEAR(glm::length(f.arch.getNodePosition(f.plant, s, 0) - (tip + vec3(0, 0, 0.02f))),
                0.0f, 1e-5f);
    EXPECT_NEAR(f.arch.getPlantStemHeight(f.plant), 2 * 0.04f + 2 * 0.02f, 1e-5f);
}

TEST(PlantModel, DeletePlantRemovesItsObjects) {
    Fixture f(straightShoot(), 3);
    EXPECT_GT(f.ctx.objectCount(), 0u);
    f.arch.deletePlantInstance(f.plant);
    EXPECT_EQ(f.ctx.objectCount(), 0u);
    EXPECT_THROW(f.arch.getPlantHeight(f.plant), Error);
}

TEST(PlantModel, InvalidInputGivesClearErrors) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters p = straightShoot();
    p.phytomer_parameters.petiole.length = -0.1f;
    try {
        arch.defineShootType("main", p);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "main.phytomer.petiole.length");
        EXPECT_EQ(e.value(), "-0.1");
        EXPECT_EQ(e.validRange(), "0 to 10");
    }
    p = straightShoot();
    p.fruit_set_probability = 1.5f;
    EXPECT_THROW(arch.defineShootType("main", p), Error);
    p = straightShoot();
    p.child_shoot_types = {{"a", 0.5f}, {"b", 0.6f}};
    try {
        arch.defineShootType("main", p);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sum to 1"), std::string::npos);
    }
    EXPECT_THROW(p.defineChildShootTypes({"a"}, {1.2f}), Error);
    p = straightShoot();
    p.phytomer_parameters.inflorescence.flower_arrangement = static_cast<FlowerArrangement>(7);
    EXPECT_THROW(arch.defineShootType("main", p), Error);
    p = straightShoot();
    p.phytomer_parameters.inflorescence.fruit_prototype_function = "NoSuchFruit";
    EXPECT_THROW(arch.defineShootType("main", p), Error);

    arch.defineShootType("main", straightShoot());
    const unsigned plant = arch.addPlantInstance({0, 0, 0}, 0);
    try {
        arch.addBaseStemShoot(plant, {2, {}, {0.002f, 0.04f, 1, 1}, 0, "mian"});
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "shoot_type_label");
        EXPECT_EQ(e.value(), "mian");
        EXPECT_EQ(e.validRange(), "one of: main");
    }
    EXPECT_THROW(arch.addBaseStemShoot(plant, {2, {}, {-0.002f, 0.04f, 1, 1}, 0, "main"}), Error);
    EXPECT_THROW(arch.addBaseStemShoot(plant, {0, {}, {0.002f, 0.04f, 1, 1}, 0, "main"}), Error);
    EXPECT_THROW(arch.addBaseStemShoot(plant, {2, {}, {0.002f, 0.04f, 1.5f, 1}, 0, "main"}), Error);
    arch.addBaseStemShoot(plant, {2, {}, {0.002f, 0.04f, 1, 1}, 0, "main"});
    EXPECT_THROW(arch.addBaseStemShoot(plant, {2, {}, {0.002f, 0.04f, 1, 1}, 0, "main"}), Error);
    try {
        arch.addChildShoot(plant, 0, 5, {1, {}, {0.002f, 0.02f, 1, 1}, 0, "main"});
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "parent_node_index");
        EXPECT_EQ(e.validRange(), "0 to 1");
    }
    EXPECT_THROW(arch.addChildShoot(plant, 7, 0, {1, {}, {0.002f, 0.02f, 1, 1}, 0, "main"}), Error);
    EXPECT_THROW(arch.addPlantInstance({0, 0, 0}, -1.0f), Error);
    EXPECT_THROW(arch.getPlantHeight(99), Error);
    EXPECT_THROW(arch.pruneBranch(plant, 0, 9), Error);
}

TEST(PlantModel, SameSeedSameGeometry) {
    auto build = [](std::uint64_t seed) {
        ShootParameters p = straightShoot();
        p.phytomer_parameters.internode.phyllotactic_angle = RandomFloat::uniform(120, 200);
        p.phytomer_parameters.petiole.pitch = RandomFloat::normal(60, 10);
        p.phytomer_parameters.leaf.prototype_scale = RandomFloat::uniform(0.03f, 0.06f);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(seed);
        arch.defineShootType("main", p);
        const unsigned plant = arch.addPlantInstance({0, 0, 0}, 0);
        arch.addBaseStemShoot(plant, {6, {}, {0.002f, 0.04f, 1, 1}, 0, "main"});
        std::vector<vec3> all;
        ctx.forEachObject([&](const ObjectView& v) {
            all.insert(all.end(), v.positions.begin(), v.positions.end());
        });
        return all;
    };
    EXPECT_EQ(build(7), build(7));
    EXPECT_NE(build(7), build(8));
}

TEST(PlantModel, LeavesShareAFewShapeVariantsOrAreAllUnique) {
    auto distinctShapes = [](unsigned variants) {
        ShootParameters p = straightShoot();
        p.phytomer_parameters.leaf.prototype.unique_prototypes = variants;
        p.phytomer_parameters.leaf.prototype.leaf_aspect_ratio = RandomFloat::uniform(0.3f, 0.7f);
        p.phytomer_parameters.leaf.prototype.subdivisions = 3;
        Fixture f(p, 20);
        std::set<double> areas;  // a leaf's area divided by its scale^2 identifies its shape
        for (const Phytomer& ph : f.shoot().phytomers) {
            const LeafOrgan& l = ph.petioles[0].leaves[0];
            areas.insert(std::round(f.ctx.objectArea(l.objects[0]) / (l.scale * l.scale) * 1e5));
        }
        return areas.size();
    };
    EXPECT_EQ(distinctShapes(1), 1u);
    EXPECT_EQ(distinctShapes(3),
              3u);  // 20 leaves over 3 variants: all used (deterministic for the fixed seed)
    EXPECT_EQ(distinctShapes(0), 20u);
}
