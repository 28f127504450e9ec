// A sample's labels: instance and semantic masks from the surfaces seen, leaf keypoints, and
// the COCO and YOLO annotations made from them.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dataset/dataset_internal.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch::dataset {

std::vector<std::string> categoryNames() {
    std::vector<std::string> out;
    for (std::size_t i = 1; i < kOrganLabels.size(); ++i) out.emplace_back(kOrganLabels[i]);
    out.emplace_back("plant");
    return out;
}

int plantCategory() {
    return int(kOrganLabels.size());
}

namespace {

int organCategory(const std::string& organ) {
    for (std::size_t i = 1; i < kOrganLabels.size(); ++i)
        if (organ == kOrganLabels[i]) return int(i);
    return 0;
}

}  // namespace

SampleLabels labelPixels(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                         const SurfaceImage& surfaces) {
    const Context& ctx = arch.context();
    SampleLabels out;
    out.width = surfaces.width;
    out.height = surfaces.height;
    std::map<int, int> plantNumber;  // plant ID -> instance
    for (std::size_t k = 0; k < plants.size(); ++k) plantNumber[int(plants[k])] = int(k) + 1;
    // Objects seen, numbered in ID order.
    std::vector<ObjectID> seen;
    for (std::uint32_t v : surfaces.object)
        if (v != 0) seen.push_back(v - 1);
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    if (seen.size() > 65535)
        throw Error(fmt::format("{} objects are seen in one image: instance masks hold at most "
                                "65535 (use a smaller scene or image)",
                                seen.size()),
                    {.parameter = "camera"});
    std::map<ObjectID, std::size_t> index;
    for (ObjectID id : seen) {
        Instance in;
        in.number = std::uint32_t(out.instances.size() + 1);
        in.object = id;
        in.category = organCategory(ctx.objectDataString(id, "organ").value_or(""));
        in.plantID = ctx.objectDataInt(id, "plantID").value_or(-1);
        if (const auto p = plantNumber.find(in.plantID); p != plantNumber.end())
            in.plant = p->second;
        in.shoot = ctx.objectDataInt(id, "shootID").value_or(-1);
        in.node = ctx.objectDataInt(id, "node").value_or(-1);
        in.leafID = ctx.objectDataInt(id, "leafID").value_or(-1);
        index[id] = out.instances.size();
        out.instances.push_back(in);
    }
    const std::size_t n = surfaces.object.size();
    out.organMask.assign(n, 0);
    out.plantMask.assign(n, 0);
    out.semantic.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (surfaces.object[i] == 0) continue;
        const Instance& in = out.instances[index.at(surfaces.object[i] - 1)];
        out.organMask[i] = in.number;
        out.plantMask[i] = std::uint32_t(in.plant);
        out.semantic[i] = std::uint8_t(in.category);
    }
    return out;
}

namespace {

// The vertices of a leaf's objects and the points it hangs from (its petiole, or its node).
struct LeafGeometry {
    std::vector<vec3> blade;
    std::vector<vec3> attachment;
};

// The leaf's base (the blade vertex nearest its attachment) and tip (the blade vertex
// farthest from the base).
std::array<vec3, 2> baseAndTip(const LeafGeometry& g) {
    vec3 base = g.blade.front();
    float best = std::numeric_limits<float>::max();
    for (const vec3& v : g.blade)
        for (const vec3& a : g.attachment) {
            const vec3 d = v - a;
            const float d2 = glm::dot(d, d);
            if (d2 < best) {
                best = d2;
                base = v;
            }
        }
    vec3 tip = base;
    float far = -1.0f;
    for (const vec3& v : g.blade) {
        const vec3 d = v - base;
        if (glm::dot(d, d) > far) {
            far = glm::dot(d, d);
            tip = v;
        }
    }
    return {base, tip};
}

// Projects p with the camera; the depth is along the view axis (z of the camera frame).
void project(const CameraMatrices& c, const vec3& p, std::array<double, 2>& pixel, double& depth) {
    double cam[3];
    for (int r = 0; r < 3; ++r)
        cam[r] = c.worldToCamera[std::size_t(r)][0] * p.x +
                 c.worldToCamera[std::size_t(r)][1] * p.y +
                 c.worldToCamera[std::size_t(r)][2] * p.z + c.worldToCamera[std::size_t(r)][3];
    depth = cam[2];
    if (cam[2] <= 0.0) {
        pixel = {0.0, 0.0};
        return;
    }
    for (int r = 0; r < 2; ++r)
        pixel[std::size_t(r)] = (c.K[std::size_t(r)][0] * cam[0] + c.K[std::size_t(r)][1] * cam[1] +
                                 c.K[std::size_t(r)][2] * cam[2]) /
                                cam[2];
}

// 2 seen (nothing between the eye and the point but the point's own surface, within 0.5 mm
// and a ten-thousandth of the distance), 1 hidden, 0 outside the frame or behind the eye.
int visibility(const std::array<double, 2>& px, double depth, const vec3& point, const vec3& eye,
               const RenderScene& scene, int width, int height) {
    if (depth <= 0.0) return 0;
    const double x = std::round(px[0]), y = std::round(px[1]);
    if (x < 0.0 || y < 0.0 || x >= width || y >= height) return 0;
    const float distance = glm::length(point - eye);
    const float hit = scene.hitDistance(eye, (point - eye) / distance);
    return hit >= distance - (5e-4f + 1e-4f * distance) ? 2 : 1;
}

}  // namespace

std::vector<LeafKeypoints> leafKeypoints(const PlantArchitecture& arch,
                                         const std::vector<unsigned>& plants,
                                         const CameraMatrices& camera, const vec3& eye,
                                         const RenderScene& scene, int width, int height) {
    const Context& ctx = arch.context();
    std::vector<LeafKeypoints> out;
    auto vertices = [&](ObjectID id, std::vector<vec3>& into) {
        if (id == kNoObject || !ctx.doesObjectExist(id) || ctx.isObjectHidden(id)) return;
        const ObjectView v = ctx.object(id);
        into.insert(into.end(), v.positions.begin(), v.positions.end());
    };
    for (std::size_t k = 0; k < plants.size(); ++k) {
        const PlantInstance& plant = arch.plant(plants[k]);
        for (const Shoot& shoot : plant.shoots)
            for (std::size_t n = 0; n < shoot.phytomers.size(); ++n)
                for (const Petiole& pt : shoot.phytomers[n].petioles) {
                    LeafGeometry g;
                    vertices(pt.object, g.attachment);
                    if (g.attachment.empty())
                        g.attachment.push_back(
                            arch.getNodePosition(plants[k], shoot.id, unsigned(n)));
                    for (const LeafOrgan& leaf : pt.leaves) {
                        if (leaf.removed) continue;
                        g.blade.clear();
                        for (ObjectID id : leaf.objects) vertices(id, g.blade);
                        if (g.blade.empty()) continue;
                        LeafKeypoints kp;
                        kp.plant = int(k) + 1;
                        kp.objects = leaf.objects;
                        kp.shoot = int(shoot.id);
                        kp.node = int(n);
                        kp.leafID = leaf.leafID;
                        kp.world = baseAndTip(g);
                        for (std::size_t j = 0; j < 2; ++j) {
                            project(camera, kp.world[j], kp.pixel[j], kp.depth[j]);
                            kp.visibility[j] = visibility(kp.pixel[j], kp.depth[j], kp.world[j],
                                                          eye, scene, width, height);
                        }
                        out.push_back(std::move(kp));
                    }
                }
    }
    return out;
}

OrderedJson sampleCOCO(const DatasetSpec& spec, const DatasetSample& sample,
                       const SampleLabels& labels, const std::vector<LeafKeypoints>& keypoints) {
    const int w = labels.width, h = labels.height;
    OrderedJson categories = OrderedJson::array();
    const std::vector<std::string> names = categoryNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
        OrderedJson c = {{"id", i + 1},
                         {"name", names[i]},
                         {"supercategory", int(i + 1) == plantCategory() ? "plant" : "organ"}};
        if (names[i] == "leaf") {
            c["keypoints"] = {"base", "tip"};
            c["skeleton"] = {{1, 2}};
        }
        categories.push_back(c);
    }
    // A leaf's keypoints go on the annotation of its first object seen.
    std::map<ObjectID, const LeafKeypoints*> leafOf;
    for (const LeafKeypoints& kp : keypoints)
        for (ObjectID id : kp.objects) leafOf.emplace(id, &kp);
    OrderedJson annotations = OrderedJson::array();
    auto add = [&](const MaskRegion& r, int category, OrderedJson extra) {
        if (double(r.area) < spec.cocoMinArea) return;
        OrderedJson a = {{"id", annotations.size() + 1},
                         {"image_id", sample.index},
                         {"category_id", category},
                         {"iscrowd", 0},
                         {"area", r.area},
                         {"bbox", r.bbox},
                         {"segmentation", {{"counts", r.rle}, {"size", {h, w}}}}};
        for (auto& [k, v] : extra.items()) a[k] = v;
        annotations.push_back(a);
    };
    std::map<const LeafKeypoints*, bool> placed;
    for (const MaskRegion& r : maskRegions(labels.organMask, w, h)) {
        const Instance& in = labels.instances[r.label - 1];
        OrderedJson extra = {
            {"instance", in.number}, {"plant_instance", in.plant}, {"object_id", in.object}};
        if (const auto it = leafOf.find(in.object);
            it != leafOf.end() && !placed[it->second] && double(r.area) >= spec.cocoMinArea) {
            const LeafKeypoints& kp = *it->second;
            OrderedJson points = OrderedJson::array();
            int labelled = 0;
            for (std::size_t j = 0; j < 2; ++j) {
                const bool in = kp.visibility[j] > 0;
                points.push_back(in ? kp.pixel[j][0] : 0.0);
                points.push_back(in ? kp.pixel[j][1] : 0.0);
                points.push_back(kp.visibility[j]);
                labelled += in ? 1 : 0;
            }
            extra["keypoints"] = points;
            extra["num_keypoints"] = labelled;
            placed[it->second] = true;
        }
        add(r, in.category, extra);
    }
    for (const MaskRegion& r : maskRegions(labels.plantMask, w, h))
        add(r, plantCategory(), {{"plant_instance", r.label}});
    OrderedJson info = {{"description", "plantarch synthetic dataset"},
                        {"dataset", spec.name},
                        {"sample", sample.index},
                        {"seed", sample.seed},
                        {"species", sample.species},
                        {"split", sample.split}};
    OrderedJson image = {
        {"id", sample.index}, {"file_name", "rgb.png"}, {"width", w}, {"height", h}};
    return {{"info", info},
            {"images", {image}},
            {"categories", categories},
            {"annotations", annotations}};
}

std::string sampleYOLO(const OrderedJson& coco, int width, int height) {
    // One line per annotation: class (category id - 1) and the box's centre and size as
    // fractions of the image, six decimals.
    std::string out;
    for (const auto& a : coco["annotations"]) {
        const auto box = a["bbox"].get<std::array<int, 4>>();
        out += fmt::format("{} {:.6f} {:.6f} {:.6f} {:.6f}\n", a["category_id"].get<int>() - 1,
                           (box[0] + 0.5 * box[2]) / width, (box[1] + 0.5 * box[3]) / height,
                           double(box[2]) / width, double(box[3]) / height);
    }
    return out;
}

}  // namespace plantarch::dataset
