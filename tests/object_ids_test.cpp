// Object IDs through a save and restore (docs/plant-xml.md, "Object IDs"): a plant file
// written with its object IDs, read into a fresh PlantArchitecture, gives objects with the
// same IDs, so OBJ (with its .mtl), PLY and glTF exports are the same bytes as the original's.

#include <gtest/gtest.h>

#include <filesystem>

#include "cli_run.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStructureWrite.h"

using namespace plantarch;
using plantarch::testing::fileBytes;
using plantarch::testing::firstDifference;

namespace {

namespace fs = std::filesystem;

fs::path folder(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("object_ids_" + name);
    fs::create_directories(d);
    return d;
}

// Every export format's bytes of the whole Context (the .mtl after the .obj).
std::string exports(const Context& ctx, const fs::path& dir) {
    fs::create_directories(dir);
    writeOBJ(ctx, (dir / "p.obj").string());
    writePLY(ctx, (dir / "p.ply").string());
    writeGLTF(ctx, (dir / "p.glb").string());
    return fileBytes((dir / "p.obj").string()) + fileBytes((dir / "p.mtl").string()) +
           fileBytes((dir / "p.ply").string()) + fileBytes((dir / "p.glb").string());
}

// Builds with `make`, writes the file with object IDs, reads it into a fresh Context and
// compares the exports.
template <class Make>
void expectSameExports(const std::string& name, const std::string& species, Make&& make) {
    SCOPED_TRACE(name);
    const fs::path dir = folder(name);
    Context a;
    PlantArchitecture archA(&a);
    archA.loadPlantModelFromLibrary(species);
    const std::vector<unsigned> ids = make(archA);
    PlantStructureWriteOptions with;
    with.objectIDs = true;
    const std::string text = getPlantStructureXML(archA, ids, with);
    EXPECT_NE(text.find("<object_ID>"), std::string::npos);
    EXPECT_EQ(archA.getPlantStructureXML(ids).find("<object_ID>"), std::string::npos)
        << "the default file holds no object IDs";

    Context b;
    PlantArchitecture archB(&b);
    const std::vector<unsigned> read = archB.readPlantStructureXMLString(text);
    ASSERT_EQ(read, ids);
    for (std::size_t i = 0; i < ids.size(); ++i)
        EXPECT_EQ(archB.getAllPlantObjectIDs(read[i]), archA.getAllPlantObjectIDs(ids[i]));
    const std::string original = exports(a, dir / "a");
    EXPECT_GT(original.size(), 10000u);
    EXPECT_EQ(firstDifference(exports(b, dir / "b"), original), "");
    // Written again, the same file; grown on, the same plant as the original grown on.
    EXPECT_EQ(firstDifference(getPlantStructureXML(archB, read, with), text), "");
    archA.advanceTime(10.0);
    archB.advanceTime(10.0);
    EXPECT_EQ(firstDifference(archB.getPlantStructureXML(read), archA.getPlantStructureXML(ids)),
              "");
    fs::remove_all(dir);
}

}  // namespace

TEST(ObjectIDs, BeanKeepsItsObjectIDs) {
    expectSameExports("bean", "bean", [](PlantArchitecture& arch) {
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
        arch.advanceTime(15.0);  // objects made at two times, some deleted in between
        return std::vector<unsigned>{id};
    });
}

TEST(ObjectIDs, AlmondTreeKeepsItsObjectIDs) {
    expectSameExports("almond", "almond", [](PlantArchitecture& arch) {
        return std::vector<unsigned>{arch.buildPlantInstanceFromLibrary(vec3(0.0f), 630.0f)};
    });
}

TEST(ObjectIDs, CanopyKeepsItsObjectIDs) {
    expectSameExports("canopy", "cowpea", [](PlantArchitecture& arch) {
        const auto ids =
            arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.4f), glm::ivec2(3, 2), 25.0f);
        arch.advanceTime(10.0);
        return ids;
    });
}

TEST(ObjectIDs, TakenIDsGiveNewObjects) {
    Context a;
    PlantArchitecture archA(&a);
    archA.loadPlantModelFromLibrary("bean");
    const unsigned id = archA.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
    PlantStructureWriteOptions with;
    with.objectIDs = true;
    const std::string text = getPlantStructureXML(archA, {id}, with);
    // Read twice into one Context: the second copy finds its IDs taken and gets new ones, in
    // organ order after every ID issued; the first copy's objects are untouched.
    Context b;
    PlantArchitecture archB(&b);
    const unsigned first = archB.readPlantStructureXMLString(text).at(0);
    const std::vector<ObjectID> firstIDs = archB.getAllPlantObjectIDs(first);
    const ObjectID limit = b.objectIDLimit();
    const unsigned second = archB.readPlantStructureXMLString(text).at(0);
    EXPECT_EQ(archB.getAllPlantObjectIDs(first), firstIDs);
    const std::vector<ObjectID> secondIDs = archB.getAllPlantObjectIDs(second);
    ASSERT_EQ(secondIDs.size(), firstIDs.size());
    for (ObjectID o : secondIDs) EXPECT_GE(o, limit);
    EXPECT_EQ(plantarch::testing::organBytes(archB, {second}),
              plantarch::testing::organBytes(archB, {first}));
}

TEST(ObjectIDs, CommandLineRoundTripGivesTheSameOBJ) {
    // An OBJ names its material library after itself (mtllib a.mtl): the copy is written
    // under the same name in another folder, so that the whole files compare.
    const fs::path d = folder("cli");
    fs::create_directories(d / "copy");
    const std::string a = (d / "a").string();
    auto r = cli::run("build bean --age 40 --object-ids -o " + a + ".obj -o " + a + ".xml");
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("convert " + a + ".xml " + (d / "copy" / "a.obj").string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(firstDifference(fileBytes((d / "copy" / "a.obj").string()), fileBytes(a + ".obj")),
              "");
    EXPECT_EQ(firstDifference(fileBytes((d / "copy" / "a.mtl").string()), fileBytes(a + ".mtl")),
              "");
    // Without --object-ids the file holds no IDs, and the copy's objects are numbered anew.
    r = cli::run("build bean --age 40 -o " + a + "2.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(fileBytes(a + "2.xml").find("object_ID"), std::string::npos);
    fs::remove_all(d);
}

// A plant built in one call (and a canopy) is drawn once, at its age, so its objects are made
// in organ order, as reading its file makes them: a default file, without IDs, gives the same
// exports too.
TEST(ObjectIDs, PlantsBuiltInOneCallNeedNoIDsInTheirFile) {
    for (const char* species : {"bean", "almond"}) {
        SCOPED_TRACE(species);
        const fs::path dir = folder(std::string("default_") + species);
        Context a;
        PlantArchitecture archA(&a);
        archA.loadPlantModelFromLibrary(species);
        std::vector<unsigned> ids = {archA.buildPlantInstanceFromLibrary(vec3(0.0f), 120.0f)};
        for (unsigned id : archA.buildPlantCanopyFromLibrary(vec3(3.0f, 0, 0), vec2(1.0f),
                                                             glm::ivec2(2, 2), 90.0f))
            ids.push_back(id);
        const std::string text = archA.getPlantStructureXML(ids);
        EXPECT_EQ(text.find("<object_ID>"), std::string::npos);
        Context b;
        PlantArchitecture archB(&b);
        ASSERT_EQ(archB.readPlantStructureXMLString(text), ids);
        const std::string original = exports(a, dir / "a");
        EXPECT_GT(original.size(), 10000u);
        EXPECT_EQ(firstDifference(exports(b, dir / "b"), original), "");
        fs::remove_all(dir);
    }
}
