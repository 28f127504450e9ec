// Trellises drawn with trellis species: posts and wires where the species file puts them,
// labelled, outside the plant's own objects, switched off on request, one per canopy plant,
// deleted with their plant; and the species file's <trellis> read, written and checked.

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli_run.h"
#include "error_of.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

AABB boxOf(const Context& ctx, ObjectID id) {
    AABB b;
    for (const vec3& p : ctx.object(id).positions) b.add(p);
    return b;
}

std::vector<ObjectID> parts(const Context& ctx, const std::vector<ObjectID>& ids,
                            const std::string& kind) {
    std::vector<ObjectID> out;
    for (ObjectID id : ids)
        if (ctx.objectDataString(id, "trellis_part") == kind) out.push_back(id);
    return out;
}

}  // namespace

// The Wye vine with its defaults (vine_spacing 1.8, cordon_spacing 0.6, catch_wire_height 2.1,
// trunk_height 0.165): one post at x = 0.9 up to 2.1 - 0.95 = 1.15 m, two arms and six wires
// along the row from x = -0.9 to 0.9 (the fruiting wires at y = -/+0.3, z = 1.75), and a
// cross-arm carrying two cordon wires at y = -/+0.3, z = 0.165 + 0.3 - 0.025 = 0.44, on which
// the cordons rest (docs: the species file).
TEST(Trellis, WyePostsAndWiresStandWhereTheSpeciesFileSays) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("grapevine_Wye");
    const vec3 base(2.0f, 1.0f, 0.0f);
    const unsigned p = arch.buildPlantInstanceFromLibrary(base, 100.0f);
    const std::vector<ObjectID> t = arch.getPlantTrellisObjectIDs(p);
    ASSERT_EQ(t.size(), 12u);
    for (ObjectID id : t) {
        EXPECT_EQ(ctx.objectDataString(id, "organ"), "trellis");
        EXPECT_EQ(ctx.objectDataInt(id, "plantID"), int(p));
        EXPECT_EQ(ctx.objectDataString(id, "plant_name"), "grapevine_Wye");
    }
    const std::vector<ObjectID> posts = parts(ctx, t, "post"), wires = parts(ctx, t, "wire");
    ASSERT_EQ(posts.size(), 1u);
    ASSERT_EQ(wires.size(), 11u);
    const AABB post = boxOf(ctx, posts[0]);
    EXPECT_NEAR(post.center().x, base.x + 0.9f, 1e-4f);
    EXPECT_NEAR(post.center().y, base.y, 1e-4f);
    EXPECT_NEAR(post.min.z, 0.0f, 1e-5f);
    EXPECT_NEAR(post.max.z, 1.15f, 1e-4f);
    EXPECT_NEAR(post.extent().x, 0.08f, 1e-3f);  // radius 0.04
    // The fruiting wires.
    int fruiting = 0;
    for (ObjectID id : wires) {
        const AABB w = boxOf(ctx, id);
        if (std::abs(w.center().z - 1.75f) < 1e-3f &&
            std::abs(std::abs(w.center().y - base.y) - 0.3f) < 1e-3f) {
            ++fruiting;
            EXPECT_NEAR(w.min.x, base.x - 0.9f, 0.003f);
            EXPECT_NEAR(w.max.x, base.x + 0.9f, 0.003f);
            EXPECT_NEAR(w.extent().z, 0.004f, 1e-3f);  // radius 0.002
        }
    }
    EXPECT_EQ(fruiting, 2);
    // The cordon wires, and every node of the four cordons within 5 cm above one of them (the
    // arms' pitch varies by 3 degrees, the cordons' height with it).
    std::vector<AABB> cordonWires;
    for (ObjectID id : wires) {
        const AABB w = boxOf(ctx, id);
        if (std::abs(w.center().z - 0.44f) < 1e-3f && w.extent().x > 1.7f) cordonWires.push_back(w);
    }
    ASSERT_EQ(cordonWires.size(), 2u);
    unsigned cordonNodes = 0;
    for (const Shoot& s : arch.plant(p).shoots) {
        if (s.type != "grapevine_cordon") continue;
        for (unsigned k = 0; k < s.phytomers.size(); ++k) {
            const vec3 n = arch.getNodePosition(p, s.id, k);
            bool resting = false;
            for (const AABB& w : cordonWires)
                resting = resting ||
                          (std::abs(n.y - w.center().y) < 0.03f && n.z > w.max.z - 1e-3f &&
                           n.z < w.max.z + 0.05f && n.x > w.min.x - 0.03f && n.x < w.max.x + 0.03f);
            EXPECT_TRUE(resting) << "cordon " << s.id << " node " << k << " at " << n.x << " "
                                 << n.y << " " << n.z;
            ++cordonNodes;
        }
    }
    EXPECT_EQ(cordonNodes, 4u * 8u);
    // Build parameters move it: a higher catch wire lifts the top wires.
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    arch2.loadPlantModelFromLibrary("grapevine_Wye");
    const unsigned q =
        arch2.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f, {{"catch_wire_height", 2.5f}});
    float top = 0.0f;  // the highest wire along the row: the second catch wires
    for (ObjectID id : arch2.getPlantTrellisObjectIDs(q))
        if (boxOf(ctx2, id).extent().x > 1.0f) top = std::max(top, boxOf(ctx2, id).center().z);
    EXPECT_NEAR(top, 2.5f, 1e-4f);
}

// The trellis is scene, not plant: the plant's objects, height and geometry are the same with
// and without it, and without it there are no trellis objects at all.
TEST(Trellis, IsNotPartOfThePlantAndCanBeLeftOut) {
    std::string bytes[2];
    float height[2];
    for (bool on : {true, false}) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("apple_fruitingwall");
        arch.setTrellisGeometry(on);
        EXPECT_EQ(arch.getTrellisGeometry(), on);
        const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 200.0f);
        const std::vector<ObjectID> t = arch.getPlantTrellisObjectIDs(p);
        EXPECT_EQ(t.size(), on ? 5u : 0u);
        EXPECT_EQ(ctx.objectCount(), arch.getAllPlantObjectIDs(p).size() + t.size());
        for (ObjectID id : arch.getAllPlantObjectIDs(p))
            EXPECT_EQ(std::find(t.begin(), t.end(), id), t.end());
        bytes[on] = plantarch::testing::organBytes(arch, {p});
        height[on] = arch.getPlantHeight(p);
    }
    EXPECT_EQ(bytes[0], bytes[1]);
    EXPECT_EQ(height[0], height[1]);
}

// A canopy: every plant its own trellis at its own base, the same for one and two threads;
// deleting a plant deletes its trellis.
TEST(Trellis, OnePerCanopyPlantAndDeletedWithIt) {
    std::string scene[2];
    for (int threads : {1, 2}) {
        const int before = omp_get_max_threads();
        omp_set_num_threads(threads);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("grapevine_VSP");
        const std::vector<unsigned> ids =
            arch.buildPlantCanopyFromLibrary(vec3(0.0f), {3.0f, 2.4f}, {1, 3}, 30.0f);
        omp_set_num_threads(before);
        ASSERT_EQ(ids.size(), 3u);
        for (unsigned id : ids) {
            const std::vector<ObjectID> t = arch.getPlantTrellisObjectIDs(id);
            ASSERT_EQ(t.size(), 6u);
            const AABB post = boxOf(ctx, parts(ctx, t, "post").at(0));
            const vec3 b = arch.getPlantBasePosition(id);
            EXPECT_NEAR(post.center().x, b.x, 1e-4f);
            EXPECT_NEAR(post.center().y, b.y + 1.2f, 1e-4f);  // y = vine_spacing / 2
            scene[threads - 1] += std::to_string(t.size());
            for (ObjectID o : t) {
                const auto v = ctx.object(o).positions;
                scene[threads - 1].append(reinterpret_cast<const char*>(v.data()), v.size_bytes());
            }
        }
        const std::vector<ObjectID> gone = arch.getPlantTrellisObjectIDs(ids[1]);
        arch.deletePlantInstance(ids[1]);
        for (ObjectID o : gone) EXPECT_FALSE(ctx.doesObjectExist(o));
        EXPECT_EQ(arch.getPlantTrellisObjectIDs(ids[0]).size(), 6u);
    }
    EXPECT_EQ(scene[0], scene[1]);
}

TEST(Trellis, SpeciesFilesReadWriteAndCheckIt) {
    const SpeciesModel wye = loadSpecies("grapevine_Wye");
    ASSERT_TRUE(wye.trellis);
    EXPECT_EQ(wye.trellis->posts.size(), 1u);
    EXPECT_EQ(wye.trellis->wires.size(), 11u);
    const SpeciesModel again = readSpeciesString(writeSpeciesString(wye), "wye");
    ASSERT_TRUE(again.trellis);
    EXPECT_EQ(writeSpeciesString(again), writeSpeciesString(wye));

    std::string text = writeSpeciesString(wye);
    auto withTrellis = [&](const std::string& body) {
        const auto a = text.find("<trellis>"), b = text.find("</trellis>");
        return text.substr(0, a) + "<trellis>\n" + body + "\n  " + text.substr(b);
    };
    auto readError = [&](const std::string& body) {
        return errorOf([&] { readSpeciesString(withTrellis(body), "mine.xml"); });
    };
    EXPECT_NE(std::string(readError(R"(<post at="0, 0, 1" height="2"/>)").what())
                  .find("expected two expressions x, y separated by commas"),
              std::string::npos);
    EXPECT_EQ(readError(R"(<post at="0, 0"/>)").parameter(), "trellis.post[1].height");
    EXPECT_NE(std::string(readError(R"(<post at="0, nosuch" height="2"/>)").what()).find("nosuch"),
              std::string::npos);
    EXPECT_NE(std::string(readError(R"(<beam at="0, 0"/>)").what()).find("beam"),
              std::string::npos);
    // Values checked when a plant is built: before it is made.
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::string path = ::testing::TempDir() + "/bad_trellis.xml";
    writeSpeciesFile(readSpeciesString(withTrellis(R"(<post at="0, 0" height="-1"/>)"), "mine.xml"),
                     path);
    arch.loadPlantModelFromLibrary(path);
    const Error e = errorOf([&] { arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f); });
    EXPECT_EQ(e.parameter(), "trellis.post[1].height");
    EXPECT_EQ(e.validRange(), "> 0 and <= 100 m");
    EXPECT_EQ(ctx.objectCount(), 0u);
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
}

TEST(Trellis, CommandLineDrawsItUnlessAskedNot) {
    const std::string d = ::testing::TempDir();
    for (bool off : {false, true}) {
        const std::string out = d + "/vsp" + (off ? "_off" : "") + ".obj";
        const cli::Result r =
            cli::run("build grapevine_VSP --age 10 -o " + out + (off ? " --no-trellis" : ""));
        ASSERT_EQ(r.status, 0) << r.out;
        const std::string obj = plantarch::testing::fileBytes(out);
        EXPECT_EQ(obj.find("_trellis") != std::string::npos, !off) << out;
    }
}
