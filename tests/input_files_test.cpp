// Input files: FIFOs, devices, folders and files over their size limit are refused before a
// byte is read, naming the file; paths named inside a file (textures, OBJ models, mtllib) are
// resolved from that file and checked like the file itself; images are decoded before
// anything embeds them. Every call that used to hang runs under a time limit, so a
// regression fails instead of stopping the suite.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <string>

#include "cli_run.h"
#include "core/image_file.h"
#include "core/input_file.h"
#include "error_of.h"
#include "folder_test.h"
#include "plantarch/Collision.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Project.h"
#include "plantarch/Render.h"
#include "plantarch/SpeciesIO.h"

using plantarch::testing::errorOf;
namespace pa = plantarch;

namespace {

// Runs fn; a call still running after 60 s is a hang: the test fails and the process ends
// (a thread blocked in read() cannot be stopped).
template <class F>
void withinTimeLimit(F&& fn) {
    auto done = std::async(std::launch::async, std::forward<F>(fn));
    if (done.wait_for(std::chrono::seconds(60)) == std::future_status::timeout) {
        std::fprintf(stderr, "FAILED: an input was still being read after 60 s (a hang)\n");
        std::fflush(stderr);
        std::_Exit(1);
    }
    done.get();
}

// A species with one shoot type whose stem texture is `texture`; the texture's line is 7.
std::string texturedSpecies(const std::string& texture) {
    return R"(<?xml version="1.0" encoding="UTF-8"?>
<plantarch_species format="1">
  <name>textured</name>
  <shoot_type label="stem">
    <phytomer>
      <internode>
        <image_texture>)" +
           texture + R"(</image_texture>
      </internode>
    </phytomer>
  </shoot_type>
  <build>
    <base_stem type="stem" nodes="3"/>
  </build>
</plantarch_species>
)";
}

// A 2 x 2 PNG.
std::string smallPNG() {
    pa::Image image(2, 2);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = std::uint8_t(40 * i);
    return pa::encodePNG(image);
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

class InputFiles : public FolderTest {
protected:
    InputFiles() : FolderTest("plantarch_input_files_") {}

    std::string fifo(const std::string& name) {
        EXPECT_EQ(::mkfifo(at(name).c_str(), 0600), 0);
        return at(name);
    }
    // A file of `bytes` bytes that takes no room (a hole).
    std::string sparse(const std::string& name, std::uint64_t bytes) {
        const int fd = ::open(at(name).c_str(), O_CREAT | O_WRONLY | O_CLOEXEC, 0600);
        EXPECT_GE(fd, 0);
        EXPECT_EQ(::ftruncate(fd, off_t(bytes)), 0);
        ::close(fd);
        return at(name);
    }
};

}  // namespace

TEST_F(InputFiles, FifoIsRefusedByEveryReaderWithoutWaiting) {
    const std::string f = fifo("input.fifo");
    withinTimeLimit([&] {
        EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesFile(f); }).what()),
                  f + ": is a FIFO, not a species file");
        const std::vector<pa::Error> errors = pa::checkSpeciesFile(f);
        ASSERT_EQ(errors.size(), 1u);
        EXPECT_EQ(std::string(errors[0].what()), f + ": is a FIFO, not a species file");
        pa::Context ctx;
        EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, f); }).what()),
                  f + ": is a FIFO, not an OBJ file");
        EXPECT_EQ(std::string(errorOf([&] { pa::readAttractionPointsCSV(f, "points"); }).what()),
                  f + ": is a FIFO, not an attraction point file");
        EXPECT_EQ(std::string(errorOf([&] { pa::readImage(f); }).what()),
                  f + ": is a FIFO, not an image file");
        EXPECT_EQ(std::string(errorOf([&] { pa::readProjectFile(f); }).what()),
                  f + ": is a FIFO, not a project file");
        pa::PlantArchitecture arch(&ctx);
        EXPECT_EQ(std::string(errorOf([&] { arch.readPlantStructureXML(f); }).what()),
                  f + ": is a FIFO, not a plant structure file");
        EXPECT_EQ(std::string(errorOf([&] { arch.loadPlantModelFromLibrary(f); }).what()),
                  f + ": is a FIFO, not a species file");
    });
}

TEST_F(InputFiles, DevicesAndFoldersAreRefused) {
    withinTimeLimit([&] {
        for (const std::string device : {"/dev/zero", "/dev/null", "/dev/urandom"}) {
            EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesFile(device); }).what()),
                      device + ": is a device, not a species file");
            pa::Context ctx;
            EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, device); }).what()),
                      device + ": is a device, not an OBJ file");
            EXPECT_EQ(std::string(errorOf([&] { pa::readImage(device); }).what()),
                      device + ": is a device, not an image file");
        }
        // A link to a device is the device.
        std::filesystem::create_symlink("/dev/zero", at("plant.xml"));
        pa::Context ctx;
        pa::PlantArchitecture arch(&ctx);
        EXPECT_EQ(std::string(errorOf([&] { arch.readPlantStructureXML(at("plant.xml")); }).what()),
                  at("plant.xml") + ": is a device, not a plant structure file");
    });
    EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesFile(dir_.string()); }).what()),
              dir_.string() + ": is a directory, not a species file");
    pa::Context ctx;
    EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, dir_.string()); }).what()),
              dir_.string() + ": is a directory, not an OBJ file");
}

TEST_F(InputFiles, FilesOverTheirLimitAreRefusedBeforeReading) {
    const std::string species = sparse("big.xml", 16 * pa::io::kMiB + 1);
    EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesFile(species); }).what()),
              species +
                  ": too large for a species file: 16.0 MiB (16777217 bytes) (valid: at most 16 "
                  "MiB)");
    const std::string obj = sparse("big.obj", 4096 * pa::io::kMiB + 1);
    pa::Context ctx;
    EXPECT_EQ(
        std::string(errorOf([&] { pa::readOBJ(ctx, obj); }).what()),
        obj + ": too large for an OBJ file: 4.0 GiB (4294967297 bytes) (valid: at most 4 GiB)");
    const std::string image = sparse("big.png", 256 * pa::io::kMiB + 1);
    EXPECT_NE(std::string(errorOf([&] { pa::readImage(image); }).what())
                  .find(": too large for an image file: 256.0 MiB"),
              std::string::npos);
    // At the limit is fine as far as size goes (then the content is read).
    const std::string atLimit = sparse("limit.xml", 16 * pa::io::kMiB);
    EXPECT_NE(std::string(errorOf([&] { pa::readSpeciesFile(atLimit); }).what()).find("binary"),
              std::string::npos);
}

TEST(InputFileSizes, AreWrittenForPeople) {
    EXPECT_EQ(pa::io::sizeText(0), "0 bytes");
    EXPECT_EQ(pa::io::sizeText(1), "1 byte");
    EXPECT_EQ(pa::io::sizeText(1024), "1 KiB");
    EXPECT_EQ(pa::io::sizeText(1536), "1.5 KiB (1536 bytes)");
    EXPECT_EQ(pa::io::sizeText(256 * pa::io::kMiB), "256 MiB");
    EXPECT_EQ(pa::io::sizeText(4096 * pa::io::kMiB), "4 GiB");
}

TEST_F(InputFiles, TextThatIsNotUtf8IsNamed) {
    put(at("bom.xml"), std::string("\xFF\xFE<\0?\0", 6));
    EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesFile(at("bom.xml")); }).what()),
              at("bom.xml") +
                  ": is UTF-16 text; plantarch reads species files as UTF-8 (save it "
                  "as UTF-8)");
    put(at("le.obj"), std::string("v\0 \0"
                                  "0\0",
                                  6));
    pa::Context ctx;
    EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, at("le.obj")); }).what()),
              at("le.obj") +
                  ": is UTF-16 text; plantarch reads OBJ files as UTF-8 (save it as "
                  "UTF-8)");
    put(at("nul.obj"), kTriangle + "f 1 2 3\n# \0 here\n" + std::string(1, '\0'));
    EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, at("nul.obj")); }).what()),
              at("nul.obj") + ":5: binary data (a NUL byte), not an OBJ file");
    EXPECT_EQ(ctx.objectCount(), 0u);
}

TEST_F(InputFiles, TextureThatIsNoImageIsRefusedNamingTheSpeciesLine) {
    put(at("passwd"), "root:x:0:0:root:/root:/bin/bash\n");
    put(at("s.xml"), texturedSpecies("passwd"));
    const pa::SpeciesModel model = pa::readSpeciesFile(at("s.xml"));  // reading names no file
    const std::vector<pa::Error> errors = pa::checkSpeciesFiles(model);
    ASSERT_EQ(errors.size(), 1u);
    const std::string expected = at("s.xml") +
                                 ":7: stem.phytomer.internode.image_texture = " + at("passwd") +
                                 ": not an image: no PNG, JPEG or other image header (valid: a "
                                 "PNG or JPEG image)";
    EXPECT_EQ(std::string(errors[0].what()), expected);
    pa::Context ctx;
    pa::PlantArchitecture arch(&ctx);
    EXPECT_EQ(std::string(errorOf([&] { arch.loadPlantModelFromLibrary(at("s.xml")); }).what()),
              expected);

    const std::string f = fifo("bark.fifo");
    withinTimeLimit([&] {
        for (const auto& [texture, why] :
             {std::pair<std::string, std::string>{"/dev/zero", "is a device, not a texture image"},
              {"bark.fifo", "is a FIFO, not a texture image"},
              {".", "is a directory, not a texture image"}}) {
            put(at("s.xml"), texturedSpecies(texture));
            const std::vector<pa::Error> e =
                pa::checkSpeciesFiles(pa::readSpeciesFile(at("s.xml")));
            ASSERT_EQ(e.size(), 1u) << texture;
            EXPECT_EQ(e[0].message(), why);
            EXPECT_EQ(e[0].line(), 7);
        }
    });
    // A PNG header claiming more pixels than any texture may have is refused undecoded.
    std::string huge = smallPNG();
    huge[16] = 0, huge[17] = 0, huge[18] = 0x4E, huge[19] = 0x20;  // width 20000
    put(at("huge.png"), huge);
    EXPECT_EQ(std::string(errorOf([&] { pa::io::readTextureFile(at("huge.png")); }).what()),
              at("huge.png") +
                  ": '20000 x 2 pixels': image too large (valid: at most 16384 "
                  "pixels a side)");
}

TEST_F(InputFiles, TexturePathsAreRelativeToTheSpeciesFile) {
    std::filesystem::create_directories(at("sp"));
    put(at("sp/s.xml"), texturedSpecies("bark.png"));
    const std::string png = smallPNG();
    put(at("sp/bark.png"), png);
    const pa::SpeciesModel model = pa::readSpeciesFile(at("sp/s.xml"));
    EXPECT_TRUE(pa::checkSpeciesFiles(model).empty());
    EXPECT_EQ(pa::speciesShootTypes(model).at("stem").phytomer_parameters.internode.image_texture,
              at("sp/bark.png"));
    // The model keeps the path as written: it writes back unchanged.
    EXPECT_NE(pa::writeSpeciesString(model).find("<image_texture>bark.png</image_texture>"),
              std::string::npos);

    pa::Context ctx;
    pa::PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary(at("sp/s.xml"));
    arch.buildPlantInstanceFromLibrary(pa::vec3(0.0f), 3.0f);
    bool textured = false;
    for (pa::MaterialID m = 0; m < ctx.materialCount(); ++m)
        textured = textured || ctx.material(m).texture == at("sp/bark.png");
    EXPECT_TRUE(textured);
    pa::writeGLTF(ctx, at("plant.glb"));
    EXPECT_NE(bytes(at("plant.glb")).find(png), std::string::npos);  // embedded as it is

    // From the command line, with the species named from another folder.
    const std::string cd = "cd '" + dir_.string() + "' && ";
    const cli::Result r =
        cli::runShell(cd + PLANTARCH_CLI + " build sp/s.xml --age 3 -o out.glb 2>&1");
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(bytes(at("out.glb")).find(png), std::string::npos);
    const cli::Result v = cli::runShell("cd / && " + std::string(PLANTARCH_CLI) + " validate '" +
                                        at("sp/s.xml") + "' 2>&1");
    EXPECT_EQ(v.status, 0) << v.out;
}

TEST_F(InputFiles, GlbEmbedsOnlyTexturesThatDecode) {
    put(at("secret.txt"), "-----BEGIN PRIVATE KEY-----\n");
    pa::Context ctx;
    pa::Mesh mesh;
    mesh.positions = {pa::vec3(0, 0, 0), pa::vec3(1, 0, 0), pa::vec3(0, 1, 0)};
    mesh.uvs = {pa::vec2(0, 0), pa::vec2(1, 0), pa::vec2(0, 1)};
    mesh.indices = {0, 1, 2};
    ctx.addObject(mesh, pa::Material{pa::vec3(1.0f), at("secret.txt"), "leak"});
    EXPECT_EQ(std::string(errorOf([&] { pa::writeGLTF(ctx, at("out.glb")); }).what()),
              at("secret.txt") +
                  ": not an image: no PNG, JPEG or other image header (valid: a "
                  "PNG or JPEG image)");
    EXPECT_FALSE(std::filesystem::exists(at("out.glb")));
    pa::Context devices;
    devices.addObject(mesh, pa::Material{pa::vec3(1.0f), "/dev/zero", "zero"});
    withinTimeLimit([&] {
        EXPECT_EQ(std::string(errorOf([&] { pa::writeGLTF(devices, at("out.gltf")); }).what()),
                  "/dev/zero: is a device, not a texture image");
    });
}

TEST_F(InputFiles, MtllibIsReadAsAnInputFileNamedFromTheObj) {
    put(at("zero.obj"), "mtllib /dev/zero\n" + kTriangle + "f 1 2 3\n");
    fifo("m.fifo");
    put(at("fifo.obj"), kTriangle + "mtllib m.fifo\nf 1 2 3\n");
    sparse("big.mtl", 64 * pa::io::kMiB + 1);
    put(at("big.obj"), kTriangle + "\nmtllib big.mtl\nf 1 2 3\n");
    withinTimeLimit([&] {
        pa::Context ctx;
        EXPECT_EQ(std::string(errorOf([&] { pa::readOBJ(ctx, at("zero.obj")); }).what()),
                  at("zero.obj") + ":1: mtllib = /dev/zero: is a device, not a material file");
        EXPECT_EQ(
            std::string(errorOf([&] { pa::readOBJ(ctx, at("fifo.obj")); }).what()),
            at("fifo.obj") + ":4: mtllib = " + at("m.fifo") + ": is a FIFO, not a material file");
        EXPECT_EQ(std::string(errorOf([&] { pa::readObstacleMesh(ctx, at("big.obj")); }).what()),
                  at("big.obj") + ":5: mtllib = " + at("big.mtl") +
                      ": too large for a material file: 64.0 MiB (67108865 bytes) (valid: at "
                      "most 64 MiB)");
        EXPECT_EQ(ctx.objectCount(), 0u);
        // The command line, under a time limit of its own.
        const cli::Result r = cli::runShell("cd '" + dir_.string() + "' && timeout 60 " +
                                            PLANTARCH_CLI + " render zero.obj -o out.png 2>&1");
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_EQ(r.out,
                  "plantarch: zero.obj:1: mtllib = /dev/zero: is a device, not a material "
                  "file\n");
    });
    // A .mtl that is not there is a warning, as before: the default material.
    put(at("missing.obj"), "mtllib nowhere.mtl\n" + kTriangle + "f 1 2 3\n");
    std::vector<std::string> warnings;
    pa::Context ctx;
    pa::readOBJ(ctx, at("missing.obj"),
                {.onWarning = [&](const std::string& w) { warnings.push_back(w); }});
    EXPECT_EQ(ctx.objectCount(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0],
              "material file " + at("nowhere.mtl") + " not found: default material used");
}

TEST_F(InputFiles, BadFaceIndicesNameTheirLine) {
    pa::Context ctx;
    auto message = [&](const std::string& text) {
        put(at("f.obj"), text);
        return std::string(errorOf([&] { pa::readOBJ(ctx, at("f.obj")); }).what());
    };
    EXPECT_EQ(message(kTriangle + "f 1 2 0\n"),
              at("f.obj") +
                  ":4: f = 0: vertex index 0: OBJ indices start at 1 (valid: 1 to 3, "
                  "or -3 to -1)");
    EXPECT_EQ(message(kTriangle + "f 1 2 3\nf 1 2 7\n"),
              at("f.obj") + ":5: f = 7: vertex index out of range (valid: 1 to 3, or -3 to -1)");
    EXPECT_EQ(message(kTriangle + "vt 0 0\nf 1/1 2/1 3/0\n"),
              at("f.obj") +
                  ":5: f = 3/0: texture coordinate index 0: OBJ indices start at 1 "
                  "(valid: 1 to 1, or -1 to -1)");
    EXPECT_EQ(message("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"),
              at("f.obj") +
                  ":3: f = -3: vertex index out of range (counted back from this "
                  "line) (valid: 1 to 3, or -2 to -1)");
    EXPECT_EQ(message(kTriangle + "l 1 0\n"),
              at("f.obj") +
                  ":4: l = 0: vertex index 0: OBJ indices start at 1 (valid: 1 to 3, "
                  "or -3 to -1)");
    EXPECT_EQ(ctx.objectCount(), 0u);
}

TEST_F(InputFiles, ObjModelThatIsNoObjIsNamedWithItsSpeciesLine) {
    put(at("leaf.obj"), smallPNG());
    put(at("s.xml"), R"(<?xml version="1.0" encoding="UTF-8"?>
<plantarch_species format="1">
  <name>modelled</name>
  <shoot_type label="stem">
    <phytomer>
      <leaf>
        <prototype>
          <OBJ_model_file>leaf.obj</OBJ_model_file>
        </prototype>
      </leaf>
    </phytomer>
  </shoot_type>
  <build>
    <base_stem type="stem" nodes="3"/>
  </build>
</plantarch_species>
)");
    const std::vector<pa::Error> errors = pa::checkSpeciesFiles(pa::readSpeciesFile(at("s.xml")));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(std::string(errors[0].what()),
              at("s.xml") + ":8: stem.phytomer.leaf.prototype.OBJ_model_file = " + at("leaf.obj") +
                  ": is a PNG image, not an OBJ file (valid: an OBJ file)");
}

TEST(InputXml, NulCharacterReferencesAndTextAfterTheRootAreRefused) {
    const std::string good = texturedSpecies("bark.png");
    std::string nul = good;
    nul.replace(nul.find("textured"), 8, "text&#x0;ured");
    EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesString(nul, "s.xml"); }).what()),
              "s.xml:3: '&#x0;': a character reference to a character XML does not allow (a NUL "
              "or control character) (valid: &#9;, &#10;, &#13; or &#32; and above)");
    std::string label = good;
    label.replace(label.find("label=\"stem\""), 12, "label=\"st&#0;em\"");
    EXPECT_EQ(errorOf([&] { pa::readSpeciesString(label, "s.xml"); }).line(), 4);
    // In a comment it is only text.
    EXPECT_NO_THROW(pa::readSpeciesString(good + "<!-- &#0; -->\n", "s.xml"));
    EXPECT_EQ(
        std::string(errorOf([&] { pa::readSpeciesString(good + "\n\nmore", "s.xml"); }).what()),
        "s.xml:17: 'more': text outside the root element");
    EXPECT_EQ(std::string(errorOf([&] { pa::readSpeciesString(good + "&amp;", "s.xml"); }).what()),
              "s.xml:15: '&': text outside the root element");
}
