// OBJ organ prototypes: the convention check, normalization, errors, and use on a plant.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "plantarch/Error.h"
#include "plantarch/OrganPrototypes.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

std::string writeFile(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::temp_directory_path() / "plantarch-objproto";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
}

// A two-material fruit: a body from x 0 to 1 and a stalk; `scale`/`shift` move it off the
// convention.
std::string fruitOBJ(const std::string& name, float scale, float shift) {
    auto v = [&](float x, float y, float z) {
        return "v " + std::to_string(x * scale + shift) + " " + std::to_string(y * scale) + " " +
               std::to_string(z * scale) + "\n";
    };
    writeFile(name + ".mtl", "newmtl skin\nKd 0.8 0.1 0.1\nnewmtl stalk\nKd 0.2 0.5 0.1\n");
    return writeFile(name + ".obj", "mtllib " + name + ".mtl\n" + v(0, 0, 0) + v(1, -0.3f, 0) +
                                        v(1, 0.3f, 0) + v(0.5f, 0, 0.4f) + v(0, 0, 0) +
                                        v(0.1f, 0.02f, 0) + v(0.1f, -0.02f, 0) +
                                        "usemtl skin\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
                                        "usemtl stalk\nf 5 6 7\n");
}

}  // namespace

TEST(OBJPrototype, AModelFollowingTheConventionLoadsWithItsMaterials) {
    const OrganPrototype p = loadOBJPrototype(fruitOBJ("good", 1.0f, 0.0f), false);
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0].mesh.triangleCount(), 4u);
    EXPECT_EQ(p[1].mesh.triangleCount(), 1u);
    EXPECT_NEAR(p[0].material.color.r, 0.8f, 1e-6f);
    EXPECT_NEAR(p[1].material.color.g, 0.5f, 1e-6f);
}

TEST(OBJPrototype, AModelOffTheConventionIsAnErrorUnlessNormalized) {
    const std::string path = fruitOBJ("big", 5.0f, 2.0f);  // x from 2 to 7
    try {
        loadOBJPrototype(path, false);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(e.value().find("x from 2 to 7"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("normalize_OBJ_model"), std::string::npos);
    }
    const OrganPrototype p = loadOBJPrototype(path, true);
    AABB box;
    for (const PrototypePart& part : p)
        for (const vec3& v : part.mesh.positions) box.add(v);
    EXPECT_NEAR(box.min.x, 0.0f, 1e-5f);
    EXPECT_NEAR(box.max.x, 1.0f, 1e-5f);
    EXPECT_NEAR(box.max.z, 0.4f, 1e-5f);  // scaled by 1/5 like the rest
}

TEST(OBJPrototype, MissingAndMalformedFilesAreErrorsNamingTheFile) {
    const std::string missing = "/nonexistent/fruit.obj";
    try {
        loadOBJPrototype(missing, true);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
    }
    const std::string bad = writeFile("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    EXPECT_THROW(loadOBJPrototype(bad, true), Error);
    const std::string empty = writeFile("empty.obj", "# nothing\n");
    EXPECT_THROW(loadOBJPrototype(empty, true), Error);
    EXPECT_TRUE(isOBJPrototypeName("a/b.obj"));
    EXPECT_FALSE(isOBJPrototypeName("berry"));
}

TEST(OBJPrototype, PlantsUseOBJFruitAndLeaves) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters s;
    s.phytomer_parameters.inflorescence.fruit_prototype_function =
        fruitOBJ("plantfruit", 3.0f, 1.0f);
    s.phytomer_parameters.inflorescence.normalize_OBJ_model = true;
    s.phytomer_parameters.inflorescence.fruit_prototype_scale = 0.04f;
    s.phytomer_parameters.leaf.prototype.OBJ_model_file = fruitOBJ("leafmodel", 1.0f, 0.0f);
    arch.defineShootType("main", s);
    const unsigned p = arch.addPlantInstance({0, 0, 0}, 0);
    arch.addBaseStemShoot(p, {2, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    arch.addFloralBud(p, 0, 1, FloralStage::Fruit);
    const auto fruit = arch.getPlantObjectIDs(p, OrganKind::Fruit);
    ASSERT_EQ(fruit.size(), 2u);  // body and stalk of one fruit
    AABB box;
    for (ObjectID id : fruit) box.add(ctx.objectBoundingBox(id));
    EXPECT_NEAR(std::max({box.extent().x, box.extent().y, box.extent().z}), 0.04f, 0.01f);
    EXPECT_EQ(arch.getPlantObjectIDs(p, OrganKind::Leaf).size(), 4u);  // two leaves, two parts each
    // A missing model is caught when the shoot type is defined.
    ShootParameters bad = s;
    bad.phytomer_parameters.leaf.prototype.OBJ_model_file = "/nonexistent/leaf.obj";
    try {
        arch.defineShootType("bad", bad);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "bad.phytomer.leaf.prototype.OBJ_model_file");
    }
}
