// Writing one sample: its scene built from the drawn project, leaf colours varied, the
// camera fixed, the images rendered, and every file written into a temporary folder that is
// renamed into place when complete.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <system_error>

#include "core/atomic_file.h"
#include "core/stb.h"
#include "core/temporary_files.h"
#include "dataset/dataset_internal.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFiles.h"
#include "plantarch/PlantStructureWrite.h"
#include "plantarch/Scan.h"

namespace plantarch {

namespace fs = std::filesystem;

const char* datasetOutputName(DatasetOutput o) {
    switch (o) {
        case DatasetOutput::RGB:
            return "rgb";
        case DatasetOutput::Semantic:
            return "semantic";
        case DatasetOutput::OrganInstances:
            return "organ_instances";
        case DatasetOutput::PlantInstances:
            return "plant_instances";
        case DatasetOutput::Depth:
            return "depth";
        case DatasetOutput::Normals:
            return "normals";
        case DatasetOutput::Camera:
            return "camera";
        case DatasetOutput::COCO:
            return "coco";
        case DatasetOutput::YOLO:
            return "yolo";
        case DatasetOutput::Keypoints:
            return "keypoints";
        case DatasetOutput::Points:
            return "points";
        case DatasetOutput::Scan:
            return "scan";
        case DatasetOutput::PlantXML:
            return "plant_xml";
    }
    return "rgb";
}

const std::vector<DatasetOutput>& datasetOutputs() {
    static const std::vector<DatasetOutput> all = {DatasetOutput::RGB,
                                                   DatasetOutput::Semantic,
                                                   DatasetOutput::OrganInstances,
                                                   DatasetOutput::PlantInstances,
                                                   DatasetOutput::Depth,
                                                   DatasetOutput::Normals,
                                                   DatasetOutput::Camera,
                                                   DatasetOutput::COCO,
                                                   DatasetOutput::YOLO,
                                                   DatasetOutput::Keypoints,
                                                   DatasetOutput::Points,
                                                   DatasetOutput::Scan,
                                                   DatasetOutput::PlantXML};
    return all;
}

namespace dataset {

std::string samplesFolder(const std::string& outDir) {
    return (fs::path(outDir) / "samples").string();
}

std::vector<std::string> sampleFiles(const DatasetSpec& spec) {
    std::vector<std::string> files;
    for (DatasetOutput o : spec.outputs) switch (o) {
            case DatasetOutput::RGB:
                files.push_back("rgb.png");
                break;
            case DatasetOutput::Semantic:
                files.push_back("semantic.png");
                break;
            case DatasetOutput::OrganInstances:
                files.push_back("organ_instances.png");
                break;
            case DatasetOutput::PlantInstances:
                files.push_back("plant_instances.png");
                break;
            case DatasetOutput::Depth:
                files.push_back("depth.npy");
                break;
            case DatasetOutput::Normals:
                files.push_back("normals.npy");
                files.push_back("normals.png");
                break;
            case DatasetOutput::Camera:
                files.push_back("camera.json");
                break;
            case DatasetOutput::COCO:
                files.push_back("coco.json");
                break;
            case DatasetOutput::YOLO:
                files.push_back("yolo.txt");
                break;
            case DatasetOutput::Keypoints:
                files.push_back("keypoints.json");
                break;
            case DatasetOutput::Points:
                files.push_back("points.ply");
                break;
            case DatasetOutput::Scan:
                files.push_back("scan.ply");
                break;
            case DatasetOutput::PlantXML:
                files.push_back("plants.xml");
                break;
        }
    files.push_back("metadata.json");
    return files;
}

}  // namespace dataset

namespace {

using dataset::OrderedJson;

// sRGB colour -> HSV (hue in degrees) and back.
vec3 toHSV(vec3 c) {
    const float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
    const float d = mx - mn;
    float h = 0.0f;
    if (d > 0.0f) {
        if (mx == c.r)
            h = 60.0f * std::fmod((c.g - c.b) / d, 6.0f);
        else if (mx == c.g)
            h = 60.0f * ((c.b - c.r) / d + 2.0f);
        else
            h = 60.0f * ((c.r - c.g) / d + 4.0f);
    }
    if (h < 0.0f) h += 360.0f;
    return {h, mx > 0.0f ? d / mx : 0.0f, mx};
}
vec3 fromHSV(vec3 hsv) {
    const float h = std::fmod(std::fmod(hsv.x, 360.0f) + 360.0f, 360.0f) / 60.0f;
    const float s = std::clamp(hsv.y, 0.0f, 1.0f), v = std::clamp(hsv.z, 0.0f, 1.0f);
    const float c = v * s, x = c * (1.0f - std::abs(std::fmod(h, 2.0f) - 1.0f)), m = v - c;
    const int k = std::min(int(h), 5);
    const vec3 rgb[6] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
    return rgb[k] + vec3(m);
}

// Leaves and petioles of the sample's plants recoloured by the drawn hue turn and scales.
void varyLeafColours(Context& ctx, const std::array<double, 3>& hsv) {
    if (hsv[0] == 0.0 && hsv[1] == 1.0 && hsv[2] == 1.0) return;
    std::map<MaterialID, MaterialID> recoloured;
    for (ObjectID id : ctx.objectIDs()) {
        const std::string organ = ctx.objectDataString(id, "organ").value_or("");
        if (organ != "leaf" && organ != "petiole") continue;
        const MaterialID m = ctx.objectMaterial(id);
        auto it = recoloured.find(m);
        if (it == recoloured.end()) {
            Material changed = ctx.material(m);
            vec3 c = toHSV(changed.color);
            c.x += float(hsv[0]);
            c.y *= float(hsv[1]);
            c.z *= float(hsv[2]);
            changed.color = fromHSV(c);
            changed.name.clear();
            it = recoloured.emplace(m, ctx.addMaterial(changed)).first;
        }
        ctx.setObjectMaterial(id, it->second);
    }
}

// The camera made fixed: auto-framed views resolved, relative eyes placed on the scene.
void fixCamera(DatasetSample& s, const RenderScene& scene, const BuiltProject& built,
               const PlantArchitecture& arch, const DatasetSpec& spec) {
    RenderOptions& o = s.render;
    const AABB box = scene.bounds();
    const vec3 centre = box.empty() ? vec3(0.0f) : box.center();
    switch (spec.camera.kind) {
        case DatasetCamera::Kind::Row: {
            // Beside the start of the first row (the lowest y), a little before its first plant.
            vec3 first = centre;
            if (!built.blockPlants.empty() && !built.blockPlants[0].empty())
                first = arch.plant(built.blockPlants[0][0]).base;
            const vec3 look = o.camera.target - o.camera.eye;
            o.camera.eye =
                vec3(box.empty() ? first.x - 0.3f : box.min.x - 0.3f, first.y, o.camera.eye.z);
            o.camera.target = o.camera.eye + look;
            break;
        }
        case DatasetCamera::Kind::Random:
            o.camera.eye += centre;
            o.camera.target = centre;
            if (glm::length(o.camera.target - o.camera.eye) <= 0.0f) o.camera.eye.z += 0.5f;
            break;
        default:
            break;
    }
    const CameraFrame frame = scene.camera(o);
    o.camera.autoFrame = false;
    o.camera.eye = frame.eye;
    o.camera.target = frame.target;
    o.camera.up = frame.up;
    o.camera.fovDeg = frame.fovDeg;
}

// Camera-frame normals of the surfaces (OpenCV axes: x right, y down, z forward).
std::vector<float> cameraNormals(const SurfaceImage& s, const CameraMatrices& c) {
    std::vector<float> out(s.normal.size() * 3, 0.0f);
    for (std::size_t i = 0; i < s.normal.size(); ++i) {
        const vec3 n = s.normal[i];
        if (n == vec3(0.0f)) continue;
        for (std::size_t r = 0; r < 3; ++r)
            out[3 * i + r] = float(c.worldToCamera[r][0] * n.x + c.worldToCamera[r][1] * n.y +
                                   c.worldToCamera[r][2] * n.z);
    }
    return out;
}

std::string png8(const std::vector<std::uint8_t>& values, int w, int h, int channels,
                 const std::string& path) {
    std::vector<std::uint8_t> bytes;
    if (!core::stbEncodePng(values.data(), w, h, channels, w * channels, bytes))
        throw Error("PNG encoding failed", {.file = path});
    return std::string(bytes.begin(), bytes.end());
}

std::string png16(const std::vector<std::uint32_t>& values, int w, int h) {
    Image16 image{w, h, {}};
    image.values.assign(values.begin(), values.end());  // numbers are at most 65535
    return encodePNG16(image);
}

OrderedJson keypointsJSON(const std::vector<dataset::LeafKeypoints>& keypoints,
                          const dataset::SampleLabels& labels) {
    std::map<ObjectID, std::uint32_t> instanceOf;
    for (const dataset::Instance& in : labels.instances) instanceOf[in.object] = in.number;
    OrderedJson leaves = OrderedJson::array();
    for (const dataset::LeafKeypoints& kp : keypoints) {
        std::uint32_t instance = 0;
        for (ObjectID id : kp.objects)
            if (const auto it = instanceOf.find(id); it != instanceOf.end() && instance == 0)
                instance = it->second;
        OrderedJson points = OrderedJson::object();
        for (std::size_t j = 0; j < 2; ++j)
            points[j == 0 ? "base" : "tip"] = {
                {"world", {kp.world[j].x, kp.world[j].y, kp.world[j].z}},
                {"pixel", {kp.pixel[j][0], kp.pixel[j][1]}},
                {"depth", kp.depth[j]},
                {"visibility", kp.visibility[j]}};
        leaves.push_back({{"plant_instance", kp.plant},
                          {"object_ids", kp.objects},
                          {"instance", instance},
                          {"shoot", kp.shoot},
                          {"node", kp.node},
                          {"leaf_id", kp.leafID},
                          {"base", points["base"]},
                          {"tip", points["tip"]}});
    }
    return {{"keypoints", {"base", "tip"}}, {"leaves", leaves}};
}

OrderedJson metadataJSON(const DatasetSpec& spec, const DatasetSample& s,
                         const PlantArchitecture& arch, const BuiltProject& built,
                         const dataset::SampleLabels& labels) {
    const RenderOptions& o = s.render;
    OrderedJson plants = OrderedJson::array();
    int number = 0;
    for (std::size_t b = 0; b < built.blockPlants.size(); ++b)
        for (unsigned id : built.blockPlants[b]) {
            const PlantInstance& p = arch.plant(id);
            plants.push_back({{"plant_instance", ++number},
                              {"plant_id", id},
                              {"block", s.project.blocks[b].name},
                              {"species", s.project.blocks[b].species},
                              {"base", {p.base.x, p.base.y, p.base.z}},
                              {"age", p.age}});
        }
    OrderedJson instances = OrderedJson::array();
    const std::vector<std::string> names = dataset::categoryNames();
    for (const dataset::Instance& in : labels.instances)
        instances.push_back(
            {{"instance", in.number},
             {"object_id", in.object},
             {"category", in.category > 0 ? names[std::size_t(in.category - 1)] : "unlabelled"},
             {"plant_instance", in.plant},
             {"plant_id", in.plantID},
             {"shoot", in.shoot},
             {"node", in.node},
             {"leaf_id", in.leafID}});
    OrderedJson categories = OrderedJson::array();
    for (std::size_t i = 0; i < names.size(); ++i)
        categories.push_back({{"id", i + 1}, {"name", names[i]}});
    const OrderedJson render = {
        {"width", o.width},
        {"height", o.height},
        {"samples_per_pixel", o.samplesPerPixel},
        {"eye", {o.camera.eye.x, o.camera.eye.y, o.camera.eye.z}},
        {"target", {o.camera.target.x, o.camera.target.y, o.camera.target.z}},
        {"up", {o.camera.up.x, o.camera.up.y, o.camera.up.z}},
        {"fov", o.camera.fovDeg},
        {"sun_direction", {o.sunDirection.x, o.sunDirection.y, o.sunDirection.z}},
        {"sun_intensity", o.sunIntensity},
        {"sun_angular_radius", o.sunAngularRadiusDeg},
        {"sky_zenith", {o.skyZenithColor.x, o.skyZenithColor.y, o.skyZenithColor.z}},
        {"sky_horizon", {o.skyHorizonColor.x, o.skyHorizonColor.y, o.skyHorizonColor.z}},
        {"sky_intensity", o.skyIntensity},
        {"exposure", o.exposure},
        {"ground_color", {o.groundColor.x, o.groundColor.y, o.groundColor.z}},
        {"ground_variation", o.groundVariation},
        {"ground_patch_size", o.groundPatchSize}};
    return {
        {"dataset", spec.name},     {"sample", s.index},
        {"seed", s.seed},           {"split", s.split},
        {"species", s.species},     {"day_of_year", s.dayOfYear},
        {"solar_hour", s.hour},     {"leaf_hsv", s.leafHSV},
        {"render", render},         {"project", OrderedJson::parse(writeProjectString(s.project))},
        {"categories", categories}, {"plants", plants},
        {"instances", instances},   {"files", dataset::sampleFiles(spec)}};
}

// A folder written file by file and renamed into place; removed on an error, on SIGINT and
// on SIGTERM (its files registered as temporaries until the rename).
class PartialFolder {
public:
    explicit PartialFolder(std::string path) : path_(std::move(path)) {
        // .partial (and the output folder) when this makes them: removed again when empty,
        // on signals too.
        parents_ = makeFoldersForOutputs(fs::path(path_).parent_path().string());
        std::error_code ec;
        fs::remove_all(path_, ec);
        if (!fs::create_directories(path_, ec) && ec)
            throw Error("cannot make a folder: " + ec.message(), {.file = path_});
        folderSlot_ = io::registerTemporaryFolder(path_.c_str());
    }
    ~PartialFolder() {
        std::error_code ec;
        if (!kept_) fs::remove_all(path_, ec);
        release();
        // .partial, when no other run uses it; a folder this made, when it holds nothing.
        fs::remove(fs::path(path_).parent_path(), ec);
        for (auto it = parents_.rbegin(); it != parents_.rend(); ++it) it->remove();
    }
    PartialFolder(const PartialFolder&) = delete;
    PartialFolder& operator=(const PartialFolder&) = delete;

    std::uint64_t write(const std::string& name, std::string_view bytes) {
        const std::string path = (fs::path(path_) / name).string();
        io::writeWholeFile(path, bytes);
        slots_.push_back(io::registerTemporary(path.c_str()));
        return bytes.size();
    }
    std::string path(const std::string& name) const { return (fs::path(path_) / name).string(); }
    std::uint64_t add(const std::string& name) {
        const std::string p = path(name);
        slots_.push_back(io::registerTemporary(p.c_str()));
        return fs::file_size(p);
    }
    // Renames the folder to `target`; false when the target exists (another run made it).
    bool keepAs(const std::string& target) {
        if (::rename(path_.c_str(), target.c_str()) != 0) {
            if (errno == EEXIST || errno == ENOTEMPTY) return false;
            throw Error(std::string("cannot rename the finished sample into place: ") +
                            std::strerror(errno),
                        {.file = target});
        }
        kept_ = true;
        release();
        return true;
    }

private:
    void release() {
        for (int s : slots_) io::unregisterTemporary(s);
        slots_.clear();
        io::unregisterTemporaryFolder(folderSlot_);
        folderSlot_ = -1;
    }
    std::string path_;
    std::vector<FolderMadeForOutputs> parents_;
    std::vector<int> slots_;
    int folderSlot_ = -1;
    bool kept_ = false;
};

// What a sample's files are made from, once it is built, seen and labelled.
struct SampleViews {
    const Context& ctx;
    const PlantArchitecture& arch;
    const std::vector<unsigned>& plants;
    const RenderScene& scene;
    const CameraFrame& frame;
    const CameraMatrices& matrices;
    const SurfaceImage& surfaces;
    const dataset::SampleLabels& labels;
    const std::vector<dataset::LeafKeypoints>& keypoints;
    const OrderedJson& coco;
};

// Writes the files of the spec's outputs into `folder`; returns their bytes.
std::uint64_t writeOutputs(const DatasetSpec& spec, const DatasetSample& s, const SampleViews& v,
                           PartialFolder& folder, const std::string& target) {
    const RenderOptions& o = s.render;
    const int w = o.width, h = o.height;
    std::uint64_t bytes = 0;
    for (DatasetOutput out : spec.outputs) switch (out) {
            case DatasetOutput::RGB:
                bytes += folder.write("rgb.png", encodePNG(v.scene.render(o)));
                break;
            case DatasetOutput::Semantic:
                bytes += folder.write("semantic.png", png8(v.labels.semantic, w, h, 1, target));
                break;
            case DatasetOutput::OrganInstances:
                bytes += folder.write("organ_instances.png", png16(v.labels.organMask, w, h));
                break;
            case DatasetOutput::PlantInstances:
                bytes += folder.write("plant_instances.png", png16(v.labels.plantMask, w, h));
                break;
            case DatasetOutput::Depth:
                writeNPY(v.surfaces.depth, {std::size_t(h), std::size_t(w)},
                         folder.path("depth.npy"));
                bytes += folder.add("depth.npy");
                break;
            case DatasetOutput::Normals: {
                const std::vector<float> n = cameraNormals(v.surfaces, v.matrices);
                writeNPY(n, {std::size_t(h), std::size_t(w), 3}, folder.path("normals.npy"));
                bytes += folder.add("normals.npy");
                std::vector<std::uint8_t> picture(n.size(), 0);
                for (std::size_t i = 0; i < n.size(); ++i)
                    if (v.surfaces.normal[i / 3] != vec3(0.0f))
                        picture[i] = std::uint8_t(std::lround(127.5f * (n[i] + 1.0f)));
                bytes += folder.write("normals.png", png8(picture, w, h, 3, target));
                break;
            }
            case DatasetOutput::Camera:
                bytes += folder.write("camera.json", cameraJSON(v.frame, w, h));
                break;
            case DatasetOutput::COCO:
                bytes += folder.write("coco.json", v.coco.dump() + "\n");
                break;
            case DatasetOutput::YOLO:
                bytes += folder.write("yolo.txt", dataset::sampleYOLO(v.coco, w, h));
                break;
            case DatasetOutput::Keypoints:
                bytes += folder.write("keypoints.json",
                                      keypointsJSON(v.keypoints, v.labels).dump(1) + "\n");
                break;
            case DatasetOutput::Points: {
                PointSampleOptions po;
                po.points = spec.points;
                po.seed = s.seed;
                writePointCloudPLY(samplePoints(v.ctx, po), folder.path("points.ply"));
                bytes += folder.add("points.ply");
                break;
            }
            case DatasetOutput::Scan: {
                ScanOptions so;
                Scanner scanner;
                scanner.origin = o.camera.eye;
                scanner.resolution = spec.scanResolution;
                scanner.zenithMin = 0.0f;
                scanner.zenithMax = 180.0f;
                so.scanners.push_back(scanner);
                so.seed = s.seed;
                writePointCloudPLY(scan(v.ctx, so), folder.path("scan.ply"));
                bytes += folder.add("scan.ply");
                break;
            }
            case DatasetOutput::PlantXML:
                bytes += folder.write("plants.xml",
                                      getPlantStructureXML(v.arch, v.plants, {.objectIDs = true}));
                break;
        }
    return bytes;
}

std::string partialName(const std::string& name) {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    // The host and process, and a number of this process's own: two threads making the
    // same sample at once write into folders of their own (the first rename wins).
    static std::atomic<std::uint64_t> made{0};
    return fmt::format("{}.{}.{}.{}", name, host[0] ? host : "host", ::getpid(), made++);
}

}  // namespace

DatasetSampleResult writeDatasetSample(const DatasetSpec& spec, std::size_t index,
                                       const std::string& outDir,
                                       const DatasetWriteOptions& options) {
    if (index >= kMaxDatasetSamples)
        throw Error("sample index out of range",
                    {.parameter = "index",
                     .value = std::to_string(index),
                     .validRange = "0 to " + std::to_string(kMaxDatasetSamples - 1)});
    const std::string name = datasetSampleName(index);
    const std::string samples = dataset::samplesFolder(outDir);
    const std::string target = (fs::path(samples) / name).string();
    DatasetSampleResult result;
    result.index = index;
    DatasetSample s = drawDatasetSample(spec, index);
    result.split = s.split;
    std::error_code ec;
    if (fs::exists(target, ec)) {
        if (!options.resume)
            throw Error("the sample exists (resume with --resume, or write elsewhere)",
                        {.file = target});
        result.skipped = true;
        return result;
    }
    Context ctx;
    PlantArchitecture arch(&ctx);
    ProjectBuildOptions build;
    build.progress = options.progress;
    build.maxTriangles = spec.maxTriangles;
    BuiltProject built;
    try {
        built = buildProject(s.project, arch, build);
    } catch (const Error& e) {
        throw Error("sample " + name + ": " + e.message(), {.file = e.file(),
                                                            .line = e.line(),
                                                            .parameter = e.parameter(),
                                                            .value = e.value(),
                                                            .validRange = e.validRange()});
    }
    varyLeafColours(ctx, s.leafHSV);
    const std::vector<unsigned> plants = built.plants();
    RenderSceneOptions sceneOptions;
    sceneOptions.bvhQuality = RenderSceneOptions::BvhQuality::Low;
    const RenderScene scene(ctx, sceneOptions);
    fixCamera(s, scene, built, arch, spec);
    const RenderOptions& o = s.render;
    const CameraFrame frame{o.camera.eye, o.camera.target, o.camera.up, o.camera.fovDeg};
    const CameraMatrices matrices = cameraMatrices(frame, o.width, o.height);
    const SurfaceImage surfaces = scene.renderSurfaces(o);
    const dataset::SampleLabels labels = dataset::labelPixels(arch, plants, surfaces);
    const std::vector<dataset::LeafKeypoints> keypoints =
        dataset::leafKeypoints(arch, plants, matrices, o.camera.eye, scene, o.width, o.height);
    const OrderedJson coco = dataset::sampleCOCO(spec, s, labels, keypoints);

    PartialFolder folder((fs::path(outDir) / ".partial" / partialName(name)).string());
    const SampleViews views{ctx,      arch,     plants, scene,     frame,
                            matrices, surfaces, labels, keypoints, coco};
    std::uint64_t bytes = writeOutputs(spec, s, views, folder, target);
    bytes +=
        folder.write("metadata.json", metadataJSON(spec, s, arch, built, labels).dump(1) + "\n");
    fs::create_directories(samples, ec);
    if (!fs::is_directory(samples))
        throw Error("cannot make the samples folder" + (ec ? ": " + ec.message() : ""),
                    {.file = samples});
    if (!folder.keepAs(target)) {
        if (!options.resume)
            throw Error("the sample was written meanwhile by another run", {.file = target});
        result.skipped = true;
        return result;
    }
    result.bytes = bytes;
    result.plants = plants.size();
    result.triangles = ctx.triangleCount();
    result.annotations = coco["annotations"].size();
    return result;
}

std::vector<std::size_t> datasetShard(std::size_t samples, std::size_t k, std::size_t n) {
    if (n == 0 || k >= n)
        throw Error("shard out of range", {.parameter = "shard",
                                           .value = std::to_string(k) + "/" + std::to_string(n),
                                           .validRange = "K/N with 0 <= K < N"});
    std::vector<std::size_t> out;
    for (std::size_t i = k; i < samples; i += n) out.push_back(i);
    return out;
}

}  // namespace plantarch
