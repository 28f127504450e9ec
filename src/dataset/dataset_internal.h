#pragma once
// What the dataset files share: the spec's field tables, drawing numbers, sample folders.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plantarch/Dataset.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Random.h"
#include "plantarch/Render.h"

namespace plantarch::dataset {

/// A value drawn from `d` with `rng` (the rules of Draw in plantarch/Dataset.h).
double draw(const Draw& d, Rng& rng);
/// An index drawn in proportion to `weights` (all >= 0, sum > 0).
std::size_t drawIndex(const std::vector<double>& weights, Rng& rng);

/// Where sample folders go: outDir/samples.
std::string samplesFolder(const std::string& outDir);
/// The files of a sample folder, in the order a sample writes them (those its outputs ask
/// for, and metadata.json last).
std::vector<std::string> sampleFiles(const DatasetSpec& spec);

/// The organ categories of COCO, YOLO and the semantic mask: kOrganLabels 1.. (internode,
/// petiole, leaf, ..., ground, obstacle), and "plant" after them.
std::vector<std::string> categoryNames();
/// The category id of whole plants in COCO (after the organ kinds).
int plantCategory();

using OrderedJson = nlohmann::ordered_json;

/// One organ seen in a sample's image: its number in organ_instances.png and its labels.
struct Instance {
    std::uint32_t number = 0;  ///< 1.. in object ID order
    ObjectID object = 0;
    int category = 0;  ///< index into categoryNames() plus 1
    int plant = 0;     ///< plant instance: 1.. in the sample's plant order (0: none)
    int plantID = -1;  ///< the plant's ID in its PlantArchitecture
    int shoot = -1, node = -1, leafID = -1;
};

/// The label images of a sample and what their numbers mean.
struct SampleLabels {
    int width = 0, height = 0;
    std::vector<Instance> instances;       ///< by number - 1
    std::vector<std::uint32_t> organMask;  ///< instance number per pixel (0 none)
    std::vector<std::uint32_t> plantMask;  ///< plant instance per pixel (0 none)
    std::vector<std::uint8_t> semantic;    ///< category per pixel (0 none)
};

/// The labels of the pixels of `surfaces`: plants are numbered in the order of `plants`
/// (IDs of `arch`); objects of no plant get the category of their organ string and no plant.
SampleLabels labelPixels(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                         const SurfaceImage& surfaces);

/// A leaf's base and tip: 3D (m) and in the image (pixels, OpenCV convention), with COCO's
/// visibility: 2 seen (a ray from the eye reaches it), 1 in the frame but hidden, 0 outside the
/// frame (or behind the eye).
struct LeafKeypoints {
    int plant = 0;  ///< plant instance
    std::vector<ObjectID> objects;
    int shoot = 0, node = 0, leafID = -1;
    std::array<vec3, 2> world{};  ///< base, tip
    std::array<std::array<double, 2>, 2> pixel{};
    std::array<double, 2> depth{};
    std::array<int, 2> visibility{};
};
/// `scene` is the sample's, seen from `eye` in a width x height image.
std::vector<LeafKeypoints> leafKeypoints(const PlantArchitecture& arch,
                                         const std::vector<unsigned>& plants,
                                         const CameraMatrices& camera, const vec3& eye,
                                         const RenderScene& scene, int width, int height);

/// The sample's COCO document (plant and organ categories, one annotation per instance
/// and per plant of at least spec.cocoMinArea pixels, leaf keypoints) and YOLO lines.
OrderedJson sampleCOCO(const DatasetSpec& spec, const DatasetSample& sample,
                       const SampleLabels& labels, const std::vector<LeafKeypoints>& keypoints);
std::string sampleYOLO(const OrderedJson& coco, int width, int height);

}  // namespace plantarch::dataset
