// USD text (.usda) writer: z up, metres, an Xform per plant (placed at its base, species, age
// and seed in customData), and under it a Mesh per organ kind with normals, UVs, display
// colours and per-face labels (organ, plant, object) as uniform primvars, plus semantic labels
// (SemanticsLabelsAPI, class = the organ kind) that Omniverse and Isaac Sim read.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"
#include "scene_io/instancing.h"
#include "scene_io/usd_materials.h"
#include "scene_io/usd_skin.h"
#include "scene_io/usd_text.h"

namespace plantarch {

namespace {

using io::primName;
using io::Text;
using io::usdQuoted;

struct Group {  // the objects of one plant and organ kind
    std::vector<ObjectID> objects;
    std::size_t vertices = 0, triangles = 0;
    bool uvs = true;
};

// The Xforms of one scene's plants (and one for the objects of no plant).
// Progress: `done` grows by the triangles of each mesh written.
void writeScene(Text& out, const Context& context, const std::vector<GltfPlant>& plantInfo,
                const UsdOptions& options, ProgressSteps& steps, double& done,
                const io::UsdLooks& looks) {
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    const bool hasPlant = context.objectDataType("plantID") == DataType::Int;
    // plant -> organ -> objects; plants in ID order, the objects of no plant (-1) last.
    std::map<std::int32_t, std::map<std::string, Group>> plants;
    for (ObjectID id : ids) {
        const std::int32_t plant =
            hasPlant ? context.objectDataInt(id, "plantID").value_or(-1) : -1;
        std::string organ = io::organOf(context, id);
        if (organ.empty()) organ = "unlabelled";
        if (options.nodes == NodeLevel::Plant) organ = "plant";  // one mesh per plant
        Group& g = plants[plant][organ];
        const ObjectView o = context.object(id);
        g.objects.push_back(id);
        g.vertices += o.positions.size();
        g.triangles += o.triangleCount();
        g.uvs = g.uvs && !o.uvs.empty();
    }
    const io::LabelReader labelsOf(context);
    std::map<std::int32_t, const GltfPlant*> info;
    for (const GltfPlant& p : plantInfo) info[p.id] = &p;
    auto writePlant = [&](std::int32_t plant, const std::map<std::string, Group>& organs) {
        const auto it = info.find(plant);
        const vec3 base = it != info.end() ? it->second->base : vec3(0.0f);
        std::string name = "scene";
        if (plant >= 0)
            name = primName(
                (it != info.end() && !it->second->species.empty() ? it->second->species : "plant") +
                "_" + std::to_string(plant));
        // A skinned plant (usd_skin.cpp): a SkelRoot over its Skeleton and bound meshes.
        const GltfSkeleton* skeleton = io::usdSkeletonOf(options, plant);
        out << (skeleton ? "    def SkelRoot " : "    def Xform ") << usdQuoted(name)
            << " (\n        customData = {\n";
        if (plant >= 0) {
            out << "            int plantID = ";
            out.integer(plant) << "\n";
            if (it != info.end()) {
                out << "            string species = " << usdQuoted(it->second->species) << "\n";
                out << "            double age = ";
                out.number(float(it->second->age)) << "\n";
                out << "            uint64 seed = ";
                out.integer(std::int64_t(it->second->seed)) << "\n";
            }
        }
        out << "        }\n    )\n    {\n";
        if (base != vec3(0.0f)) {
            out << "        double3 xformOp:translate = ";
            out.tuple(&base.x, 3)
                << "\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n";
        }
        if (skeleton) out << io::usdSkeleton(*skeleton, base);
        for (const auto& [organ, g] : organs) {
            out << "\n        def Mesh " << usdQuoted(primName(organ))
                << " (\n            prepend apiSchemas = [\"SemanticsLabelsAPI:class\""
                << (skeleton ? ", \"SkelBindingAPI\"" : "")
                << "]\n        )\n"
                   "        {\n            uniform token subdivisionScheme = \"none\"\n"
                   "            uniform bool doubleSided = 1\n";
            out << "            token[] semantics:labels:class = [" << usdQuoted(organ) << "]\n";
            io::writeMeshData(out, context, g.objects, base, plant, g.uvs && options.uvs, options,
                              labelsOf);
            if (skeleton)
                out << io::usdSkinBinding(*skeleton, context, g.objects,
                                          "/plantarch/" + name + "/skeleton");
            out << looks.subsets(context, g.objects);  // textured materials (usd_materials.cpp)
            out << "        }\n";
            steps.at(done += double(g.triangles));
        }
        out << "    }\n";
    };
    for (const auto& [plant, organs] : plants)
        if (plant >= 0) writePlant(plant, organs);
    if (plants.count(-1)) writePlant(-1, plants.at(-1));
}

const char* kHeader =
    "#usda 1.0\n(\n    defaultPrim = \"plantarch\"\n    doc = \"plantarch scene\"\n"
    "    metersPerUnit = 1\n    upAxis = \"Z\"\n";

// Textured materials: the maps of a .usda are files beside it, named after it; a .usdz
// package holds them as they are named.
std::string texturePrefix(const std::string& path) {
    return lowerExtension(path) == ".usdz" ? "" : std::filesystem::path(path).stem().string() + "_";
}

// Writes the layer `body` makes: a .usda, with the texture files beside it (all put in place
// together), or a .usdz package of the layer (`<stem>.usda`, first) and the textures.
template <class Body>
void writeLayer(const std::string& path, const io::UsdLooks& looks, Body&& body) {
    const std::filesystem::path target(path);
    io::AtomicFile file(path);
    if (lowerExtension(path) == ".usdz") {
        std::string layer;
        Text out(layer);
        body(out);
        std::vector<std::pair<std::string, std::string_view>> files = looks.files();
        files.insert(files.begin(), {target.stem().string() + ".usda", layer});
        io::writeUsdz(file, files);
        file.commit();
        return;
    }
    std::vector<io::AtomicFile> textures;
    for (const auto& [name, bytes] : looks.files()) {
        textures.emplace_back((target.parent_path() / name).string());
        textures.back().write(bytes.data(), bytes.size());
        textures.back().finish();
    }
    Text out(file);
    body(out);
    file.finish();
    for (io::AtomicFile& t : textures) t.commit();
    file.commit();
}

}  // namespace

void writeUSDA(const Context& context, const std::string& path, const UsdOptions& options) {
    requireOutputFormat(path, {".usda", ".usdz"}, "writeUSDA writes USD text or a USDZ package");
    io::checkInstancing(path, options.nodes, options.instancing, false);
    const Context* contexts[] = {&context};
    const io::UsdLooks looks(contexts, options, texturePrefix(path));
    io::checkUsdSkins(options, context, path);  // usd_skin.cpp
    ProgressSteps steps(options.progress, "writing USD", double(context.triangleCount()));
    double done = 0.0;
    writeLayer(path, looks, [&](Text& out) {
        out << kHeader << ")\n\ndef Xform \"plantarch\"\n{\n" << looks.scope();
        if (options.nodes == NodeLevel::Organ)  // usd_organs.cpp
            io::writeOrganPrims(out, {&context}, {options.plants}, options, looks, false);
        else
            writeScene(out, context, options.plants, options, steps, done, looks);
        out << "}\n";
    });
    steps.finish();
}

void writeUSDA(const std::vector<AnimationFrame>& frames, const std::string& path,
               const UsdOptions& given, const AnimationOptions& animation) {
    requireOutputFormat(path, {".usda", ".usdz"}, "writeUSDA writes USD text or a USDZ package");
    io::checkAnimation(frames, animation, path);
    io::checkInstancing(path, NodeLevel::Organ, given.instancing, true);
    UsdOptions options = given;  // skeletons bind one scene's objects, not a frame's
    options.skeletons.clear();
    std::vector<const Context*> contexts;
    for (const AnimationFrame& frame : frames) contexts.push_back(frame.context);
    const io::UsdLooks looks(contexts, options, texturePrefix(path));
    writeLayer(path, looks, [&](Text& out) {
        out << kHeader << "    startTimeCode = 0\n    endTimeCode = ";
        out.integer(std::int64_t(frames.size() - 1)) << "\n    timeCodesPerSecond = ";
        out.number(float(animation.framesPerSecond))
            << "\n)\n\ndef Xform \"plantarch\" (\n    customData = {\n        double[] days = [";
        for (std::size_t f = 0; f < frames.size(); ++f)
            out << (f ? ", " : "") << text::formatDouble(frames[f].day);
        out << "]\n    }\n)\n{\n" << looks.scope();
        // A prim per organ, its placement sampled at each frame (usd_organs.cpp).
        std::vector<std::vector<GltfPlant>> plants;
        for (const AnimationFrame& frame : frames) plants.push_back(frame.plants);
        io::writeOrganPrims(out, contexts, plants, options, looks, true);
        out << "}\n";
    });
}

}  // namespace plantarch
