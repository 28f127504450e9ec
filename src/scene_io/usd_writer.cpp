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
#include "scene_io/usd_materials.h"
#include "scene_io/usd_skin.h"

namespace plantarch {

namespace {

// Prim names are identifiers: letters, digits and '_', not starting with a digit.
std::string primName(const std::string& text) {
    std::string out;
    for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
    if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "_" + out;
    return out;
}

std::string usdQuoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += (c == '\n' ? ' ' : c);
    }
    return out + "\"";
}

// Numbers into the file's buffer (or a string, for a .usdz package), shortest exact text.
class Text {
public:
    explicit Text(io::AtomicFile& file) : file_(&file) {}
    explicit Text(std::string& text) : text_(&text) {}
    /// Text written at the start of each line from now on (the nesting of a frame's prims);
    /// called at the start of a line.
    void indent(std::string_view prefix) {
        indent_ = prefix;
        lineStart_ = true;
    }
    Text& operator<<(std::string_view s) {
        if (indent_.empty()) {
            put(s);
            return *this;
        }
        for (std::size_t at = 0; at < s.size();) {
            const std::size_t end = std::min(s.find('\n', at), s.size() - 1);
            lineStart();
            put(s.substr(at, end + 1 - at));
            lineStart_ = s[end] == '\n';
            at = end + 1;
        }
        return *this;
    }
    Text& number(float v) {
        lineStart();
        char p[io::kMaxFloatChars];
        put(std::string_view(p, std::size_t(io::writeFloat(p, v) - p)));
        return *this;
    }
    Text& integer(std::int64_t v) {
        lineStart();
        char p[24];
        put(std::string_view(p, std::size_t(io::writeInt(p, v) - p)));
        return *this;
    }
    Text& tuple(const float* v, int n) {
        put("(");
        for (int i = 0; i < n; ++i) {
            if (i) put(", ");
            number(v[i]);
        }
        put(")");
        return *this;
    }

private:
    void put(std::string_view s) {
        if (file_)
            file_->write(s);
        else
            text_->append(s);
    }
    void lineStart() {
        if (lineStart_ && !indent_.empty()) put(indent_);
        lineStart_ = false;
    }

    io::AtomicFile* file_ = nullptr;
    std::string* text_ = nullptr;
    std::string indent_;
    bool lineStart_ = false;
};

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
        std::vector<vec3> normals;
        for (const auto& [organ, g] : organs) {
            out << "\n        def Mesh " << usdQuoted(primName(organ))
                << " (\n            prepend apiSchemas = [\"SemanticsLabelsAPI:class\""
                << (skeleton ? ", \"SkelBindingAPI\"" : "")
                << "]\n        )\n"
                   "        {\n            uniform token subdivisionScheme = \"none\"\n"
                   "            uniform bool doubleSided = 1\n";
            out << "            token[] semantics:labels:class = [" << usdQuoted(organ) << "]\n";
            out << "            int[] faceVertexCounts = [";
            for (std::size_t t = 0; t < g.triangles; ++t) out << (t ? ", 3" : "3");
            out << "]\n            int[] faceVertexIndices = [";
            std::size_t first = 0;
            bool comma = false;
            for (ObjectID id : g.objects) {
                const ObjectView o = context.object(id);
                for (std::uint32_t k : o.indices) {
                    if (comma) out << ", ";
                    out.integer(std::int64_t(first + k));
                    comma = true;
                }
                first += o.positions.size();
            }
            out << "]\n            point3f[] points = [";
            comma = false;
            for (ObjectID id : g.objects)
                for (const vec3& v : context.object(id).positions) {
                    const vec3 local = v - base;
                    if (comma) out << ", ";
                    out.tuple(&local.x, 3);
                    comma = true;
                }
            out << "]\n";
            if (options.normals) {
                out << "            normal3f[] primvars:normals = [";
                comma = false;
                for (ObjectID id : g.objects) {
                    smoothNormals(context.object(id), normals);
                    for (const vec3& n : normals) {
                        if (comma) out << ", ";
                        out.tuple(&n.x, 3);
                        comma = true;
                    }
                }
                out << "] (\n                interpolation = \"vertex\"\n            )\n";
            }
            if (g.uvs && options.uvs) {
                out << "            texCoord2f[] primvars:st = [";
                comma = false;
                for (ObjectID id : g.objects)
                    for (const vec2& uv : context.object(id).uvs) {
                        if (comma) out << ", ";
                        out.tuple(&uv.x, 2);
                        comma = true;
                    }
                out << "] (\n                interpolation = \"vertex\"\n            )\n";
            }
            // Per face: display colour (the organ's material) and the labels.
            auto perFace = [&, &objects = g.objects](const char* type, const char* name,
                                                     auto write) {
                out << "            " << type << " primvars:" << name << " = [";
                bool sep = false;
                for (ObjectID id : objects) {
                    const std::size_t n = context.object(id).triangleCount();
                    for (std::size_t t = 0; t < n; ++t) {
                        if (sep) out << ", ";
                        write(id);
                        sep = true;
                    }
                }
                out << "] (\n                interpolation = \"uniform\"\n            )\n";
            };
            perFace("color3f[]", "displayColor", [&](ObjectID id) {
                const vec3 c = context.material(context.objectMaterial(id)).color;
                out.tuple(&c.x, 3);
            });
            std::int64_t code = 0;  // the index in kOrganLabels (trellis parts are obstacles)
            for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
                if (organ == kOrganLabels[i]) code = std::int64_t(i);
            if (organ == "trellis") code = 9;
            perFace("int[]", "organ", [&](ObjectID) { out.integer(code); });
            perFace("int[]", "plantID", [&](ObjectID) { out.integer(plant); });
            perFace("int[]", "objectID", [&](ObjectID id) { out.integer(std::int64_t(id)); });
            perFace("int[]", "leafID", [&](ObjectID id) { out.integer(labelsOf(id).leaf); });
            perFace("int[]", "shootID", [&](ObjectID id) { out.integer(labelsOf(id).shoot); });
            perFace("int[]", "rank", [&](ObjectID id) { out.integer(labelsOf(id).rank); });
            perFace("int[]", "node", [&](ObjectID id) { out.integer(labelsOf(id).node); });
            perFace("float[]", "age", [&](ObjectID id) { out.number(labelsOf(id).age); });
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
    const Context* contexts[] = {&context};
    const io::UsdLooks looks(contexts, options, texturePrefix(path));
    io::checkUsdSkins(options, context, path);  // usd_skin.cpp
    ProgressSteps steps(options.progress, "writing USD", double(context.triangleCount()));
    double done = 0.0;
    writeLayer(path, looks, [&](Text& out) {
        out << kHeader << ")\n\ndef Xform \"plantarch\"\n{\n" << looks.scope();
        writeScene(out, context, options.plants, options, steps, done, looks);
        out << "}\n";
    });
    steps.finish();
}

void writeUSDA(const std::vector<AnimationFrame>& frames, const std::string& path,
               const UsdOptions& given, const AnimationOptions& animation) {
    requireOutputFormat(path, {".usda", ".usdz"}, "writeUSDA writes USD text or a USDZ package");
    io::checkAnimation(frames, animation, path);
    UsdOptions options = given;  // skeletons bind one scene's objects, not a frame's
    options.skeletons.clear();
    std::vector<const Context*> contexts;
    for (const AnimationFrame& frame : frames) contexts.push_back(frame.context);
    const io::UsdLooks looks(contexts, options, texturePrefix(path));
    double triangles = 0.0, done = 0.0;
    for (const AnimationFrame& frame : frames) triangles += double(frame.context->triangleCount());
    ProgressSteps steps(options.progress, "writing USD", triangles);
    writeLayer(path, looks, [&](Text& out) {
        out << kHeader << "    startTimeCode = 0\n    endTimeCode = ";
        out.integer(std::int64_t(frames.size() - 1)) << "\n    timeCodesPerSecond = ";
        out.number(float(animation.framesPerSecond)) << "\n)\n\ndef Xform \"plantarch\"\n{\n"
                                                     << looks.scope();
        for (std::size_t f = 0; f < frames.size(); ++f) {
            std::string name = "day_" + text::formatDouble(frames[f].day);
            for (char& c : name)
                if (c == '.' || c == '-') c = '_';
            out << (f ? "\n" : "") << "    def Xform " << usdQuoted(name)
                << " (\n        customData = {\n            double day = "
                << text::formatDouble(frames[f].day) << "\n        }\n    )\n    {\n";
            // Shown at time code f alone: hidden before (held from the first sample back) and
            // after; token values are held, never interpolated.
            out << "        token visibility.timeSamples = {\n";
            if (f > 0) out << "            0: \"invisible\",\n";
            out << "            ";
            out.integer(std::int64_t(f)) << ": \"inherited\",\n";
            if (f + 1 < frames.size()) {
                out << "            ";
                out.integer(std::int64_t(f + 1)) << ": \"invisible\",\n";
            }
            out << "        }\n";
            out.indent("    ");
            writeScene(out, *frames[f].context, frames[f].plants, options, steps, done, looks);
            out.indent("");
            out << "    }\n";
        }
        out << "}\n";
    });
    steps.finish();
}

}  // namespace plantarch
