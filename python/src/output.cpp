// Exporters (OBJ, PLY, plant label table), the renderer (images as numpy arrays) and the
// species library directory.

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "plantarch/Scan.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::python {

namespace {

py::array_t<std::uint8_t> imageArray(Image&& image) {
    auto* owned = new Image(std::move(image));
    py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
    return py::array_t<std::uint8_t>(
        {std::size_t(owned->height), std::size_t(owned->width), std::size_t(3)},
        {std::size_t(owned->width) * 3, std::size_t(3), std::size_t(1)}, owned->rgb.data(), owner);
}

/// A point cloud as numpy arrays viewing one owned copy.
py::dict cloudArrays(PointCloud&& cloud) {
    auto* owned = new PointCloud(std::move(cloud));
    py::capsule owner(owned, [](void* p) { delete static_cast<PointCloud*>(p); });
    const std::size_t n = owned->positions.size();
    py::dict out;
    out["positions"] =
        py::array_t<float>({n, std::size_t(3)}, {12, 4}, &owned->positions.data()->x, owner);
    out["normals"] =
        py::array_t<float>({n, std::size_t(3)}, {12, 4}, &owned->normals.data()->x, owner);
    out["plant_id"] = py::array_t<std::int32_t>({n}, {4}, owned->plantID.data(), owner);
    out["object_id"] = py::array_t<std::uint32_t>({n}, {4}, owned->objectID.data(), owner);
    out["organ"] = py::array_t<std::uint8_t>({n}, {1}, owned->organ.data(), owner);
    out["leaf_id"] = py::array_t<std::int32_t>({n}, {4}, owned->leafID.data(), owner);
    out["shoot_id"] = py::array_t<std::int32_t>({n}, {4}, owned->shootID.data(), owner);
    out["rank"] = py::array_t<std::int32_t>({n}, {4}, owned->rank.data(), owner);
    out["age"] = py::array_t<float>({n}, {4}, owned->age.data(), owner);
    if (!owned->range.empty()) {
        out["range"] = py::array_t<float>({n}, {4}, owned->range.data(), owner);
        out["scanner"] = py::array_t<std::uint16_t>({n}, {2}, owned->scanner.data(), owner);
    }
    return out;
}

Image imageFrom(const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
    if (a.ndim() != 3 || a.shape(2) != 3)
        throw Error("wrong array shape",
                    {.parameter = "image", .validRange = "height x width x 3 uint8"});
    Image image(int(a.shape(1)), int(a.shape(0)));
    std::memcpy(image.rgb.data(), a.data(), image.rgb.size());
    return image;
}

RenderMode modeNamed(const std::string& mode) {
    if (mode == "shaded") return RenderMode::Shaded;
    if (mode == "organ") return RenderMode::LabelOrgan;
    if (mode == "object") return RenderMode::LabelObject;
    throw Error(
        "unknown render mode",
        {.parameter = "mode", .value = mode, .validRange = "one of: shaded, organ, object"});
}

// The camera of a render call: orbit angles around the auto-framed scene, or a fixed eye
// (with a target, the scene's centre when none is given, and an up direction).
struct CameraArgs {
    float azimuth, elevation, fov;
    py::object eye, target, up;
};

Camera cameraOf(const CameraArgs& a) {
    Camera c;
    c.azimuthDeg = a.azimuth;
    c.elevationDeg = a.elevation;
    c.fovDeg = a.fov;
    if (!a.eye.is_none()) {
        c.autoFrame = false;
        c.eye = toVec3(a.eye, "eye");
        if (!a.target.is_none()) c.target = toVec3(a.target, "target");
        c.up = toVec3(a.up, "up");
    } else if (!a.target.is_none()) {
        throw Error("a target needs an eye",
                    {.parameter = "target", .validRange = "eye=(x, y, z) with target"});
    }
    return c;
}

// The options' camera made whole for `scene`: a fixed eye without a target looks at the
// scene's centre.
void aimAtScene(RenderOptions& o, const CameraArgs& a, const RenderScene& scene) {
    if (!o.camera.autoFrame && a.target.is_none()) o.camera.target = scene.bounds().center();
}

py::dict cameraDict(const CameraFrame& f, int width, int height) {
    const CameraMatrices m = cameraMatrices(f, width, height);
    py::dict d;
    d["width"] = width;
    d["height"] = height;
    d["eye"] = f.eye;
    d["target"] = f.target;
    d["up"] = f.up;
    d["fov_y_deg"] = f.fovDeg;
    d["K"] = m.K;
    d["world_to_camera"] = m.worldToCamera;
    return d;
}

}  // namespace

/// The materials keyword arguments of the writers (`appearance`, `texture_size`, `atlas`),
/// checked as the command line checks --materials and --texture-size.
MaterialOptions appearanceOf(const std::string& style, const py::object& size, bool atlas) {
    const std::optional<MaterialStyle> s = materialStyleFromName(style);
    if (!s)
        throw Error("unknown material style",
                    {.parameter = "appearance", .value = style, .validRange = "flat, textured"});
    const std::string range = "a power of two from 16 to 4096";
    const std::string text = py::str(size).cast<std::string>();
    if (!py::isinstance<py::int_>(size) || py::isinstance<py::bool_>(size))
        throw Error("texture size is a whole number of texels",
                    {.parameter = "texture_size", .value = text, .validRange = range});
    long long n = 0;
    try {
        n = py::int_(size).cast<long long>();
    } catch (const py::cast_error&) {
        n = kMaxTextureSize + 1;  // past 64 bits
    }
    if (n < kMinTextureSize || n > kMaxTextureSize)
        throw Error("texture size " + text + " is not allowed",
                    {.parameter = "texture_size", .value = text, .validRange = range});
    const MaterialOptions o{*s, int(n), atlas};
    checkMaterialOptions(o);
    return o;
}

/// The node level of the writers' `nodes` keyword ("plant", "kind", "organ"), as --nodes.
NodeLevel nodeLevelOf(const std::string& name) {
    const std::optional<NodeLevel> level = nodeLevelFromName(name);
    if (!level)
        throw Error("unknown node level",
                    {.parameter = "nodes", .value = name, .validRange = "plant, kind, organ"});
    return *level;
}

Instancing instancingOf(const std::string& name) {
    const std::optional<Instancing> instancing = instancingFromName(name);
    if (!instancing)
        throw Error("unknown instancing",
                    {.parameter = "instancing", .value = name, .validRange = "none, shared, gpu"});
    return *instancing;
}

/// The skeletons of the writers' `skin=True` (exportSkeletons), which needs the architecture.
std::vector<GltfSkeleton> skeletonsOf(const py::object& architecture) {
    if (architecture.is_none())
        throw Error("a skin needs the plants: give architecture=",
                    {.parameter = "skin",
                     .value = "True",
                     .validRange = "skin=True with architecture=<PlantArchitecture>"});
    return exportSkeletons(architecture.cast<const PlantArchitecture&>());
}

void bindOutput(py::module_& m) {
    py::class_<ObjOptions>(m, "ObjOptions", "Options of writeOBJ.")
        .def(py::init([](bool hidden, bool normals, bool uvs, bool materials, bool split) {
                 ObjOptions o;
                 o.includeHidden = hidden;
                 o.normals = normals;
                 o.uvs = uvs;
                 o.materials = materials;
                 o.splitPerObject = split;
                 return o;
             }),
             py::kw_only(), py::arg("include_hidden") = false, py::arg("normals") = true,
             py::arg("uvs") = true, py::arg("materials") = true,
             py::arg("split_per_object") = false)
        .def_readwrite("includeHidden", &ObjOptions::includeHidden, "also write hidden objects")
        .def_readwrite("normals", &ObjOptions::normals, "smooth per-vertex normals (vn)")
        .def_readwrite("uvs", &ObjOptions::uvs, "texture coordinates of objects that have them")
        .def_readwrite("materials", &ObjOptions::materials, "the .mtl library and usemtl lines")
        .def_readwrite("splitPerObject", &ObjOptions::splitPerObject,
                       "one OBJ file per object in the folder the path names");
    m.def(
        "writeOBJ",
        [](const Context& c, const std::string& path, const ObjOptions& options) {
            py::gil_scoped_release release;
            writeOBJ(c, path, options);
        },
        py::arg("context"), py::arg("filename"), py::arg("options"),
        inPython(
            docs::writeOBJ,
            "Writes the Context as OBJ (+ MTL) with the options of an ObjOptions, atomically."));
    m.def(
        "writeOBJ",
        [](const Context& c, const std::string& path, bool includeHidden, bool normals, bool uvs,
           bool materials, bool splitPerObject, const std::string& appearance,
           const py::object& textureSize, bool atlas) {
            ObjOptions o{includeHidden, normals, uvs, materials, splitPerObject};
            o.appearance = appearanceOf(appearance, textureSize, atlas);
            py::gil_scoped_release release;
            writeOBJ(c, path, o);
        },
        py::arg("context"), py::arg("filename"), py::arg("include_hidden") = false,
        py::arg("normals") = true, py::arg("uvs") = true, py::arg("materials") = true,
        py::arg("split_per_object") = false, py::arg("appearance") = "flat",
        py::arg("texture_size") = 512, py::arg("atlas") = true,
        inPython(docs::writeOBJ,
                 "Writes the Context as OBJ (+ MTL) with one group per object, atomically. "
                 "`appearance` 'textured': procedural texture maps (PNG files beside the .mtl, "
                 "`texture_size` texels a side) in the .mtl, as the command line's --materials; "
                 "`atlas` False: an image per leaf material, as --no-texture-atlas."));
    m.def(
        "writePLY",
        [](const Context& c, const std::string& path, bool ascii, bool includeHidden, bool normals,
           const std::string& color) {
            const std::optional<PlyColor> mode = plyColorFromName(color);
            if (!mode)
                throw Error("unknown PLY colour", {.parameter = "color",
                                                   .value = color,
                                                   .validRange = "none, organ, plant, material"});
            py::gil_scoped_release release;
            writePLY(c, path,
                     {ascii ? PlyFormat::Ascii : PlyFormat::BinaryLittleEndian, includeHidden,
                      normals, *mode});
        },
        py::arg("context"), py::arg("filename"), py::arg("ascii") = false,
        py::arg("include_hidden") = false, py::arg("normals") = false, py::arg("color") = "none",
        inPython(
            docs::writePLY,
            "Writes the Context as PLY with per-face labels (plant, object, organ, leaf, shoot, "
            "rank, node, age) and, with color 'organ', 'plant' or 'material', vertex colours, "
            "atomically."));
    m.def(
        "writeGLTF",
        [](const Context& c, const std::string& path, py::object architecture, bool includeHidden,
           bool normals, bool uvs, bool labels, const std::string& lod, bool meshopt,
           const std::string& appearance, const py::object& textureSize, bool skin,
           const std::string& nodes, const std::string& instancing, float wind, bool atlas) {
            GltfOptions o;
            o.appearance = appearanceOf(appearance, textureSize, atlas);
            o.nodes = nodeLevelOf(nodes);
            o.instancing = instancingOf(instancing);
            o.includeHidden = includeHidden;
            o.normals = normals;
            o.uvs = uvs;
            o.labels = labels;
            o.levels = parseGltfLevels(lod);  // levels of detail, as the CLI's --lod
            o.meshoptCompression = meshopt;
            if (!architecture.is_none())
                o.plants = exportPlants(architecture.cast<const PlantArchitecture&>());
            if (skin || wind > 0.0f) o.skeletons = skeletonsOf(architecture);
            o.windDegrees = wind;
            py::gil_scoped_release release;
            writeGLTF(c, path, o);
        },
        py::arg("context"), py::arg("filename"), py::arg("architecture") = py::none(),
        py::arg("include_hidden") = false, py::arg("normals") = true, py::arg("uvs") = true,
        py::arg("labels") = true, py::arg("lod") = "", py::arg("meshopt") = false,
        py::arg("appearance") = "flat", py::arg("texture_size") = 512, py::arg("skin") = false,
        py::arg("nodes") = "kind", py::arg("instancing") = "shared", py::arg("wind") = 0.0f,
        py::arg("atlas") = true,
        inPython(
            docs::writeGLTF,
            "Writes the Context as glTF 2.0 (.glb binary or .gltf text), atomically: a node per "
            "plant (named, placed and described from `architecture` when given), a mesh per organ "
            "kind, labels as vertex attributes and EXT_mesh_features / EXT_structural_metadata. "
            "`lod`: levels of detail as MSFT_lod, as the command line's --lod (e.g. "
            "'reduced,cards'); `meshopt`: EXT_meshopt_compression; `appearance` 'textured': PBR "
            "materials with procedural textures embedded, `texture_size` texels a side (16 to "
            "4096, a power of two), leaves' maps in one atlas unless `atlas` is False, as the "
            "command line's --materials, --texture-size and --no-texture-atlas; "
            "`skin`: a wind-ready skeleton per plant of `architecture` (a glTF skin: a joint per "
            "internode, per-vertex weights), as the command line's --skin; `wind`: degrees of a "
            "looping 'wind' animation swaying it (implies skin), as --wind; `nodes` 'plant', "
            "'kind' or 'organ' (a node per shoot and organ, named and labelled); `instancing` "
            "with 'organ': 'shared' (organs of one shape point at one mesh), 'gpu' "
            "(EXT_mesh_gpu_instancing, one node per shared shape) or 'none', as --nodes and "
            "--instancing."));
    m.def(
        "writeUSDA",
        [](const Context& c, const std::string& path, py::object architecture, bool includeHidden,
           bool normals, bool uvs, const std::string& appearance, const py::object& textureSize,
           bool skin, const std::string& nodes, const std::string& instancing, bool atlas) {
            UsdOptions o;
            o.appearance = appearanceOf(appearance, textureSize, atlas);
            o.nodes = nodeLevelOf(nodes);
            o.instancing = instancingOf(instancing);
            o.includeHidden = includeHidden;
            o.normals = normals;
            o.uvs = uvs;
            if (!architecture.is_none())
                o.plants = exportPlants(architecture.cast<const PlantArchitecture&>());
            if (skin) o.skeletons = skeletonsOf(architecture);
            py::gil_scoped_release release;
            writeUSDA(c, path, o);
        },
        py::arg("context"), py::arg("filename"), py::arg("architecture") = py::none(),
        py::arg("include_hidden") = false, py::arg("normals") = true, py::arg("uvs") = true,
        py::arg("appearance") = "flat", py::arg("texture_size") = 512, py::arg("skin") = false,
        py::arg("nodes") = "kind", py::arg("instancing") = "shared", py::arg("atlas") = true,
        inPython(
            docs::writeUSDA,
            "Writes the Context as USD text (.usda), or a .usdz package, atomically: an Xform per "
            "plant (placed and described from `architecture` when given), a Mesh per organ kind "
            "with normals, UVs, per-face organ/plantID/objectID primvars and semantic class "
            "labels. `appearance` 'textured': UsdPreviewSurface materials with procedural "
            "textures (PNG files beside the .usda, or inside the .usdz); `skin`: UsdSkel, a "
            "skeleton per plant of `architecture`, as the command line's --skin; `nodes` and "
            "`instancing` as for writeGLTF (a prim per organ); `atlas` as for writeGLTF."));
    m.def(
        "samplePoints",
        [](const Context& c, std::size_t points, std::uint64_t seed, bool includeHidden) {
            PointCloud cloud;
            {
                py::gil_scoped_release release;
                cloud = samplePoints(c, {points, seed, includeHidden});
            }
            return cloudArrays(std::move(cloud));
        },
        py::arg("context"), py::arg("points") = 100000, py::arg("seed") = 0,
        py::arg("include_hidden") = false,
        inPython(docs::samplePoints,
                 "A labelled point cloud: `points` points drawn uniformly by area over the visible "
                 "triangles, as numpy arrays positions (N x 3), normals (N x 3), plant_id, "
                 "object_id and "
                 "organ (an index into ORGAN_LABELS). Same seed, same points; numpy.savez writes "
                 "them."));
    m.def(
        "scan",
        [](const Context& c, const std::vector<vec3>& scanners, float resolution,
           std::pair<float, float> zenith, std::pair<float, float> azimuth, float noise,
           float maxRange, std::uint64_t seed) {
            ScanOptions o;
            for (const vec3& at : scanners)
                o.scanners.push_back(
                    {at, zenith.first, zenith.second, azimuth.first, azimuth.second, resolution});
            o.rangeNoise = noise;
            o.maxRange = maxRange;
            o.seed = seed;
            PointCloud cloud;
            {
                py::gil_scoped_release release;
                cloud = scan(c, o);
            }
            return cloudArrays(std::move(cloud));
        },
        py::arg("context"), py::arg("scanners"), py::arg("resolution") = 0.1f,
        py::arg("zenith") = std::pair<float, float>(30.0f, 150.0f),
        py::arg("azimuth") = std::pair<float, float>(0.0f, 360.0f), py::arg("noise") = 0.0f,
        py::arg("max_range") = 100.0f, py::arg("seed") = 0,
        inPython(
            docs::scan,
            "A simulated terrestrial LiDAR scan: rays from each scanner position (x, y, z) every "
            "`resolution` degrees over the zenith (from straight up) and azimuth (from +x) ranges; "
            "the first hit of each, as numpy arrays positions, normals (toward the scanner), "
            "plant_id, object_id, organ, range (m, with Gaussian noise of sd `noise`) and "
            "scanner."));
    m.def(
        "writePointCloudPLY",
        [](const Context& c, const std::string& path, std::size_t points, std::uint64_t seed) {
            py::gil_scoped_release release;
            writePointCloudPLY(samplePoints(c, {points, seed, false}), path);
        },
        py::arg("context"), py::arg("filename"), py::arg("points") = 100000, py::arg("seed") = 0,
        inPython(docs::writePointCloudPLY,
                 "Samples a labelled point cloud and writes it as a binary PLY of vertices."));
    m.def(
        "writeQSM",
        [](const PlantArchitecture& a, const std::string& path, py::object plantIDs) {
            const std::vector<unsigned> plants =
                plantIDs.is_none() ? a.getAllPlantIDs() : idList(plantIDs, "plantIDs");
            py::gil_scoped_release release;
            writeQSM(a, plants, path);
        },
        py::arg("architecture"), py::arg("filename"), py::arg("plantIDs") = py::none(),
        inPython(
            docs::writeQSM,
            "Writes the plants' internodes (all plants by default) as QSM cylinders, CSV: id, "
            "parent, plant, start, axis, length, radius, branch, branch order, position, type."));
    m.def(
        "readOBJ", [](Context& c, const std::string& path) { return readOBJ(c, path); },
        py::arg("context"), py::arg("filename"),
        inPython(docs::readOBJ,
                 "Adds the objects of an OBJ file (obstacles, ground); returns their IDs."));
    m.def(
        "readPLY",
        [](Context& c, const std::string& path, bool labels) {
            return readPLY(c, path, {.labels = labels});
        },
        py::arg("context"), py::arg("filename"), py::arg("labels") = true,
        inPython(docs::readPLY,
                 "Adds the mesh of a PLY file (ASCII or binary): one object per object_id with the "
                 "labels writePLY writes, or one object; returns their IDs."));
    m.def("readGLTF", &readGLTF, py::arg("context"), py::arg("filename"),
          inPython(
              docs::readGLTF,
              "Adds the triangle meshes of a glTF scene (.glb, or .gltf with embedded buffers), z "
              "up: one object per _OBJECT_ID with plantID and organ in files plantarch wrote; "
              "returns their IDs."));
    m.def("readObstacleMesh", &readObstacleMesh, py::arg("context"), py::arg("filename"),
          inPython(docs::readObstacleMesh,
                   "Adds an obstacle mesh (.obj or .ply) without labels, its objects with organ "
                   "'obstacle'; returns their IDs."));
    m.def(
        "render",
        [](const Context& c, int width, int height, const std::string& mode, float azimuth,
           float elevation, float fov, int samples, bool ground, std::uint64_t seed, py::object eye,
           py::object target, py::object up, const std::string& appearance,
           const py::object& textureSize, bool atlas) {
            const CameraArgs args{azimuth, elevation, fov, eye, target, up};
            RenderOptions o;
            o.width = width;
            o.height = height;
            o.scene.appearance = appearanceOf(appearance, textureSize, atlas);
            o.mode = modeNamed(mode);
            o.camera = cameraOf(args);
            o.samplesPerPixel = samples;
            o.groundPlane = ground;
            o.seed = seed;
            Image image;
            {
                py::gil_scoped_release release;
                const RenderScene scene(c, o.scene);
                aimAtScene(o, args, scene);
                image = scene.render(o);
            }
            return imageArray(std::move(image));
        },
        py::arg("context"), py::arg("width") = 640, py::arg("height") = 480,
        py::arg("mode") = "shaded", py::arg("azimuth") = -60.0f, py::arg("elevation") = 22.0f,
        py::arg("fov") = 35.0f, py::arg("samples_per_pixel") = 4, py::arg("ground") = true,
        py::arg("seed") = 0, py::arg("eye") = py::none(), py::arg("target") = py::none(),
        py::arg("up") = vec3(0.0f, 0.0f, 1.0f), py::arg("appearance") = "flat",
        py::arg("texture_size") = 512, py::arg("atlas") = true,
        inPython(
            docs::render,
            "Renders the Context as a height x width x 3 uint8 array. mode: 'shaded', 'organ' "
            "(label colours per organ) or 'object' (one colour per object ID; "
            "objectIDsFromLabelImage decodes it). The camera is framed on the scene from azimuth "
            "and elevation (degrees), or fixed with eye=(x, y, z), target (default: the scene's "
            "centre) and up: a fixed camera frames every call alike. renderCamera gives its "
            "matrices. appearance='textured': the procedural leaf, bark and stem textures of "
            "the exporters (texture_size texels a side)."));
    m.def(
        "renderCamera",
        [](const Context& c, int width, int height, float azimuth, float elevation, float fov,
           py::object eye, py::object target, py::object up) {
            const CameraArgs args{azimuth, elevation, fov, eye, target, up};
            RenderOptions o;
            o.width = width;
            o.height = height;
            o.camera = cameraOf(args);
            CameraFrame frame;
            {
                py::gil_scoped_release release;
                const RenderScene scene(c, o.scene);
                aimAtScene(o, args, scene);
                frame = scene.camera(o);
            }
            return cameraDict(frame, width, height);
        },
        py::arg("context"), py::arg("width") = 640, py::arg("height") = 480,
        py::arg("azimuth") = -60.0f, py::arg("elevation") = 22.0f, py::arg("fov") = 35.0f,
        py::arg("eye") = py::none(), py::arg("target") = py::none(),
        py::arg("up") = vec3(0.0f, 0.0f, 1.0f),
        "The camera render() and renderDepth() use with the same arguments, as a dict: eye, "
        "target, up, fov_y_deg, width, height, intrinsics K (3 x 3) and extrinsics "
        "world_to_camera (4 x 4), in OpenCV's pinhole convention (x right, y down, z forward, "
        "pixel centres at whole coordinates).");
    m.def(
        "renderDepth",
        [](const Context& c, int width, int height, float azimuth, float elevation, float fov,
           bool ground, py::object eye, py::object target, py::object up) {
            const CameraArgs args{azimuth, elevation, fov, eye, target, up};
            RenderOptions o;
            o.width = width;
            o.height = height;
            o.camera = cameraOf(args);
            o.groundPlane = ground;
            auto* owned = new DepthImage;
            {
                py::gil_scoped_release release;
                try {
                    const RenderScene scene(c, o.scene);
                    aimAtScene(o, args, scene);
                    *owned = scene.renderDepth(o);
                } catch (...) {
                    delete owned;
                    throw;
                }
            }
            py::capsule owner(owned, [](void* p) { delete static_cast<DepthImage*>(p); });
            return py::array_t<float>({std::size_t(owned->height), std::size_t(owned->width)},
                                      {std::size_t(owned->width) * sizeof(float), sizeof(float)},
                                      owned->depth.data(), owner);
        },
        py::arg("context"), py::arg("width") = 640, py::arg("height") = 480,
        py::arg("azimuth") = -60.0f, py::arg("elevation") = 22.0f, py::arg("fov") = 35.0f,
        py::arg("ground") = true, py::arg("eye") = py::none(), py::arg("target") = py::none(),
        py::arg("up") = vec3(0.0f, 0.0f, 1.0f),
        inPython(
            docs::renderDepth,
            "The depth image of the camera render() would use: a height x width float32 array of "
            "distances along the view axis in metres, 0 where nothing is hit."));
    m.def(
        "objectIDsFromLabelImage",
        [](const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
            if (a.ndim() != 3 || a.shape(2) != 3)
                throw Error("a label image is height x width x 3",
                            {.parameter = "image", .validRange = "an array of shape (h, w, 3)"});
            const auto h = std::size_t(a.shape(0)), w = std::size_t(a.shape(1));
            py::array_t<std::int64_t> ids({h, w});
            const std::uint8_t* in = a.data();
            std::int64_t* out = ids.mutable_data();
            for (std::size_t i = 0; i < h * w; ++i) {
                const auto id = objectIDFromLabelColor({in[3 * i], in[3 * i + 1], in[3 * i + 2]});
                out[i] = id ? std::int64_t(*id) : -1;
            }
            return ids;
        },
        py::arg("image"),
        "The object ID of every pixel of a render(mode='object') image as a height x width "
        "int64 array, -1 where no object is (black).");
    m.def(
        "cocoAnnotations",
        [](const Context& c,
           const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a,
           const std::string& imageFile) { return cocoAnnotations(c, imageFrom(a), imageFile); },
        py::arg("context"), py::arg("image"), py::arg("image_file") = "image.png",
        inPython(docs::cocoAnnotations,
                 "COCO instance annotations (JSON text) of a render(mode='object') image of the "
                 "Context: one per object in view, its organ as category, object_id and plant_id, "
                 "bounding box and RLE mask; what `plantarch render --coco` writes."));
    m.def(
        "objectIDFromLabelColor",
        [](std::uint8_t r, std::uint8_t g, std::uint8_t b) -> std::optional<ObjectID> {
            return objectIDFromLabelColor({r, g, b});
        },
        py::arg("r"), py::arg("g"), py::arg("b"),
        inPython(docs::objectIDFromLabelColor,
                 "The object ID of one colour of a render(mode='object') image; None for black."));
    m.def(
        "writePNG",
        [](const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a,
           const std::string& path) { writePNG(imageFrom(a), path); },
        py::arg("image"), py::arg("filename"),
        inPython(docs::writePNG, "Writes an image array as PNG, atomically."));
    m.def(
        "encodePNG",
        [](const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
            return py::bytes(encodePNG(imageFrom(a)));
        },
        py::arg("image"), docs::encodePNG);
    m.def(
        "readImage", [](const std::string& path) { return imageArray(readImage(path)); },
        py::arg("filename"), docs::readImage);
    py::class_<GrowthRecorder>(
        m, "GrowthRecorder",
        "Frames of a scene recorded between steps of your own (growth, pruning, harvest), "
        "written as one animation (.glb, .gltf or .usda). Each frame is a copy of the scene.")
        .def(py::init<>())
        .def(
            "record",
            [](GrowthRecorder& r, const PlantArchitecture& a, std::optional<double> day) {
                double d = 0.0;
                if (day)
                    d = *day;
                else
                    for (unsigned id : a.getAllPlantIDs()) d = std::max(d, a.plant(id).age);
                r.record(a, d);
            },
            py::arg("architecture"), py::arg("day") = py::none(),
            "Records the architecture's scene as the next frame at `day` (days, after the last "
            "frame's; by default the oldest plant's age).")
        .def("frameCount", &GrowthRecorder::frameCount, "Frames recorded.")
        .def("days", &GrowthRecorder::days, "The frames' days, in order.")
        .def("clear", &GrowthRecorder::clear, "Forgets every frame.")
        .def(
            "write",
            [](const GrowthRecorder& r, const py::object& filenames, double frameRate) {
                std::vector<std::string> paths;
                if (py::isinstance<py::str>(filenames))
                    paths.push_back(filenames.cast<std::string>());
                else
                    paths = filenames.cast<std::vector<std::string>>();
                r.write(paths, {frameRate});
            },
            py::arg("filenames"), py::arg("frame_rate") = 24.0,
            "Writes the frames into a file or each of a list of files (.glb, .gltf or .usda) "
            "as one animation showing frame i alone at i / frame_rate seconds.");
    m.def("speciesLibraryDirectory", &speciesLibraryDirectory, docs::speciesLibraryDirectory);
    m.def("listSpecies", &listSpecies, docs::listSpecies);
}

}  // namespace plantarch::python
