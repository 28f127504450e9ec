// Synthetic datasets (plantarch/Dataset.h): spec files read strictly, samples drawn as pure
// functions of (spec, index), and the files of a sample agreeing with each other: masks with
// COCO and the point cloud, keypoints with the camera, instances with the plant structure.

#include "plantarch/Dataset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "docs_images.h"
#include "error_of.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Export.h"
#include "plantarch/Render.h"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace plantarch;
using plantarch::testing::errorOf;

const std::string kTiny = std::string(PLANTARCH_SOURCE_DIR) + "/examples/datasets/tiny.json";

std::string scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / "plantarch-dataset" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

std::string slurp(const fs::path& p) {
    return plantarch::testing::fileBytes(p.string());
}

// The tiny example spec with `edit` applied to its JSON.
std::string specText(const std::function<void(json&)>& edit) {
    json j = json::parse(slurp(kTiny));
    edit(j);
    return j.dump();
}

Error specError(const std::function<void(json&)>& edit) {
    const std::string text = specText(edit);
    return errorOf([&] { readDatasetSpecString(text, "spec.json"); });
}

TEST(DatasetSpec, TheExampleSpecsReadAndCheck) {
    for (const char* name : {"tiny.json", "bean_rows.json"}) {
        const DatasetSpec s =
            readDatasetSpecFile(std::string(PLANTARCH_SOURCE_DIR) + "/examples/datasets/" + name);
        EXPECT_NO_THROW(checkDatasetSpec(s)) << name;
        EXPECT_FALSE(s.species.empty());
    }
}

TEST(DatasetSpec, EveryBadFieldGetsOneLineWithItsPathValueAndRange) {
    struct Case {
        std::function<void(json&)> edit;
        std::string parameter, message;
    };
    const std::vector<Case> cases = {
        {[](json& j) { j["sampels"] = 3; }, "sampels", "did you mean 'samples'"},
        {[](json& j) { j["samples"] = 0; }, "samples", "out of range"},
        {[](json& j) { j["samples"] = -5; }, "samples", "out of range"},
        {[](json& j) { j["samples"] = 1e300; }, "samples", "out of range"},
        {[](json& j) { j["plantarch_dataset"] = 2; }, "plantarch_dataset", "out of range"},
        {[](json& j) { j.erase("scene"); }, "scene", "missing"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = json::array({30, 10});
         },
         "scene/species/0/age", "lo is above hi"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = json::array({-1, 10});
         },
         "scene/species/0/age/0", "out of range"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = {{"normal", {20, -1}}};
         },
         "scene/species/0/age/normal/1", "out of range"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = {{"gamma", {2, 1}}};
         },
         "scene/species/0/age/gamma", "unknown field"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = {{"choice", {10, 20}}, {"weights", {1}}};
         },
         "scene/species/0/age/weights", "one weight per choice"},
        {[](json& j) {
             j["scene"]["species"][0]["age"] = {{"choice", {10, 20}}, {"weights", {0, 0}}};
         },
         "scene/species/0/age/weights", "sum to 0"},
        {[](json& j) {
             j["scene"]["layouts"][1]["rows"] = json::array({1.5, 2});
         },
         "scene/layouts/1/rows/0", "whole number"},
        {[](json& j) { j["scene"]["layouts"][1]["count"] = 3; }, "scene/layouts/1/count",
         "unknown field"},
        {[](json& j) { j["scene"]["layouts"][0]["layout"] = "spiral"; }, "scene/layouts/0/layout",
         "unknown layout"},
        {[](json& j) { j["camera"]["width"] = 0; }, "camera/width", "out of range"},
        {[](json& j) { j["camera"]["width"] = 100000; }, "camera/width", "out of range"},
        {[](json& j) { j["camera"]["pitch"] = 10; }, "camera/pitch", "unknown field"},
        {[](json& j) { j["camera"]["kind"] = "fisheye"; }, "camera/kind", "unknown camera kind"},
        {[](json& j) {
             j["camera"] = {{"kind", "trajectory"}, {"path", {{0, 0, 1}}}, {"target", {0, 0, 1}}};
         },
         "camera/path/0", "an eye point is the target"},
        {[](json& j) {
             j["outputs"] = {"rgb", "depht"};
         },
         "outputs/1", "did you mean 'depth'"},
        {[](json& j) {
             j["outputs"] = {"rgb", "rgb"};
         },
         "outputs/1", "named twice"},
        {[](json& j) {
             j["splits"] = {{"train", 0.5}, {"test", 0.2}};
         },
         "splits", "sum to"},
        {[](json& j) {
             j["splits"] = {{"tr ain", 1.0}};
         },
         "splits/tr ain", "split name"},
        {[](json& j) {
             j["lighting"] = {{"hour", {10, 25}}};
         },
         "lighting/hour/1", "out of range"},
        {[](json& j) {
             j["ground"] = {{"colors", {{0, 0, 0}}}};
         },
         "ground/colors", "two sRGB"},
        {[](json& j) { j["scene"]["weeds"]["probability"] = 1.5; }, "scene/weeds/probability",
         "out of range"},
    };
    for (const Case& c : cases) {
        const Error e = specError(c.edit);
        EXPECT_EQ(e.file(), "spec.json");
        EXPECT_EQ(e.parameter(), c.parameter) << e.what();
        EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

TEST(DatasetSpec, TextThatIsNotASpecIsRefused) {
    EXPECT_NE(
        std::string(errorOf([] { readDatasetSpecString("{", "a.json"); }).what()).find("a.json"),
        std::string::npos);
    EXPECT_NE(std::string(errorOf([] { readDatasetSpecString("[1, 2]", "a.json"); }).what())
                  .find("expected an object"),
              std::string::npos);
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_NO_FATAL_FAILURE(errorOf([&] { readDatasetSpecString(deep, "deep.json"); }));
    const std::string dir = scratch("spec-dir");
    EXPECT_NE(std::string(errorOf([&] { readDatasetSpecFile(dir); }).what()).find("directory"),
              std::string::npos);
}

TEST(DatasetSpec, ASpeciesFieldThatIsNotOneIsNamedByCheck) {
    const DatasetSpec s =
        readDatasetSpecString(specText([](json& j) {
                                  j["scene"]["species"][0]["species_parameters"] = {
                                      {"shoot_types.trifoliate.internode_lenght_max", 0.04}};
                              }),
                              "spec.json");
    const Error e = errorOf([&] { checkDatasetSpec(s); });
    EXPECT_EQ(e.parameter().rfind("scene/species/0/species_parameters/", 0), 0u) << e.what();
    const DatasetSpec b = readDatasetSpecString(
        specText([](json& j) {
            j["scene"]["species"][1]["build_parameters"] = {{"no_such_parameter", 1}};
        }),
        "spec.json");
    EXPECT_EQ(errorOf([&] { checkDatasetSpec(b); }).parameter(),
              "scene/species/1/build_parameters/no_such_parameter");
    const DatasetSpec u = readDatasetSpecString(
        specText([](json& j) { j["scene"]["species"][0]["species"] = "no_such_species"; }),
        "spec.json");
    EXPECT_EQ(errorOf([&] { checkDatasetSpec(u); }).parameter(), "scene/species/0/species");
}

TEST(DatasetDraw, ASampleIsAFunctionOfTheSpecAndItsIndexAlone) {
    const DatasetSpec spec = readDatasetSpecFile(kTiny);
    std::set<std::string> projects;
    std::map<std::string, int> splits;
    for (std::size_t i = 0; i < 400; ++i) {
        const DatasetSample a = drawDatasetSample(spec, i);
        const DatasetSample b = drawDatasetSample(spec, i);
        ASSERT_EQ(writeProjectString(a.project), writeProjectString(b.project));
        ASSERT_EQ(a.seed, b.seed);
        projects.insert(writeProjectString(a.project));
        ++splits[a.split];
        for (const ProjectBlock& block : a.project.blocks) {
            ASSERT_TRUE(block.age.has_value());
            if (block.name == "crop" && block.species == "bean") {
                EXPECT_GE(*block.age, 12.0f);
                EXPECT_LE(*block.age, 18.0f);
            }
            if (block.layout == ProjectBlock::Layout::Grid) {
                EXPECT_GE(block.count.y, 1);
                EXPECT_LE(block.count.y, 2);
                EXPECT_GE(block.count.x, 2);
                EXPECT_LE(block.count.x, 3);
            }
        }
    }
    EXPECT_EQ(projects.size(), 400u);
    // train 0.5, val 0.25, test 0.25 of 400: within five standard deviations (about 50).
    EXPECT_NEAR(splits["train"], 200, 50);
    EXPECT_NEAR(splits["val"], 100, 45);
    EXPECT_NEAR(splits["test"], 100, 45);
    // Another seed, other samples.
    DatasetSpec other = spec;
    other.seed = spec.seed + 1;
    EXPECT_NE(writeProjectString(drawDatasetSample(other, 3).project),
              writeProjectString(drawDatasetSample(spec, 3).project));
}

// Every file of a sample folder, by name.
std::map<std::string, std::string> folderBytes(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out[e.path().filename()] = slurp(e.path());
    return out;
}

TEST(DatasetSample, TheSameSampleHasTheSameBytesWhateverOrderOrRunMakesIt) {
    const DatasetSpec spec = readDatasetSpecFile(kTiny);
    const std::string a = scratch("order-a"), b = scratch("order-b");
    for (std::size_t i : {0, 1, 2, 3}) writeDatasetSample(spec, i, a);
    for (std::size_t i : {3, 1, 2, 0}) writeDatasetSample(spec, i, b);
    for (std::size_t i = 0; i < 4; ++i) {
        const std::string name = datasetSampleName(i);
        const auto fa = folderBytes(fs::path(a) / "samples" / name);
        const auto fb = folderBytes(fs::path(b) / "samples" / name);
        ASSERT_EQ(fa.size(), 14u)
            << name;  // every output but the scan (normals: two files), metadata
        for (const auto& [file, bytes] : fa)
            EXPECT_TRUE(fb.at(file) == bytes) << name << "/" << file;
    }
    EXPECT_FALSE(fs::exists(fs::path(a) / ".partial") && !fs::is_empty(fs::path(a) / ".partial"));
}

TEST(DatasetSample, AnExistingSampleIsAnErrorUnlessResumed) {
    const DatasetSpec spec = readDatasetSpecFile(kTiny);
    const std::string out = scratch("resume");
    const DatasetSampleResult first = writeDatasetSample(spec, 1, out);
    EXPECT_FALSE(first.skipped);
    EXPECT_GT(first.bytes, 0u);
    const std::string before = slurp(fs::path(out) / "samples" / "000001" / "rgb.png");
    const Error e = errorOf([&] { writeDatasetSample(spec, 1, out); });
    EXPECT_NE(std::string(e.what()).find("--resume"), std::string::npos);
    DatasetWriteOptions o;
    o.resume = true;
    EXPECT_TRUE(writeDatasetSample(spec, 1, out, o).skipped);
    EXPECT_EQ(slurp(fs::path(out) / "samples" / "000001" / "rgb.png"), before);
}

TEST(DatasetSample, AFailingSampleLeavesNoFolder) {
    // A triangle limit no scene fits in: the build stops, and no sample folder is left.
    DatasetSpec spec = readDatasetSpecFile(kTiny);
    spec.maxTriangles = 10;
    const std::string out = scratch("fails");
    const Error e = errorOf([&] { writeDatasetSample(spec, 0, out); });
    EXPECT_NE(std::string(e.what()).find("sample 000000"), std::string::npos) << e.what();
    EXPECT_FALSE(fs::exists(fs::path(out) / "samples" / "000000"));
    const fs::path partial = fs::path(out) / ".partial";
    EXPECT_TRUE(!fs::exists(partial) || fs::is_empty(partial));
}

TEST(DatasetSample, AShardsManifestAndTheMergeNameWhatIsMissing) {
    const DatasetSpec spec = readDatasetSpecFile(kTiny);
    const std::string out = scratch("merge");
    writeDatasetSample(spec, 0, out);
    writeDatasetSample(spec, 2, out);
    writeDatasetManifest(spec, out, 4, 0, 2);
    const json m = json::parse(slurp(fs::path(out) / "manifest-0-of-2.json"));
    ASSERT_EQ(m["entries"].size(), 2u);
    EXPECT_EQ(m["entries"][1]["sample"], 2);
    EXPECT_GT(m["entries"][1]["files"]["rgb.png"].get<int>(), 0);
    const Error e = errorOf([&] { mergeDataset(spec, out, 4); });
    EXPECT_NE(std::string(e.what()).find("2 of 4 samples are missing (1, 3)"), std::string::npos)
        << e.what();
    EXPECT_THROW(writeDatasetManifest(spec, out, 4, 1, 2), Error);
    EXPECT_THROW(datasetShard(4, 2, 2), Error);
    EXPECT_THROW(datasetShard(4, 0, 0), Error);
    writeDatasetSample(spec, 1, out);
    writeDatasetSample(spec, 3, out);
    mergeDataset(spec, out, 4);
    const json index = json::parse(slurp(fs::path(out) / "dataset.json"));
    ASSERT_EQ(index["entries"].size(), 4u);
    std::size_t images = 0;
    for (const auto& e : fs::directory_iterator(out)) {
        const std::string f = e.path().filename();
        if (f.rfind("coco_", 0) != 0) continue;
        const json c = json::parse(slurp(e.path()));
        for (const auto& image : c["images"]) {
            EXPECT_TRUE(fs::is_regular_file(fs::path(out) / image["file_name"].get<std::string>()));
            ++images;
        }
        std::set<int> ids;
        for (const auto& a : c["annotations"]) EXPECT_TRUE(ids.insert(a["id"].get<int>()).second);
    }
    EXPECT_EQ(images, 4u);
}

// ---- the files of one sample agree with each other ------------------------------------

struct Sample {
    fs::path dir;
    Image16 organ, plant;
    std::vector<std::uint8_t> semantic;
    std::vector<float> depth;
    json metadata, coco, camera, keypoints;
    int w = 0, h = 0;
};

std::vector<float> npyFloats(const fs::path& p) {
    const std::string bytes = slurp(p);
    const std::size_t header = 10 + (std::uint8_t(bytes[8]) | std::uint8_t(bytes[9]) << 8);
    std::vector<float> v((bytes.size() - header) / 4);
    std::memcpy(v.data(), bytes.data() + header, v.size() * 4);
    return v;
}

const Sample& madeSample() {
    static const Sample s = [] {
        DatasetSpec spec =
            readDatasetSpecString(specText([](json& j) {
                                      j["camera"]["width"] = 320;
                                      j["camera"]["height"] = 240;
                                      j["points"]["count"] = 20000;
                                      j["coco"] = {{"min_area", 0}};
                                      j["scene"]["layouts"] = {{{"layout", "rows"},
                                                                {"rows", 2},
                                                                {"plants_per_row", 2},
                                                                {"row_spacing", 0.4},
                                                                {"plant_spacing", 0.25}}};
                                  }),
                                  "spec.json", std::string(PLANTARCH_SOURCE_DIR));
        const std::string out = scratch("agree");
        writeDatasetSample(spec, 5, out);
        Sample s;
        s.dir = fs::path(out) / "samples" / "000005";
        s.organ = readImage16((s.dir / "organ_instances.png").string());
        s.plant = readImage16((s.dir / "plant_instances.png").string());
        const Image16 sem = readImage16((s.dir / "semantic.png").string());
        for (std::uint16_t v : sem.values) s.semantic.push_back(std::uint8_t(v / 257));
        s.depth = npyFloats(s.dir / "depth.npy");
        s.metadata = json::parse(slurp(s.dir / "metadata.json"));
        s.coco = json::parse(slurp(s.dir / "coco.json"));
        s.camera = json::parse(slurp(s.dir / "camera.json"));
        s.keypoints = json::parse(slurp(s.dir / "keypoints.json"));
        s.w = s.organ.width;
        s.h = s.organ.height;
        return s;
    }();
    return s;
}

TEST(DatasetSample, MasksAgreeWithTheInstanceTable) {
    const Sample& s = madeSample();
    ASSERT_EQ(s.w, 320);
    ASSERT_EQ(s.h, 240);
    const json& instances = s.metadata["instances"];
    const json& categories = s.metadata["categories"];
    ASSERT_GT(instances.size(), 20u);
    std::size_t seen = 0;
    for (std::size_t i = 0; i < s.organ.values.size(); ++i) {
        const int n = s.organ.values[i];
        if (n == 0) {
            EXPECT_EQ(s.plant.values[i], 0);
            EXPECT_EQ(s.semantic[i], 0);
            continue;
        }
        ++seen;
        ASSERT_LE(std::size_t(n), instances.size());
        const json& in = instances[std::size_t(n - 1)];
        ASSERT_EQ(in["instance"], n);
        ASSERT_EQ(s.plant.values[i], in["plant_instance"].get<int>());
        ASSERT_EQ(categories[s.semantic[i] - 1]["name"], in["category"]);
    }
    EXPECT_GT(seen, 1000u);
}

TEST(DatasetSample, COCOHasOneAnnotationPerObjectSeenWithTheMasksBoxAndArea) {
    const Sample& s = madeSample();
    // The masks' own boxes and areas.
    struct Box {
        int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
        std::size_t area = 0;
    };
    std::map<int, Box> organs, plants;
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(s.w) + std::size_t(x);
            for (const auto& [mask, boxes] :
                 {std::pair{&s.organ, &organs}, std::pair{&s.plant, &plants}}) {
                const int v = mask->values[i];
                if (v == 0) continue;
                Box& b = (*boxes)[v];
                b.x0 = std::min(b.x0, x);
                b.y0 = std::min(b.y0, y);
                b.x1 = std::max(b.x1, x);
                b.y1 = std::max(b.y1, y);
                ++b.area;
            }
        }
    std::size_t organNotes = 0, plantNotes = 0;
    for (const json& a : s.coco["annotations"]) {
        const bool plant = a["category_id"] == int(kOrganLabels.size());
        const Box& b =
            plant ? plants.at(a["plant_instance"].get<int>()) : organs.at(a["instance"].get<int>());
        (plant ? plantNotes : organNotes)++;
        EXPECT_EQ(a["area"].get<std::size_t>(), b.area);
        EXPECT_EQ(a["bbox"], json({b.x0, b.y0, b.x1 - b.x0 + 1, b.y1 - b.y0 + 1}));
        std::size_t total = 0, ones = 0;
        const auto counts = a["segmentation"]["counts"].get<std::vector<std::size_t>>();
        for (std::size_t k = 0; k < counts.size(); ++k) {
            total += counts[k];
            if (k % 2) ones += counts[k];
        }
        EXPECT_EQ(total, std::size_t(s.w * s.h));
        EXPECT_EQ(ones, b.area);
    }
    EXPECT_EQ(organNotes, organs.size());  // min_area 0: every object seen
    EXPECT_EQ(plantNotes, plants.size());
    EXPECT_EQ(s.coco["images"][0]["file_name"], "rgb.png");
    EXPECT_EQ(s.coco["info"]["seed"], s.metadata["seed"]);
}

TEST(DatasetSample, AMinimumAreaLeavesOutSmallerAnnotations) {
    DatasetSpec spec = readDatasetSpecFile(kTiny);
    spec.cocoMinArea = 40;
    const std::string out = scratch("min-area");
    writeDatasetSample(spec, 2, out);
    const json c = json::parse(slurp(fs::path(out) / "samples" / "000002" / "coco.json"));
    ASSERT_FALSE(c["annotations"].empty());
    for (const json& a : c["annotations"]) EXPECT_GE(a["area"].get<int>(), 40);
    const std::string yolo = slurp(fs::path(out) / "samples" / "000002" / "yolo.txt");
    EXPECT_EQ(std::size_t(std::count(yolo.begin(), yolo.end(), '\n')), c["annotations"].size());
}

TEST(DatasetSample, TheCameraMatricesProjectEachLeafTipOntoItsKeypoint) {
    const Sample& s = madeSample();
    const json& K = s.camera["K"];
    const json& E = s.camera["world_to_camera"];
    std::size_t seen = 0, onSurface = 0, onLeaf = 0, leaves = 0;
    for (const json& leaf : s.keypoints["leaves"]) {
        ++leaves;
        for (const char* point : {"base", "tip"}) {
            const json& p = leaf[point];
            double c[3];
            for (int r = 0; r < 3; ++r)
                c[r] = E[r][0].get<double>() * p["world"][0].get<double>() +
                       E[r][1].get<double>() * p["world"][1].get<double>() +
                       E[r][2].get<double>() * p["world"][2].get<double>() + E[r][3].get<double>();
            const double u = (K[0][0].get<double>() * c[0] + K[0][2].get<double>() * c[2]) / c[2];
            const double v = (K[1][1].get<double>() * c[1] + K[1][2].get<double>() * c[2]) / c[2];
            EXPECT_NEAR(u, p["pixel"][0].get<double>(), 1e-3);
            EXPECT_NEAR(v, p["pixel"][1].get<double>(), 1e-3);
            EXPECT_NEAR(c[2], p["depth"].get<double>(), 1e-4);
            if (p["visibility"] != 2) continue;
            ++seen;
            // Where the surface at the keypoint's pixel is at the keypoint's depth (not a thin
            // tip's background), a pixel within one of it shows the leaf; at an edge where two
            // leaves meet at one depth a neighbour may cover all nine, so not every one does.
            // Matrices off by a pixel would fail most.
            const int x = int(std::lround(u)), y = int(std::lround(v));
            const float at = s.depth[std::size_t(y) * std::size_t(s.w) + std::size_t(x)];
            if (std::abs(at - c[2]) > 0.003 + 0.01 * c[2]) continue;
            ++onSurface;
            bool found = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = std::clamp(x + dx, 0, s.w - 1),
                              yy = std::clamp(y + dy, 0, s.h - 1);
                    found |= s.organ.values[std::size_t(yy) * std::size_t(s.w) + std::size_t(xx)] ==
                             leaf["instance"].get<int>();
                }
            onLeaf += found;
        }
    }
    EXPECT_GT(leaves, 10u);
    EXPECT_GT(seen, 10u);
    EXPECT_GT(onSurface, 50u);
    EXPECT_GE(double(onLeaf), 0.95 * double(onSurface)) << onLeaf << " of " << onSurface;
}

TEST(DatasetSample, InstancesAreTheObjectsOfTheirPlantInThePlantStructure) {
    const Sample& s = madeSample();
    const std::string xml = slurp(s.dir / "plants.xml");
    // Each plant's part of the file, in the order the plants are listed.
    std::vector<std::string> parts;
    for (std::size_t at = xml.find("<plant_instance"); at != std::string::npos;) {
        const std::size_t next = xml.find("<plant_instance", at + 1);
        parts.push_back(xml.substr(at, next == std::string::npos ? std::string::npos : next - at));
        at = next;
    }
    ASSERT_EQ(parts.size(), s.metadata["plants"].size());
    for (const json& in : s.metadata["instances"]) {
        const int plant = in["plant_instance"];
        if (plant == 0) continue;
        const std::string id = std::to_string(in["object_id"].get<int>());
        const std::string& part = parts[std::size_t(plant - 1)];
        bool found = false;
        for (std::size_t at = part.find(id); at != std::string::npos && !found;
             at = part.find(id, at + 1))
            found = !std::isdigit(static_cast<unsigned char>(part[at - 1])) &&
                    !std::isdigit(static_cast<unsigned char>(part[at + id.size()]));
        EXPECT_TRUE(found) << "object " << id << " not in plant " << plant;
    }
}

TEST(DatasetSample, TheMasksAgreeWithThePointCloudLabels) {
    const Sample& s = madeSample();
    const std::vector<vec3> points = readPLYPoints((s.dir / "points.ply").string());
    ASSERT_EQ(points.size(), 20000u);
    // The labels of the PLY (binary, little endian): after the header, per point
    // x y z nx ny nz (float) plant_id object_id (int) organ (uchar) ...
    const std::string bytes = slurp(s.dir / "points.ply");
    const std::size_t body = bytes.find("end_header\n") + 11;
    const std::size_t stride = (bytes.size() - body) / points.size();
    std::map<int, int> plantInstance;
    for (const json& p : s.metadata["plants"]) plantInstance[p["plant_id"]] = p["plant_instance"];
    const json& K = s.camera["K"];
    const json& E = s.camera["world_to_camera"];
    std::size_t checked = 0, agree = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const vec3 p = points[k];
        double c[3];
        for (int r = 0; r < 3; ++r)
            c[r] = E[r][0].get<double>() * p.x + E[r][1].get<double>() * p.y +
                   E[r][2].get<double>() * p.z + E[r][3].get<double>();
        if (c[2] <= 0) continue;
        const int x =
            int(std::lround((K[0][0].get<double>() * c[0] + K[0][2].get<double>() * c[2]) / c[2]));
        const int y =
            int(std::lround((K[1][1].get<double>() * c[1] + K[1][2].get<double>() * c[2]) / c[2]));
        if (x < 1 || y < 1 || x >= s.w - 1 || y >= s.h - 1) continue;
        const std::size_t i = std::size_t(y) * std::size_t(s.w) + std::size_t(x);
        // Seen (the surface there is at the point's depth) and inside one object.
        if (std::abs(s.depth[i] - c[2]) > 0.002 + 0.002 * c[2]) continue;
        bool interior = true;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                interior &= s.organ.values[i + std::size_t(dy * s.w + dx)] == s.organ.values[i];
        if (!interior || s.organ.values[i] == 0) continue;
        std::int32_t plantID = 0;
        std::memcpy(&plantID, bytes.data() + body + k * stride + 24, 4);
        const std::uint8_t organ = std::uint8_t(bytes[body + k * stride + 32]);
        ++checked;
        agree += s.semantic[i] == organ && s.plant.values[i] == plantInstance[plantID];
    }
    EXPECT_GT(checked, 500u);
    EXPECT_GE(double(agree), 0.99 * double(checked)) << agree << " of " << checked;
}

}  // namespace

namespace {

// Rows `panels` of equal size stacked: a grid of strips.
Image stack(const std::vector<Image>& rows) {
    Image out(rows.front().width, 0);
    for (const Image& r : rows) {
        out.rgb.insert(out.rgb.end(), r.rgb.begin(), r.rgb.end());
        out.height += r.height;
    }
    return out;
}

Image colouredLabels(const Image16& labels, bool organs) {
    Image out(labels.width, labels.height);
    for (std::size_t i = 0; i < labels.values.size(); ++i) {
        const std::uint16_t v = labels.values[i];
        if (v == 0) continue;
        const auto c = organs ? organLabelColors()[v / 257 - 1].rgb : objectLabelColor(v * 7919u);
        std::copy(c.begin(), c.end(), out.rgb.begin() + std::ptrdiff_t(3 * i));
    }
    return out;
}

// docs/images/dataset-sample.png: one sample of examples/datasets/bean_rows.json, its RGB,
// semantic mask, organ and plant instances, depth and normals. Written full size with
// PLANTARCH_WRITE_DOCS_IMAGES=1; otherwise made small as a check that the pipeline runs.
TEST(DocsImages, ADatasetSampleAndItsLabels) {
    const bool full = plantarch::testing::writingDocsImages();
    DatasetSpec spec = readDatasetSpecFile(std::string(PLANTARCH_SOURCE_DIR) +
                                           "/examples/datasets/bean_rows.json");
    spec.camera.width = spec.camera.height = full ? 360 : 64;
    spec.camera.samplesPerPixel = full ? 16 : 1;
    spec.points = 1000;
    const std::string out = scratch("docs-image");
    writeDatasetSample(spec, 4, out);
    const fs::path d = fs::path(out) / "samples" / "000004";
    DepthImage depth;
    depth.width = depth.height = spec.camera.width;
    depth.depth = npyFloats(d / "depth.npy");
    const Image16 semantic = readImage16((d / "semantic.png").string());
    const Image picture =
        stack({plantarch::testing::strip(
                   {readImage((d / "rgb.png").string()), colouredLabels(semantic, true),
                    colouredLabels(readImage16((d / "organ_instances.png").string()), false)}),
               plantarch::testing::strip(
                   {colouredLabels(readImage16((d / "plant_instances.png").string()), false),
                    depthPicture(depth), readImage((d / "normals.png").string())})});
    EXPECT_EQ(picture.width, 3 * spec.camera.width);
    EXPECT_EQ(picture.height, 2 * spec.camera.height);
    writePNG(picture, full ? plantarch::testing::docsImagePath("dataset-sample.png")
                           : (fs::path(out) / "dataset-sample.png").string());
}

}  // namespace
