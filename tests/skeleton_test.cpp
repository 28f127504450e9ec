// Measured plants: shoots on measured points, skeleton node tables, JSON skeletons and MTG
// files, read and written, and the errors each bad input gets.

#include "plantarch/Skeleton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "error_of.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

// A curved stem: 8 points from the base up and over.
std::vector<vec3> curvedPoints(vec3 base) {
    std::vector<vec3> p{base};
    for (int k = 1; k <= 8; ++k) {
        const float t = float(k) / 8.0f;
        p.push_back(base + vec3(0.08f * t * t, 0.02f * std::sin(3.0f * t), 0.3f * t));
    }
    return p;
}

float distance(vec3 a, vec3 b) {
    return glm::length(a - b);
}

// Every node of every shoot, with its shoot's type, parent and parent node.
struct ShootShape {
    std::string type;
    int parent;
    int parentNode;
    std::vector<vec3> nodes;
    std::vector<float> radii;
};
std::vector<ShootShape> shapes(const PlantArchitecture& arch, unsigned plant) {
    std::vector<ShootShape> out;
    const PlantInstance& p = arch.plant(plant);
    for (const Shoot& s : p.shoots) {
        if (s.removed) continue;
        ShootShape sh{s.type, s.parent, s.parentNode, {}, {}};
        for (unsigned k = 0; k < s.phytomers.size(); ++k) {
            sh.nodes.push_back(arch.getNodePosition(plant, s.id, k));
            sh.radii.push_back(s.phytomers[k].internode.radius);
        }
        out.push_back(sh);
    }
    return out;
}

// Shoots matched by where they start (shoot IDs follow the order shoots were made, which a
// rebuilt plant need not share): the same types, nodes, radii and parents' places.
void expectSameShapes(const std::vector<ShootShape>& a, const std::vector<ShootShape>& b,
                      float tolerance) {
    ASSERT_EQ(a.size(), b.size());
    auto find = [&](const ShootShape& s, const std::vector<ShootShape>& in) -> const ShootShape* {
        for (const ShootShape& t : in)
            if (!t.nodes.empty() && !s.nodes.empty() && t.nodes.size() == s.nodes.size() &&
                distance(t.nodes[0], s.nodes[0]) < tolerance &&
                distance(t.nodes.back(), s.nodes.back()) < tolerance)
                return &t;
        return nullptr;
    };
    auto firstNode = [](const std::vector<ShootShape>& in, int shoot) {
        return shoot < 0 ? vec3(-1e9f) : in[std::size_t(shoot)].nodes.front();
    };
    for (std::size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE("shoot " + std::to_string(i));
        const ShootShape* m = find(a[i], b);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(a[i].type, m->type);
        EXPECT_EQ(a[i].parentNode, m->parentNode);
        EXPECT_LT(distance(firstNode(a, a[i].parent), firstNode(b, m->parent)), tolerance);
        for (std::size_t k = 0; k < a[i].nodes.size(); ++k) {
            EXPECT_LT(distance(a[i].nodes[k], m->nodes[k]), tolerance) << "node " << k;
            EXPECT_NEAR(a[i].radii[k], m->radii[k], 1e-6f) << "node " << k;
        }
    }
}

}  // namespace

TEST(MeasuredShoot, InternodesRunThroughThePointsAndStayAsThePlantGrows) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string type = arch.getBaseStemShootType();
    ASSERT_FALSE(type.empty());
    const vec3 base(0.5f, -0.2f, 0.0f);
    const unsigned plant = arch.addPlantInstance(base, 20.0f);
    const std::vector<vec3> points = curvedPoints(base);
    std::vector<float> radii(points.size());
    for (std::size_t k = 0; k < radii.size(); ++k) radii[k] = 0.004f - 0.0003f * float(k);
    const unsigned shoot = arch.addShootFromNodePositions(plant, -1, 0, points, radii, type);
    ASSERT_EQ(arch.getShootNodeCount(plant, shoot), 8u);
    for (unsigned k = 0; k < 8; ++k) {
        EXPECT_LT(distance(arch.getNodePosition(plant, shoot, k), points[k + 1]), 1e-5f);
        EXPECT_FLOAT_EQ(arch.plant(plant).shoots[shoot].phytomers[k].internode.radius,
                        radii[k + 1]);
        EXPECT_TRUE(arch.plant(plant).shoots[shoot].phytomers[k].measured.has_value());
    }
    EXPECT_GT(arch.getPlantLeafCount(plant), 0u);  // the species' leaves on measured nodes
    // A branch from node 3, measured too.
    const vec3 at = arch.getNodePosition(plant, shoot, 3);
    const unsigned branch = arch.addShootFromNodePositions(
        plant, int(shoot), 3, {at, at + vec3(0.05f, 0.0f, 0.02f), at + vec3(0.1f, 0.01f, 0.03f)},
        {}, type);
    EXPECT_EQ(arch.getShootParent(plant, branch), int(shoot));
    EXPECT_LT(distance(arch.getNodePosition(plant, branch, 1), at + vec3(0.1f, 0.01f, 0.03f)),
              1e-5f);

    // Growing on: the measured internodes keep their place and radius; growth goes on.
    arch.advanceTime(plant, 25.0);
    for (unsigned k = 0; k < 8; ++k) {
        EXPECT_LT(distance(arch.getNodePosition(plant, shoot, k), points[k + 1]), 1e-5f);
        EXPECT_FLOAT_EQ(arch.plant(plant).shoots[shoot].phytomers[k].internode.radius,
                        radii[k + 1]);
    }
    EXPECT_GT(arch.getShootCount(plant), 2u);  // buds broke into shoots
    const unsigned nodes = arch.getShootNodeCount(plant, shoot);
    EXPECT_GE(nodes, 8u);
    for (unsigned k = 8; k < nodes; ++k)  // new growth is not measured
        EXPECT_FALSE(arch.plant(plant).shoots[shoot].phytomers[k].measured.has_value());

    // The plant structure file keeps what was measured.
    Context ctx2;
    PlantArchitecture back(&ctx2);
    const std::vector<unsigned> read =
        back.readPlantStructureXMLString(arch.getPlantStructureXML({plant}));
    ASSERT_EQ(read.size(), 1u);
    expectSameShapes(shapes(arch, plant), shapes(back, read[0]), 1e-6f);
    EXPECT_TRUE(back.plant(read[0]).shoots[shoot].phytomers[0].measured.has_value());
    EXPECT_FLOAT_EQ(back.plant(read[0]).shoots[shoot].phytomers[0].measured->radius, radii[1]);
}

TEST(MeasuredShoot, BadArgumentsNameWhatIsWrong) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string type = arch.getBaseStemShootType();
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 10.0f);
    const std::vector<vec3> good = curvedPoints(vec3(0.0f));
    auto add = [&](std::vector<vec3> p, std::vector<float> r, MeasuredShootOptions o = {}) {
        return errorOf([&] { arch.addShootFromNodePositions(plant, -1, 0, p, r, type, o); });
    };
    std::vector<vec3> nan = good;
    nan[3].y = std::nanf("");
    EXPECT_EQ(add(nan, {}).parameter(), "node_positions[3]");
    std::vector<vec3> same = good;
    same[4] = same[3];
    EXPECT_EQ(add(same, {}).parameter(), "node_positions[4]");
    EXPECT_EQ(add({good[0]}, {}).parameter(), "node_positions");
    EXPECT_EQ(add(good, {0.01f, 0.01f}).parameter(), "node_radii");
    std::vector<float> negative(good.size(), 0.002f);
    negative[2] = -1.0f;
    EXPECT_EQ(add(good, negative).parameter(), "node_radii[2]");
    std::vector<vec3> off = good;
    for (vec3& p : off) p.x += 0.5f;
    const Error far = add(off, {});
    EXPECT_EQ(far.parameter(), "node_positions[0]");
    EXPECT_NE(far.validRange().find("attach_tolerance"), std::string::npos);
    MeasuredShootOptions o;
    o.leafScale = 0.0f;
    EXPECT_EQ(add(good, {}, o).parameter(), "leaf_scale");
    o = {};
    o.bareNodes = {8};
    EXPECT_EQ(add(good, {}, o).parameter(), "bare_nodes");
    EXPECT_EQ(arch.getShootCount(plant), 0u);  // nothing was added by a refused call
    EXPECT_NE(
        errorOf([&] { arch.addShootFromNodePositions(plant, -1, 0, good, {}, "no_such_type"); })
            .message()
            .size(),
        0u);
    arch.addShootFromNodePositions(plant, -1, 0, good, {}, type);
    EXPECT_EQ(
        errorOf([&] { arch.addShootFromNodePositions(plant, 0, 8, good, {}, type); }).parameter(),
        "parentNode");
    EXPECT_EQ(
        errorOf([&] { arch.addShootFromNodePositions(plant, -1, 0, good, {}, type); }).message(),
        "the plant already has a base stem");
}

TEST(Skeleton, NodeTableOfAGrownPlantRebuildsItsShoots) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.2f, 0.1f, 0.0f), 35.0f);
    ASSERT_GT(arch.getShootCount(plant), 1u);
    const std::string csv = skeletonCSV(plantSkeleton(arch, {plant}));
    const Skeleton read = readSkeletonString(csv, "csv", "bean.skeleton.csv");
    Context ctx2;
    PlantArchitecture back(&ctx2);
    back.loadPlantModelFromLibrary("bean");
    const std::vector<unsigned> plants = reconstructPlants(back, read);
    ASSERT_EQ(plants.size(), 1u);
    expectSameShapes(shapes(arch, plant), shapes(back, plants[0]), 1e-5f);
}

TEST(Skeleton, MtgWrittenAndReadBackGivesTheSameTopologyAndNodes) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("tomato");
    const std::vector<unsigned> plants =
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.5f), glm::ivec2(2, 1), 40.0f);
    const std::string mtg = plantsMTG(arch, plants);
    EXPECT_EQ(mtg.rfind("CODE:\tFORM-A\n", 0), 0u);
    const Skeleton read = readSkeletonString(mtg, "mtg", "tomato.mtg");
    Context ctx2;
    PlantArchitecture back(&ctx2);
    back.loadPlantModelFromLibrary("tomato");
    const std::vector<unsigned> rebuilt = reconstructPlants(back, read);
    ASSERT_EQ(rebuilt.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_LT(
            distance(back.getPlantBasePosition(rebuilt[i]), arch.getPlantBasePosition(plants[i])),
            1e-6f);
        expectSameShapes(shapes(arch, plants[i]), shapes(back, rebuilt[i]), 1e-5f);
    }
}

TEST(Skeleton, ReadsAnMtgInTheOpenAleaStyle) {
    // Ranges (<<), '^' continuations, branches in the next column, a leaf class without
    // coordinates, centimetres, and no coordinates on the plant: the first internode's
    // vertex is then the base.
    const std::string mtg =
        "CODE:\tFORM-A\n"
        "CLASSES:\nSYMBOL\tSCALE\tDECOMPOSITION\tINDEXATION\tDEFINITION\n"
        "$\t0\tFREE\tFREE\tIMPLICIT\nP\t1\tFREE\tFREE\tIMPLICIT\n"
        "E\t2\tFREE\tFREE\tEXPLICIT\nL\t2\tFREE\tFREE\tIMPLICIT\n"
        "DESCRIPTION :\nLEFT\tRIGHT\tRELTYPE\tMAX\nE\tE,L\t+\t?\nE\tE\t<\t1\n"
        "FEATURES:\nNAME\tTYPE\nXX\tREAL\nYY\tREAL\nZZ\tREAL\nTopDia\tREAL\n"
        "MTG:\n"
        "TOPO\t\t\tXX\tYY\tZZ\tTopDia\n"
        "/P1/E1\t\t\t0\t0\t0\t0.8\n"
        "^<E2\t\t\t0\t0\t5\t0.7\n"
        "\t+L1\t\t\t\t\t\n"
        "\t+E1\t\t4\t0\t7\t0.3\t# a branch\n"
        "\t^<E2\t\t8\t0\t8\t0.2\n"
        "^<E3\t\t\t0\t1\t10\t0.6\n";
    const Skeleton sk = readSkeletonString(mtg, "mtg", "plant.mtg");
    ASSERT_EQ(sk.nodes.size(), 5u);
    EXPECT_EQ(sk.nodes[0].parent, -1);
    EXPECT_FLOAT_EQ(sk.nodes[2].radius, 0.15f);  // TopDia / 2
    EXPECT_EQ(sk.nodes[2].link, SkeletonLink::Branch);
    EXPECT_EQ(sk.nodes[2].parent, sk.nodes[1].id);
    EXPECT_EQ(sk.nodes[4].parent, sk.nodes[1].id);
    EXPECT_EQ(sk.nodes[4].link, SkeletonLink::Continue);
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    ReconstructOptions o;
    o.unit = 0.01f;
    const std::vector<unsigned> plants = reconstructPlants(arch, sk, o);
    ASSERT_EQ(plants.size(), 1u);
    EXPECT_EQ(arch.getShootCount(plants[0]), 2u);
    EXPECT_EQ(arch.getShootNodeCount(plants[0], 0), 2u);
    EXPECT_LT(distance(arch.getNodePosition(plants[0], 0, 1), vec3(0.0f, 0.01f, 0.1f)), 1e-6f);
    EXPECT_LT(distance(arch.getNodePosition(plants[0], 1, 1), vec3(0.08f, 0.0f, 0.08f)), 1e-6f);
    EXPECT_EQ(arch.getShootParent(plants[0], 1), 0);
    EXPECT_FLOAT_EQ(arch.plant(plants[0]).shoots[1].phytomers[0].internode.radius, 0.0015f);

    // The same with a range: E1<<E3 makes three internodes; the last gets the values.
    const std::string ranged =
        "CODE:\tFORM-A\nCLASSES:\nSYMBOL\tSCALE\tDECOMPOSITION\tINDEXATION\tDEFINITION\n"
        "P\t1\tFREE\tFREE\tIMPLICIT\nE\t2\tFREE\tFREE\tEXPLICIT\nDESCRIPTION:\n"
        "FEATURES:\nNAME\tTYPE\nXX\tREAL\nYY\tREAL\nZZ\tREAL\nMTG:\nTOPO\tXX\tYY\tZZ\n"
        "/P1/E1\t0\t0\t0\n^<E2<<E4\t0\t0\t1\n";
    EXPECT_EQ(errorOf([&] { readSkeletonString(ranged, "mtg", "r.mtg"); }).message(),
              "a stem vertex without XX, YY, ZZ");
}

TEST(Skeleton, ResamplingLaysDenseSkeletonsOnInternodesOfTheSpacing) {
    Skeleton sk;
    sk.source = "dense";
    sk.nodes.push_back({0, -1, vec3(0.0f)});
    for (int k = 1; k <= 100; ++k) {
        const float t = float(k) / 100.0f;
        sk.nodes.push_back({k, k - 1, vec3(0.1f * std::sin(t), 0.0f, 0.5f * t), 0.003f});
    }
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    ReconstructOptions o;
    o.spacing = 0.05f;
    const unsigned plant = reconstructPlants(arch, sk, o).at(0);
    const unsigned n = arch.getShootNodeCount(plant, 0);
    EXPECT_GE(n, 10u);
    EXPECT_LE(n, 11u);
    EXPECT_LT(distance(arch.getNodePosition(plant, 0, n - 1), sk.nodes.back().position), 1e-5f);
    for (unsigned k = 0; k < n; ++k) {  // every node on the measured curve
        const vec3 p = arch.getNodePosition(plant, 0, k);
        const float t = p.z / 0.5f;
        EXPECT_NEAR(p.x, 0.1f * std::sin(t), 2e-4f) << "node " << k;
    }
    o.spacing = 11.0f;
    EXPECT_EQ(errorOf([&] { reconstructPlants(arch, sk, o); }).parameter(), "spacing");
}

TEST(Skeleton, TagsAndShootTypesFromTheTable) {
    const std::string csv =
        "# a measured bean\n"
        "id,parent,x,y,z,radius,link,shoot_type,organs\n"
        "0,,0,0,0,,,,\n"
        "1,0,0,0,0.04,0.003,,,bare\n"
        "2,1,0,0,0.08,0.0025,,,\n"
        "3,2,0,0.01,0.12,0.002,,,fruit\n"
        "4,1,0.03,0,0.06,0.0015,+,,\n"
        "5,4,0.06,0,0.07,0.0015,,,\n";
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = reconstructPlants(arch, readSkeletonString(csv, "csv", "b.csv")).at(0);
    const PlantInstance& p = arch.plant(plant);
    ASSERT_EQ(p.shoots.size(), 2u);
    for (const Petiole& pt : p.shoots[0].phytomers[0].petioles)
        EXPECT_TRUE(pt.leaves.empty() || pt.leaves.front().removed);
    bool fruit = false;
    for (const Petiole& pt : p.shoots[0].phytomers[2].petioles)
        for (const FloralBud& b : pt.floralBuds) fruit = fruit || b.stage == FloralStage::Fruit;
    EXPECT_TRUE(fruit);
    EXPECT_EQ(p.shoots[1].parentNode, 0);
    // The branch took the main stem type's most probable child type.
    const auto& children = arch.shootType(p.shoots[0].type).child_shoot_types;
    if (!children.empty()) {
        EXPECT_TRUE(children.count(p.shoots[1].type));
    }
}

TEST(Skeleton, EachBadInputGetsOneLineNamingFileAndLine) {
    auto csvError = [](const std::string& body) {
        return errorOf([&] { readSkeletonString(body, "csv", "bad.csv"); });
    };
    const std::string head = "id,parent,x,y,z,radius\n";
    Error e = csvError("id,parent,x,y,z,radios\n");
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(e.message().find("did you mean 'radius'"), std::string::npos);
    e = csvError(head + "0,,0,0,0,0\n1,0,0,0,nan,0.1\n");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.parameter(), "z");
    e = csvError(head + "0,,0,0,0,0\n1,0,0,0,1\n");
    EXPECT_EQ(e.line(), 3);
    e = csvError(head + "0,,0,0,0,0\n1,7,0,0,1,0\n");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.message(), "parent not in the skeleton");
    e = csvError(head + "0,,0,0,0,0\n0,0,0,0,1,0\n");
    EXPECT_EQ(e.message(), "node id given twice");
    e = csvError(head + "0,1,0,0,0,0\n1,0,0,0,1,0\n");
    EXPECT_EQ(e.message(), "the skeleton has no root");
    e = csvError(head + "0,,0,0,0,0\n1,2,0,0,1,0\n2,1,0,0,2,0\n");
    EXPECT_EQ(e.message(), "the parents form a cycle");
    e = csvError(head + "0,,0,0,0,-1\n");
    EXPECT_EQ(e.parameter(), "radius");
    e = csvError("x,y,z\n");
    EXPECT_EQ(e.parameter(), "id");
    e = csvError("");
    EXPECT_EQ(e.message(), "the node table has no header");
    e = csvError("id,parent,x,y,z,link\n0,,0,0,0,\n1,0,0,0,1,sideways\n");
    EXPECT_EQ(e.parameter(), "link");
    EXPECT_EQ(e.line(), 3);

    e = errorOf([] {
        readSkeletonString(
            "{\"nodes\": [\n {\"id\": 0, \"position\": [0,0,0]},\n"
            " {\"id\": 1, \"parent\": 0, \"positon\": [0,0,1]}\n]}",
            "json", "bad.json");
    });
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.message().find("did you mean 'position'"), std::string::npos);
    e = errorOf([] { readSkeletonString("{\"nodes\": [", "json", "bad.json"); });
    EXPECT_EQ(e.message().rfind("not a JSON document: ", 0), 0u) << e.message();
    e = errorOf([] {
        readSkeletonString(std::string(200, '[') + std::string(200, ']'), "json", "deep.json");
    });
    EXPECT_EQ(e.message(), "nested too deep");
    e = errorOf(
        [] { readSkeletonString("{\"nodes\": [],\n\"nodes\": []}", "json", "twice.json"); });
    EXPECT_EQ(e.message(), "a field given twice");
    EXPECT_EQ(e.line(), 2);
    e = errorOf([] { readSkeletonString("{\"nodes\": [{\"id\": 1e400}]}", "json", "big.json"); });
    EXPECT_EQ(e.message(), "a number beyond a double's range");

    e = errorOf([] { readSkeletonString("CODE:\tFORM-B\n", "mtg", "b.mtg"); });
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.message(), "FORM-B MTG files are not read");
    e = errorOf([] {
        readSkeletonString(
            "CODE:\tFORM-A\nCLASSES:\nP\t1\tFREE\tFREE\tIMPLICIT\nDESCRIPTION:\n"
            "FEATURES:\nMTG:\nTOPO\n/P1/Q1\n",
            "mtg", "c.mtg");
    });
    EXPECT_EQ(e.line(), 8);
    EXPECT_EQ(e.value(), "Q");
    e = errorOf([] {
        readSkeletonString(
            "CODE:\tFORM-A\nCLASSES:\nP\t1\tFREE\tFREE\tIMPLICIT\nDESCRIPTION:\n"
            "FEATURES:\nMTG:\nTOPO\n/P1\n",
            "mtg", "d.mtg");
    });
    EXPECT_NE(e.message().find("no vertex with XX, YY, ZZ"), std::string::npos);
    EXPECT_EQ(errorOf([] { readSkeletonFile("/nonexistent/skeleton.csv"); }).file(),
              "/nonexistent/skeleton.csv");
    const std::string dir = (std::filesystem::temp_directory_path() / "skeleton_dir.csv").string();
    std::filesystem::create_directories(dir);
    e = errorOf([&] { readSkeletonFile(dir); });
    EXPECT_EQ(e.file(), dir);
    EXPECT_NE(e.message().find("is a directory"), std::string::npos) << e.message();
    std::filesystem::remove(dir);
    EXPECT_EQ(errorOf([] { readSkeletonFile("plant.ply"); }).validRange(), ".csv, .json, .mtg");
}

TEST(MeasuredShoot, MeasuredLeavesFaceTheirNormalAndHaveTheirLength) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string type = arch.getBaseStemShootType();
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 20.0f);
    MeasuredShootOptions o;
    const vec3 facing = glm::normalize(vec3(0.3f, -0.2f, 0.9f));
    o.leaves = {{1, vec3(0.6f, -0.4f, 1.8f), 0.08f}, {0, vec3(0.0f, 0.0f, -1.0f), 0.0f}};
    const unsigned shoot = arch.addShootFromNodePositions(
        plant, -1, 0, {vec3(0.0f), vec3(0, 0, 0.05f), vec3(0.01f, 0, 0.1f)}, {}, type, o);
    const Phytomer& ph = arch.plant(plant).shoots[shoot].phytomers[1];
    float largest = 0.0f;
    int posed = 0;
    for (const Petiole& pt : ph.petioles)
        for (const LeafOrgan& l : pt.leaves) {
            largest = std::max(largest, l.scale);
            vec3 sum(0.0f);  // area-weighted normal of the blade's triangles
            for (ObjectID id : l.objects) {
                const ObjectView v = ctx.object(id);
                for (std::size_t t = 0; t + 2 < v.indices.size(); t += 3) {
                    const vec3 a = v.positions[v.indices[t]], b = v.positions[v.indices[t + 1]],
                               c = v.positions[v.indices[t + 2]];
                    sum += glm::cross(b - a, c - a);
                }
            }
            ASSERT_GT(glm::length(sum), 0.0f);
            const float angle =
                std::acos(std::clamp(glm::dot(glm::normalize(sum), facing), -1.0f, 1.0f)) /
                0.0174533f;
            EXPECT_LT(angle, 3.0f) << "leaf " << l.leafID;
            ++posed;
        }
    EXPECT_GT(posed, 0);
    EXPECT_FLOAT_EQ(largest, 0.08f);
    // A normal pointing down poses the blade's plane: the leaves of node 0 lie flat.
    for (const Petiole& pt : arch.plant(plant).shoots[shoot].phytomers[0].petioles)
        for (const LeafOrgan& l : pt.leaves) {
            ASSERT_TRUE(l.angleTarget.has_value());
            EXPECT_NEAR(l.angleTarget->inclination, 0.0f, 1e-4f);
        }
    o.leaves = {{5, std::nullopt, 0.0f}};
    EXPECT_EQ(
        errorOf([&] {
            arch.addShootFromNodePositions(plant, 0, 1, {vec3(0.0f), vec3(0.1f)}, {}, type, o);
        }).parameter(),
        "leaves[0].node");
    o.leaves = {{0, vec3(0.0f), 0.0f}};
    EXPECT_EQ(
        errorOf([&] {
            arch.addShootFromNodePositions(plant, 0, 1, {vec3(0.0f), vec3(0.1f)}, {}, type, o);
        }).parameter(),
        "leaves[0].normal");
    // The same from a node table: leaf_nx, leaf_ny, leaf_nz, leaf_length.
    const Skeleton sk = readSkeletonString(
        "id,parent,x,y,z,leaf_nx,leaf_ny,leaf_nz,leaf_length\n0,,0,0,0,,,,\n1,0,0,0,5,,,,\n"
        "2,1,1,0,10,0.6,-0.4,1.8,8\n",
        "csv", "leaves.csv");
    ReconstructOptions ro;
    ro.unit = 0.01f;
    const unsigned rebuilt = reconstructPlants(arch, sk, ro).at(0);
    for (const Petiole& pt : arch.plant(rebuilt).shoots[0].phytomers[1].petioles)
        for (const LeafOrgan& l : pt.leaves) {
            ASSERT_TRUE(l.angleTarget.has_value());
            EXPECT_NEAR(l.angleTarget->inclination, std::acos(facing.z) / 0.0174533f, 1e-3f);
        }
    EXPECT_NE(skeletonCSV(sk).find("leaf_nx,leaf_ny,leaf_nz,leaf_length"), std::string::npos);
    EXPECT_EQ(readSkeletonString(skeletonCSV(sk), "csv", "again").nodes[2].leafNormal,
              sk.nodes[2].leafNormal);
}

TEST(MeasuredShoot, BendingLeavesMeasuredInternodesAsMeasured) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 20.0f);
    PhenologyParameters p = arch.plant(plant).phenology;
    p.mechanics.enabled = true;
    p.mechanics.elastic_modulus = 1e7f;  // very soft: anything that may bend, bends
    arch.setPlantPhenologicalThresholds(plant, p);
    // A measured stem leaning far over, carrying its leaves, of a type that grows on.
    const std::vector<vec3> points{vec3(0.0f), vec3(0.04f, 0, 0.04f), vec3(0.1f, 0, 0.07f),
                                   vec3(0.17f, 0, 0.09f)};
    ASSERT_GT(arch.shootType("trifoliate").max_nodes.mean(), 10.0f);
    const unsigned shoot = arch.addShootFromNodePositions(plant, -1, 0, points, {}, "trifoliate");
    arch.advanceTime(plant, 10.0);
    const Shoot& s = arch.plant(plant).shoots[shoot];
    ASSERT_GT(s.phytomers.size(), 3u);
    for (unsigned k = 0; k < 3; ++k) {
        EXPECT_LT(distance(arch.getNodePosition(plant, shoot, k), points[k + 1]), 1e-5f) << k;
        EXPECT_TRUE(!s.phytomers[k].internode.bend || s.phytomers[k].internode.bend->angle == 0.0f)
            << k;
    }
    // The growth after them bends (the solve ran): its nodes hang below where they grew.
    bool bent = false;
    for (std::size_t k = 3; k < s.phytomers.size(); ++k)
        bent =
            bent || (s.phytomers[k].internode.bend && s.phytomers[k].internode.bend->angle > 1.0f);
    EXPECT_TRUE(bent);
}
