#pragma once
// Synthetic datasets: a dataset spec file (JSON, docs/datasets.md) says which scenes to draw
// (species mix, ages, layouts, weeds, parameters drawn per sample), how to see them (cameras,
// sun and sky, ground) and what to write; `plantarch dataset SPEC --out DIR` writes one folder
// of labelled files per sample.
//
// Sample i is a pure function of (spec, i): its random choices come from a stream seeded by
// the spec's seed and i alone, so any split of the samples over shards, processes or machines
// writes the same bytes for each sample. A sample is written into a temporary folder beside
// the samples and renamed into place when complete: a killed run leaves no half sample.
//
//   DatasetSpec spec = readDatasetSpecFile("beans.json");
//   for (std::size_t i = 0; i < spec.samples; ++i) writeDatasetSample(spec, i, "out");
//   writeDatasetManifest(spec, "out", {0, 1});

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Progress.h"
#include "plantarch/Project.h"
#include "plantarch/Render.h"

namespace plantarch {

/// The version of the dataset spec format ("plantarch_dataset").
inline constexpr int kDatasetVersion = 1;
/// The most samples one spec may ask for.
inline constexpr std::size_t kMaxDatasetSamples = 10000000;

/// A number drawn per sample. Written in a spec as a number (a constant), [lo, hi] (uniform;
/// whole numbers for whole-number fields), {"uniform": [lo, hi]}, {"normal": [mean, sd]}
/// (redrawn until it falls in the field's valid range, at most 64 times, then the nearest
/// end of the range; the spec reader refuses a normal whose mean is outside that range) or
/// {"choice": [a, b, ...], "weights": [...]}.
struct Draw {
    enum class Kind { Constant, Uniform, Normal, Choice };
    Kind kind = Kind::Constant;
    double a = 0.0, b = 0.0;       ///< the constant; lo and hi; mean and sd
    std::vector<double> values;    ///< Choice
    std::vector<double> weights;   ///< Choice: one per value (empty: equal)
    bool whole = false;            ///< draws whole numbers
    double lo = -1e30, hi = 1e30;  ///< the field's valid range (normal draws stay in it)

    static Draw constant(double v) { return {Kind::Constant, v, v, {}, {}, false}; }
};

/// One species the scenes may hold, with its weight among the others.
struct DatasetSpecies {
    std::string species;  ///< library name or species file (relative to the spec's folder)
    double weight = 1.0;
    Draw age = Draw::constant(30.0);  ///< days
    /// Build parameters (trunk_height...) drawn per sample.
    std::map<std::string, Draw> buildParameters;
    /// Species fields (editSpecies paths: "shoot_types.stem.internode_length_max") drawn per
    /// sample.
    std::map<std::string, Draw> speciesParameters;
};

/// One way of laying plants out, with its weight among the others.
struct DatasetLayout {
    enum class Kind {
        Single,   ///< one plant at the origin
        Rows,     ///< rows along x: `rows` of `plantsPerRow`, rowSpacing and plantSpacing apart
        Grid,     ///< alias of Rows with equal spacings: count x count, `spacing` apart
        Scatter,  ///< `plants` positions drawn over an area x area square
    };
    Kind kind = Kind::Single;
    double weight = 1.0;
    Draw rows = Draw::constant(2), plantsPerRow = Draw::constant(3);
    Draw rowSpacing = Draw::constant(0.5), plantSpacing = Draw::constant(0.25);
    Draw count = Draw::constant(3), spacing = Draw::constant(0.3);
    Draw plants = Draw::constant(5), area = Draw::constant(1.0);
};

/// Weeds among the crop: with `probability`, a scatter of weed plants over the crop's area
/// (plus `margin` on each side).
struct DatasetWeeds {
    double probability = 0.0;
    std::vector<DatasetSpecies> species;
    Draw plants = Draw::constant(4);
    Draw margin = Draw::constant(0.1);  ///< m
};

/// How the camera is placed for a sample.
struct DatasetCamera {
    enum class Kind {
        Orbit,       ///< auto-framed from (azimuth, elevation) degrees
        Nadir,       ///< straight down from `height` m above the scene's top, framed on it
        Row,         ///< beside the first row at `height`, looking along +x, `pitch` down
        Random,      ///< eye drawn in a box around the scene centre (eyeMin..eyeMax, m)
        Trajectory,  ///< eye along a polyline: sample i at fraction i / (samples - 1)
    };
    Kind kind = Kind::Orbit;
    int width = 512, height = 512;  ///< pixels
    int samplesPerPixel = 4;
    Draw fov = Draw::constant(35.0);  ///< vertical, degrees
    Draw azimuth = Draw{Draw::Kind::Uniform, -180.0, 180.0, {}, {}, false};
    Draw elevation = Draw{Draw::Kind::Uniform, 15.0, 60.0, {}, {}, false};
    Draw margin = Draw::constant(0.07);
    Draw heightAbove = Draw::constant(1.0);  ///< Nadir, Row: m
    Draw pitch = Draw::constant(20.0);       ///< Row: degrees below the horizontal
    std::array<Draw, 3> eyeMin{Draw::constant(-1), Draw::constant(-1), Draw::constant(0.3)};
    std::array<Draw, 3> eyeMax{Draw::constant(1), Draw::constant(1), Draw::constant(1.5)};
    std::vector<std::array<double, 3>> path;      ///< Trajectory: eye points, m
    std::array<double, 3> target{0.0, 0.0, 0.2};  ///< Trajectory: the point looked at, m
};

/// Sun and sky of a sample.
struct DatasetLighting {
    double latitude = 40.0, longitude = 0.0;  ///< degrees
    Draw dayOfYear = Draw{Draw::Kind::Uniform, 120.0, 240.0, {}, {}, true};
    Draw hour = Draw{Draw::Kind::Uniform, 8.0, 16.0, {}, {}, false};  ///< local solar time
    Draw sunIntensity = Draw::constant(2.6);
    Draw sunSoftness = Draw::constant(1.2);  ///< angular radius of the sun disc, degrees
    Draw skyIntensity = Draw::constant(1.0);
    Draw haze = Draw::constant(0.0);  ///< 0 a clear blue sky to 1 an overcast white one
    Draw exposure = Draw::constant(1.0);
};

/// The ground of a sample: the render's ground plane, its colour drawn between two sRGB
/// colours, with patchy soil.
struct DatasetGround {
    std::array<double, 3> colorA{0.42, 0.38, 0.33}, colorB{0.30, 0.24, 0.18};
    Draw variation = Draw::constant(0.3);  ///< RenderOptions::groundVariation
    Draw patchSize = Draw::constant(0.1);  ///< m
};

/// Per-sample colour variation of the plants' leaves (and petioles): hue turned by degrees,
/// saturation and value scaled.
struct DatasetLeafColor {
    Draw hue = Draw::constant(0.0);
    Draw saturation = Draw::constant(1.0);
    Draw value = Draw::constant(1.0);
};

/// The files a sample can hold (docs/datasets.md lists each).
enum class DatasetOutput {
    RGB,             ///< rgb.png
    Semantic,        ///< semantic.png: organ category per pixel (8-bit)
    OrganInstances,  ///< organ_instances.png: instance number per pixel (16-bit)
    PlantInstances,  ///< plant_instances.png: plant number per pixel (16-bit)
    Depth,           ///< depth.npy
    Normals,         ///< normals.npy and normals.png (camera frame)
    Camera,          ///< camera.json
    COCO,            ///< coco.json
    YOLO,            ///< yolo.txt
    Keypoints,       ///< keypoints.json: leaf bases and tips
    Points,          ///< points.ply: labelled surface samples
    Scan,            ///< scan.ply: a simulated LiDAR scan
    PlantXML,        ///< plants.xml: every plant's structure
};
const char* datasetOutputName(DatasetOutput o);
/// Every output, in the order above.
const std::vector<DatasetOutput>& datasetOutputs();

/// A dataset spec as read.
struct DatasetSpec {
    std::string name = "dataset";
    std::uint64_t seed = 1;
    std::size_t samples = 10;
    std::vector<DatasetSpecies> species;
    std::vector<DatasetLayout> layouts;
    DatasetWeeds weeds;
    Draw germination = Draw::constant(1.0);
    Draw meshDetail = Draw::constant(1.0);
    bool softCollision = false;
    DatasetLeafColor leafColor;
    DatasetCamera camera;
    DatasetLighting lighting;
    DatasetGround ground;
    std::vector<DatasetOutput> outputs;  ///< default: all but Scan
    double cocoMinArea = 20.0;           ///< pixels: smaller annotations are left out
    std::size_t points = 100000;         ///< Points: surface samples
    float scanResolution = 0.5f;         ///< Scan: degrees between rays
    std::vector<std::pair<std::string, double>> splits{{"train", 0.8}, {"val", 0.1}, {"test", 0.1}};
    std::size_t maxTriangles = 20000000;  ///< a sample's scene may hold at most this many
    std::string folder = ".";             ///< relative species files are taken from here
    std::string file;                     ///< named by errors
};

/// Reads a spec file strictly: an unknown field (with the nearest valid name), a value of the
/// wrong type or out of its range is a plantarch::Error naming the file, the field as a JSON
/// pointer without its leading slash ("scene/species/0/age"), the value and the valid range.
DatasetSpec readDatasetSpecFile(const std::string& path);
DatasetSpec readDatasetSpecString(const std::string& json, const std::string& nameForErrors,
                                  const std::string& folder = ".");
/// Loads each species and checks each drawn species field and build parameter names a field
/// of it (without building a plant). Throws plantarch::Error naming the spec's field.
void checkDatasetSpec(const DatasetSpec& spec);

/// What sample i is, before it is built: every random choice made.
struct DatasetSample {
    std::size_t index = 0;
    std::uint64_t seed = 0;  ///< the sample's own seed (its scene's)
    std::string split;
    std::string species;   ///< the crop's
    Project project;       ///< the scene, as `plantarch project run` builds it
    RenderOptions render;  ///< camera (fixed, not auto-framed, once built), sun, sky, ground
    std::array<double, 3> leafHSV{0.0, 1.0, 1.0};
    double dayOfYear = 0.0, hour = 0.0;
};
/// The choices of sample `index` (< kMaxDatasetSamples).
DatasetSample drawDatasetSample(const DatasetSpec& spec, std::size_t index);

/// The folder name of a sample ("000012"): at least six digits.
std::string datasetSampleName(std::size_t index);

/// What writing a sample did.
struct DatasetSampleResult {
    std::size_t index = 0;
    std::string split;
    bool skipped = false;  ///< it existed (resume)
    std::uint64_t bytes = 0;
    std::size_t plants = 0, triangles = 0, annotations = 0;
};

struct DatasetWriteOptions {
    bool resume = false;  ///< an existing sample folder is kept (else it is an Error)
    /// Receives ("building", ...) progress of the one sample; may be empty.
    ProgressCallback progress;
};

/// Builds sample `index` and writes its folder `outDir/samples/NAME/` atomically (a temporary
/// folder renamed into place). Throws plantarch::Error naming the spec field or the file.
DatasetSampleResult writeDatasetSample(const DatasetSpec& spec, std::size_t index,
                                       const std::string& outDir,
                                       const DatasetWriteOptions& options = {});

/// The samples of shard k of n (i % n == k), below `samples`.
std::vector<std::size_t> datasetShard(std::size_t samples, std::size_t k, std::size_t n);

/// Writes `outDir/manifest-K-of-N.json` (atomically): the spec's name and seed and, for each
/// sample of the shard, its index, split and files with their sizes, read from the sample
/// folders. Throws plantarch::Error naming a missing sample.
void writeDatasetManifest(const DatasetSpec& spec, const std::string& outDir, std::size_t samples,
                          std::size_t shard, std::size_t shards);

/// After every shard: checks every sample 0..samples-1 is present, removes temporary folders
/// left by killed runs, and writes `outDir/dataset.json` (every sample, by split) and
/// `outDir/coco_SPLIT.json` (each split's COCO with file names relative to outDir). Throws
/// plantarch::Error listing missing samples.
void mergeDataset(const DatasetSpec& spec, const std::string& outDir, std::size_t samples);

}  // namespace plantarch
