// plantarch render: ray-casts a scene (an OBJ file, any OBJ, not only ours; or plants from a
// plant structure file or plant strings) into a PNG preview or a segmentation mask, with the
// camera's matrices beside it on request.

#include "plantarch/Render.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {
namespace {

struct RenderArgs {
    std::string input;
    std::string output;
    int width = 1024;
    int height = 768;
    std::string eye, target, orbit;
    float fov = 0.0f;  // 0: the renderer's default
    std::string label;
    std::string coco;
    bool cocoGiven = false;  // --coco '' is refused, not taken for no --coco
    std::string cameraJson;
    bool cameraJsonGiven = false;
    std::string species;
    bool noGround = false;
    int samples = 0;  // 0: the renderer's default
};

// --label: a mask (organ, object), or depth: a depth image, which renderDepth draws.
RenderMode parseMode(const std::string& label) {
    if (label.empty() || label == "depth") return RenderMode::Shaded;
    return labelMode(label, "depth");
}

/// OBJ files written by plantarch name each group obj<ID>[_plant<P>]_<organ> (and carry the
/// organ in their label comments too, which readOBJ reads); restore the organ label from that
/// name when the object has none, so `--label organ` works on exports whose comments were
/// lost (and on those of earlier versions, named obj<ID>_<organ>).
void organsFromNames(Context& ctx, const std::vector<ObjectID>& ids) {
    if (ctx.objectDataType("name") != DataType::String) return;
    const auto organType = ctx.objectDataType("organ");
    if (organType && *organType != DataType::String) return;
    for (ObjectID id : ids) {
        if (ctx.hasObjectData(id, "organ")) continue;
        const auto name = ctx.objectDataString(id, "name");
        if (!name || name->rfind("obj", 0) != 0) continue;
        std::size_t i = 3;
        while (i < name->size() && std::isdigit(static_cast<unsigned char>((*name)[i]))) ++i;
        if (i == 3 || i + 1 >= name->size() || (*name)[i] != '_') continue;
        if (name->compare(i, 6, "_plant") == 0) {  // skip _plant<P>, P may be negative
            std::size_t j = i + 6;
            if (j < name->size() && (*name)[j] == '-') ++j;
            const std::size_t digits = j;
            while (j < name->size() && std::isdigit(static_cast<unsigned char>((*name)[j]))) ++j;
            if (j > digits && j + 1 < name->size() && (*name)[j] == '_') i = j;
        }
        ctx.setObjectData(id, "organ", name->substr(i + 1));
    }
}

int run(const RenderArgs& a, const GlobalOptions& g) {
    const auto start = std::chrono::steady_clock::now();
    requireInputFile(a.input, "scene file");
    const std::string in = lowerExtension(a.input);
    if (in != ".obj" && in != ".ply" && in != ".glb" && in != ".gltf" && in != ".xml" &&
        in != ".txt")
        throw Error("render reads a scene plantarch writes with geometry or plant state",
                    {.file = a.input,
                     .value = in.empty() ? "no extension" : in,
                     .validRange = ".obj, .ply, .glb or .gltf (geometry), .xml (a plant "
                                   "structure or <helios> file), .txt (plant strings, with "
                                   "--species)"});
    const bool depth = a.label == "depth";
    requireOutputFormat(a.output, depth ? kDepthOutput : kPictureOutput,
                        depth ? "a depth image is written as .npy (distances) or .png (a picture)"
                              : "render writes a PNG picture");
    const std::string ext = lowerExtension(a.output);
    RenderOptions o;
    o.width = a.width;
    o.height = a.height;
    o.groundPlane = !a.noGround;
    o.mode = parseMode(a.label);
    o.seed = g.seed;
    o.progress = terminalProgress();
    o.scene.progress = o.progress;
    o.scene.appearance = g.appearance;
    if (a.samples > 0) o.samplesPerPixel = a.samples;
    if (a.fov > 0.0f) o.camera.fovDeg = a.fov;
    if (!a.orbit.empty()) parseOrbit(a.orbit, o.camera);
    if (!a.eye.empty()) {
        o.camera.autoFrame = false;
        o.camera.eye = parseVec3(a.eye, "--eye");
    }
    const bool hasTarget = !a.target.empty();
    if (hasTarget) o.camera.target = parseVec3(a.target, "--target");
    if (hasTarget && a.eye.empty())
        throw Error("--target needs --eye", {.parameter = "--target", .value = a.target});

    // A render's cost is its rays: refused before any work when the options ask for more
    // than one render may cast.
    const RenderOptions cast = depth ? cameraRaysOnly(o) : o;
    if (const std::uint64_t rays = renderRayCount(cast); rays > kMaxRenderRays)
        throw Error(
            fmt::format("{} x {} pixels at {} samples{} are {} rays, too many for one render",
                        o.width, o.height, cast.samplesPerPixel,
                        o.mode == RenderMode::Shaded && !depth ? " with sun and sky rays" : "",
                        rays),
            {.parameter = "--samples",
             .value = std::to_string(cast.samplesPerPixel),
             .validRange = fmt::format("at most {} rays: lower --samples, --width or --height",
                                       kMaxRenderRays)});

    checkMaterialOutputs(g, {a.output});  // material_options.cpp
    // Fail before the costly part when an output could not be written anyway.
    CommandOutputs outputs({a.output});
    if (a.cocoGiven) {
        if (lowerExtension(a.coco) != ".json")
            throw Error(a.coco.empty() ? "COCO annotations need a file name"
                                       : "COCO annotations are written as JSON",
                        {.file = a.coco,
                         .parameter = "--coco",
                         .value = lowerExtension(a.coco),
                         .validRange = ".json"});
        outputs.add(a.coco);
    }
    if (a.cameraJsonGiven) {
        requireOutputFormat(a.cameraJson, {".json"}, "the camera is written as JSON");
        outputs.add(a.cameraJson);
    }
    outputs.requireNotAnInput(a.input);
    Context ctx;
    std::optional<PlantArchitecture> arch;  // holds plants read from a plant file
    if (in == ".obj") {
        const std::vector<ObjectID> ids = readOBJ(ctx, a.input, {.progress = terminalProgress()});
        organsFromNames(ctx, ids);
    } else if (in == ".ply") {
        readPLY(ctx, a.input, {.progress = terminalProgress()});
    } else if (in == ".glb" || in == ".gltf") {
        readGLTF(ctx, a.input);
    } else {
        arch.emplace(&ctx);
        arch->setSeed(g.seed);
        arch->setTriangleLimit(g.maxTriangles);
        arch->setMeshDetail(g.meshDetail);
        readPlantInput(*arch, a.input, a.species);
    }
    info(g, fmt::format("read {}: {} objects, {} triangles", a.input, ctx.objectCount(),
                        ctx.triangleCount()));
    RenderScene scene(ctx, o.scene);
    if (!o.camera.autoFrame && !hasTarget) o.camera.target = scene.bounds().center();
    const auto built = std::chrono::steady_clock::now();
    Image image;
    if (depth) {
        const DepthImage distances = scene.renderDepth(o);
        if (ext == ".npy")
            writeDepthNPY(distances, a.output);
        else
            image = depthPicture(distances);
    } else {
        image = scene.render(o);
    }
    const auto rendered = std::chrono::steady_clock::now();
    if (!image.rgb.empty()) writePNG(image, a.output);
    if (a.cameraJsonGiven) {
        writeWholeFile(a.cameraJson, cameraJSON(scene.camera(o), o.width, o.height));
        info(g, "wrote " + a.cameraJson);
    }
    if (a.cocoGiven) {
        RenderOptions mask = o;
        mask.mode = RenderMode::LabelObject;
        const Image objects = o.mode == RenderMode::LabelObject ? image : scene.render(mask);
        const std::string text =
            cocoAnnotations(ctx, objects, std::filesystem::path(a.output).filename().string());
        writeWholeFile(a.coco, text);
        info(g, "wrote " + a.coco);
    }
    outputs.commit();
    using seconds = std::chrono::duration<double>;
    info(g,
         fmt::format("wrote {} ({}x{}): read and BVH {:.3f} s, rays {:.3f} s", a.output, o.width,
                     o.height, seconds(built - start).count(), seconds(rendered - built).count()));
    return 0;
}

std::function<int()> setupRender(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Render a scene (.obj, .ply, .glb, .gltf, or plants from .xml or .txt) to a PNG (shaded "
        "preview or "
        "segmentation mask)");
    auto args = std::make_shared<RenderArgs>();
    app.add_option("input", args->input,
                   "Scene to render: .obj, .ply, .glb, .gltf, .xml (plant structure or <helios>) "
                   "or .txt (plant "
                   "strings, with --species)")
        ->required();
    app.add_option("--species", args->species,
                   "Species giving the shoot types of plant strings (.txt input)");
    app.add_option("-o,--output", args->output,
                   "PNG file to write (with --label depth: .npy distances or a .png picture)")
        ->required();
    app.add_option("--width", args->width, "Image width in pixels")
        ->check(numberCheck("--width", "a width in pixels", 1, 16384, true, "1 to 16384"))
        ->capture_default_str();
    app.add_option("--height", args->height, "Image height in pixels")
        ->check(numberCheck("--height", "a height in pixels", 1, 16384, true, "1 to 16384"))
        ->capture_default_str();
    app.add_option("--eye", args->eye, "Camera position x,y,z in metres (default: auto-framed)");
    app.add_option("--target", args->target,
                   "Point looked at x,y,z (default: centre of the scene; needs --eye)");
    app.add_option("--orbit", args->orbit,
                   "View from AZIMUTH,ELEVATION degrees, framed on the scene (default -60,22)")
        ->excludes("--eye");
    app.add_option("--fov", args->fov, "Vertical field of view in degrees (default 35)")
        ->check(numberCheck("--fov", "a field of view", 0.01, 170.0, false, "0.01 to 170 degrees"));
    app.add_option("--label", args->label,
                   "Label image instead of a shaded one: organ (a colour per organ kind), object "
                   "(an instance mask, a colour per object) or depth (metres along the view axis)");
    app.add_option_function<std::string>(
        "--coco",
        [args](const std::string& path) {
            args->coco = path;
            args->cocoGiven = true;
        },
        "Also write COCO-style JSON of the objects in view (categories: organ kinds; "
        "masks as RLE; bounding boxes in pixels)");
    app.add_option_function<std::string>(
        "--camera-json",
        [args](const std::string& path) {
            args->cameraJson = path;
            args->cameraJsonGiven = true;
        },
        "Also write the camera as JSON: eye, target, up, field of view, image size, intrinsics "
        "K and extrinsics world_to_camera (OpenCV's pinhole convention)");
    app.add_flag("--no-ground", args->noGround, "Leave out the ground plane");
    addMaterialOptions(app, global);  // --materials, --texture-size
    app.add_option("--samples", args->samples, "Camera rays per pixel (default 4)")
        ->check(numberCheck("--samples", "a ray count", 1, 1024, true, "1 to 1024"));
    return [args, &global] { return run(*args, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(render, "render", 50, setupRender);

}  // namespace plantarch::cli
