// USD meshes: the attributes of one Mesh prim (shared by every layout), and the layout with a
// prim per organ (NodeLevel::Organ, and every growth animation).
//
// With a prim per organ, each plant's Xform holds an Xform per shoot ("shoot_<S>") and under it
// a Mesh per organ, named by its organ, shoot, node and leaf and labelled in its customData. An
// organ is its shape (io::trackOrgans) placed by xformOp:translate, :orient and :scale; a shape
// several organs share is written once under the class prim "shapes" and referenced. In an
// animation the ops carry a time sample per frame and the organ's visibility is keyed where it
// appears; an organ whose shape changed otherwise is an Xform over a Mesh per shape, each visible
// on its frames, the later ones referencing the first for their faces and labels.

#include <algorithm>
#include <map>
#include <set>

#include "plantarch/Export.h"
#include "scene_io/instancing.h"
#include "scene_io/organ_tracks.h"
#include "scene_io/usd_instancing.h"
#include "scene_io/usd_materials.h"
#include "scene_io/usd_text.h"

namespace plantarch::io {

void writeMeshData(Text& out, const Context& context, std::span<const ObjectID> objects,
                   vec3 origin, std::int32_t plant, bool uvs, const UsdOptions& options,
                   const LabelReader& labelsOf, UsdMeshParts parts) {
    bool comma = false;
    if (parts.topology) {
        out << "            int[] faceVertexCounts = [";
        for (ObjectID id : objects)
            for (std::size_t t = 0; t < context.object(id).triangleCount(); ++t) {
                out << (comma ? ", 3" : "3");
                comma = true;
            }
        out << "]\n            int[] faceVertexIndices = [";
        std::size_t first = 0;
        comma = false;
        for (ObjectID id : objects) {
            const ObjectView o = context.object(id);
            for (std::uint32_t k : o.indices) {
                if (comma) out << ", ";
                out.integer(std::int64_t(first + k));
                comma = true;
            }
            first += o.positions.size();
        }
        out << "]\n";
    }
    if (parts.geometry) {
        out << "            point3f[] points = [";
        comma = false;
        for (ObjectID id : objects)
            for (const vec3& v : context.object(id).positions) {
                const vec3 local = v - origin;
                if (comma) out << ", ";
                out.tuple(&local.x, 3);
                comma = true;
            }
        out << "]\n";
        if (options.normals) {
            std::vector<vec3> normals;
            out << "            normal3f[] primvars:normals = [";
            comma = false;
            for (ObjectID id : objects) {
                smoothNormals(context.object(id), normals);
                for (const vec3& n : normals) {
                    if (comma) out << ", ";
                    out.tuple(&n.x, 3);
                    comma = true;
                }
            }
            out << "] (\n                interpolation = \"vertex\"\n            )\n";
        }
    }
    if (!parts.topology) return;
    if (uvs) {
        out << "            texCoord2f[] primvars:st = [";
        comma = false;
        for (ObjectID id : objects)
            for (const vec2& uv : context.object(id).uvs) {
                if (comma) out << ", ";
                out.tuple(&uv.x, 2);
                comma = true;
            }
        out << "] (\n                interpolation = \"vertex\"\n            )\n";
    }
    // Per face: display colour (the organ's material) and the labels.
    auto perFace = [&](const char* type, const char* name, auto write) {
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
    perFace("int[]", "organ", [&](ObjectID id) { out.integer(labelsOf(id).organ); });
    perFace("int[]", "plantID", [&](ObjectID) { out.integer(plant); });
    if (!parts.objectLabels) return;
    perFace("int[]", "objectID", [&](ObjectID id) { out.integer(std::int64_t(id)); });
    perFace("int[]", "leafID", [&](ObjectID id) { out.integer(labelsOf(id).leaf); });
    perFace("int[]", "shootID", [&](ObjectID id) { out.integer(labelsOf(id).shoot); });
    perFace("int[]", "rank", [&](ObjectID id) { out.integer(labelsOf(id).rank); });
    perFace("int[]", "node", [&](ObjectID id) { out.integer(labelsOf(id).node); });
    perFace("float[]", "age", [&](ObjectID id) { out.number(labelsOf(id).age); });
}

namespace {

bool uvsMatter(const Material& m, const UsdOptions& options) {
    return options.uvs &&
           (!m.texture.empty() || options.appearance.style == MaterialStyle::Textured);
}

class OrganPrims {
public:
    OrganPrims(Text& out, const std::vector<const Context*>& frames, const UsdOptions& options,
               const UsdLooks& looks, bool animated)
        : out_(out),
          frames_(frames),
          options_(options),
          looks_(looks),
          animated_(animated),
          organs_(trackOrgans(frames, options.includeHidden, options.instancing != Instancing::None,
                              [&options](const Material& m) { return uvsMatter(m, options); })),
          steps_(options.progress, "writing USD", shapeTriangles()) {}
    void finish() { steps_.finish(); }

    void shapes();
    void plant(std::int32_t plant, const GltfPlant* info);
    double shapeTriangles() const {
        double n = 0.0;
        for (const OrganShape& s : organs_.shapes)
            n += double(frames_[s.frame]->object(s.id).triangleCount());
        return n;
    }

private:
    void shape(std::size_t k, std::string_view indent, UsdMeshParts parts);
    void organ(std::size_t track, vec3 base);
    void placement(const OrganTrack& track, vec3 base);
    void visibility(const std::vector<bool>& shown, const char* indent);
    std::string organCustomData(const OrganTrack& track) const;

    Text& out_;
    const std::vector<const Context*>& frames_;
    const UsdOptions& options_;
    const UsdLooks& looks_;
    bool animated_;
    OrganTracks organs_;
    ProgressSteps steps_;  // by the triangles of the shapes written
    double done_ = 0.0;
    std::map<std::size_t, std::string> shapePaths_;  // shapes written under "shapes"
    std::string path_;                               // the prim the organs are written under
};

// The attributes of shape k's mesh, at 12 spaces plus `indent`.
void OrganPrims::shape(std::size_t k, std::string_view indent, UsdMeshParts parts) {
    const OrganShape& s = organs_.shapes[k];
    const Context& ctx = *frames_[s.frame];
    const LabelReader labelsOf(ctx);
    const ObjectID ids[] = {s.id};
    const ObjectView o = ctx.object(s.id);
    const OrganTrack& user = organs_.tracks[s.users.front()];
    out_.indent(indent);
    writeMeshData(out_, ctx, ids, s.centre, user.labels.plant,
                  !o.uvs.empty() && uvsMatter(ctx.material(o.material), options_), options_,
                  labelsOf, parts);
    if (parts.topology) out_ << looks_.subsets(ctx, ids);
    out_.indent("");
    steps_.at(done_ += double(o.triangleCount()));
}

// Shapes placed by several organs, once each under the class prim "shapes".
void OrganPrims::shapes() {
    bool any = false;
    for (std::size_t k = 0; k < organs_.shapes.size(); ++k) {
        const OrganShape& s = organs_.shapes[k];
        if (s.users.size() < 2) continue;
        if (!any) out_ << "    class Scope \"shapes\"\n    {\n";
        any = true;
        const std::string name = "shape_" + std::to_string(k);
        shapePaths_[k] = "/plantarch/shapes/" + name;
        const std::string organ(kOrganLabels[organs_.tracks[s.users.front()].labels.organ]);
        out_ << "        def Mesh " << usdQuoted(name)
             << " (\n            prepend apiSchemas = [\"SemanticsLabelsAPI:class\"]\n        )\n"
                "        {\n            uniform token subdivisionScheme = \"none\"\n"
                "            uniform bool doubleSided = 1\n"
                "            token[] semantics:labels:class = ["
             << usdQuoted(organ) << "]\n";
        shape(k, "", {.objectLabels = false});
        out_ << "        }\n";
    }
    if (any) out_ << "    }\n\n";
}

std::string OrganPrims::organCustomData(const OrganTrack& t) const {
    const ObjectLabels& l = t.labels;
    std::string text = "customData = {\n";
    auto add = [&](const char* type, const char* key, const std::string& value) {
        text += "                " + std::string(type) + " " + key + " = " + value + "\n";
    };
    add("int", "objectID", std::to_string(t.lastID));
    add("int", "plantID", std::to_string(l.plant));
    add("string", "organ", usdQuoted(std::string(kOrganLabels[l.organ])));
    add("int", "shootID", std::to_string(l.shoot));
    add("int", "rank", std::to_string(l.rank));
    add("int", "node", std::to_string(l.node));
    add("int", "leafID", std::to_string(l.leaf));
    char age[kMaxFloatChars];
    add("float", "age", std::string(age, std::size_t(writeFloat(age, l.age) - age)));
    return text + "            }";
}

// Visibility keyed where it changes (tokens are held from each sample to the next).
void OrganPrims::visibility(const std::vector<bool>& shown, const char* indent) {
    if (std::all_of(shown.begin(), shown.end(), [](bool b) { return b; })) return;
    out_ << indent << "token visibility.timeSamples = {\n";
    for (std::size_t f = 0; f < shown.size(); ++f)
        if (f == 0 || shown[f] != shown[f - 1]) {
            out_ << indent << "    ";
            out_.integer(std::int64_t(f))
                << (shown[f] ? ": \"inherited\",\n" : ": \"invisible\",\n");
        }
    out_ << indent << "}\n";
}

// The organ's xformOps: its placement (a sample per frame in an animation, the nearest
// placement held where it does not exist).
void OrganPrims::placement(const OrganTrack& track, vec3 base) {
    std::vector<io::OrganPlacement> at;
    std::optional<io::OrganPlacement> held;
    for (const auto& p : track.frames)
        if (p) {
            held = p;
            break;
        }
    for (const auto& p : track.frames) {
        if (p) held = p;
        at.push_back(*held);
    }
    const char* indent = "                ";
    auto op = [&](const char* type, const char* name, auto value, auto write) {
        const bool constant = std::all_of(at.begin(), at.end(), [&](const io::OrganPlacement& p) {
            return value(p) == value(at.back());
        });
        out_ << indent << type << " xformOp:" << name;
        if (!animated_ || constant) {
            out_ << " = ";
            write(value(at.back()));
            out_ << "\n";
            return;
        }
        out_ << ".timeSamples = {\n";
        for (std::size_t f = 0; f < at.size(); ++f) {
            out_ << indent << "    ";
            out_.integer(std::int64_t(f)) << ": ";
            write(value(at[f]));
            out_ << ",\n";
        }
        out_ << indent << "}\n";
    };
    op(
        "float3", "translate", [&](const io::OrganPlacement& p) { return p.translation - base; },
        [&](vec3 v) { out_.tuple(&v.x, 3); });
    op(
        "quatf", "orient",
        [](const io::OrganPlacement& p) {
            return std::array<float, 4>{p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z};
        },
        [&](std::array<float, 4> q) { out_.tuple(q.data(), 4); });
    op(
        "float3", "scale", [](const io::OrganPlacement& p) { return vec3(p.scale); },
        [&](vec3 v) { out_.tuple(&v.x, 3); });
    out_ << indent
         << "uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\", "
            "\"xformOp:scale\"]\n";
}

void OrganPrims::organ(std::size_t t, vec3 base) {
    const OrganTrack& track = organs_.tracks[t];
    std::vector<std::size_t> shapes;  // in order of first use
    for (const auto& p : track.frames)
        if (p && std::find(shapes.begin(), shapes.end(), p->shape) == shapes.end())
            shapes.push_back(p->shape);
    std::vector<bool> shown;
    for (const auto& p : track.frames) shown.push_back(p.has_value());
    const std::string name = primName(organName(track));
    const std::string organ(kOrganLabels[track.labels.organ]);
    const bool single = shapes.size() == 1;
    const auto shared = single ? shapePaths_.find(shapes.front()) : shapePaths_.end();
    out_ << "\n            def " << (single ? "Mesh " : "Xform ") << usdQuoted(name) << " (\n";
    if (single) out_ << "                prepend apiSchemas = [\"SemanticsLabelsAPI:class\"]\n";
    if (shared != shapePaths_.end())
        out_ << "                prepend references = <" << shared->second << ">\n";
    out_ << "                " << organCustomData(track) << "\n            )\n            {\n";
    if (single)
        out_ << "                token[] semantics:labels:class = [" << usdQuoted(organ) << "]\n";
    placement(track, base);
    if (animated_) visibility(shown, "                ");
    if (single) {
        if (shared == shapePaths_.end()) {
            out_ << "                uniform token subdivisionScheme = \"none\"\n"
                    "                uniform bool doubleSided = 1\n";
            shape(shapes.front(), "    ", {});
        }
        out_ << "            }\n";
        return;
    }
    // A Mesh per shape, each visible on its frames; later shapes of the first one's topology
    // take its faces and labels by reference.
    const std::string first = path_ + "/" + name + "/v0";
    for (std::size_t v = 0; v < shapes.size(); ++v) {
        const OrganShape& s = organs_.shapes[shapes[v]];
        const bool reuse = v > 0 && s.topology == organs_.shapes[shapes[0]].topology &&
                           !shapePaths_.count(shapes[0]);
        out_ << "\n                def Mesh \"v" << std::to_string(v)
             << "\" (\n                    prepend apiSchemas = [\"SemanticsLabelsAPI:class\"]\n";
        if (reuse) out_ << "                    prepend references = <" << first << ">\n";
        out_ << "                )\n                {\n";
        std::vector<bool> on;
        for (const auto& p : track.frames) on.push_back(p && p->shape == shapes[v]);
        visibility(on, "                    ");
        if (!reuse)
            out_ << "                    token[] semantics:labels:class = [" << usdQuoted(organ)
                 << "]\n                    uniform token subdivisionScheme = \"none\"\n"
                    "                    uniform bool doubleSided = 1\n";
        shape(shapes[v], "        ", {.topology = !reuse, .objectLabels = s.users.size() == 1});
        out_ << "                }\n";
    }
    out_ << "            }\n";
}

void OrganPrims::plant(std::int32_t plant, const GltfPlant* info) {
    const vec3 base = info ? info->base : vec3(0.0f);
    std::string name = "scene";
    if (plant >= 0)
        name = primName((info && !info->species.empty() ? info->species : "plant") + "_" +
                        std::to_string(plant));
    out_ << "    def Xform " << usdQuoted(name) << " (\n        customData = {\n";
    if (plant >= 0) {
        out_ << "            int plantID = ";
        out_.integer(plant) << "\n";
        if (info) {
            out_ << "            string species = " << usdQuoted(info->species) << "\n";
            out_ << "            double age = ";
            out_.number(float(info->age)) << "\n";
            out_ << "            uint64 seed = ";
            out_.integer(std::int64_t(info->seed)) << "\n";
        }
    }
    out_ << "        }\n    )\n    {\n";
    if (base != vec3(0.0f)) {
        out_ << "        double3 xformOp:translate = ";
        out_.tuple(&base.x, 3)
            << "\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n";
    }
    // Organs by shoot, shoots in ID order; organs of no shoot directly under the plant.
    // With Instancing::Gpu, organs of a shared shape are instances (usd_instancing.cpp).
    std::map<std::int32_t, std::vector<std::size_t>> shoots;
    std::vector<std::size_t> instances;
    for (std::size_t t = 0; t < organs_.tracks.size(); ++t) {
        const OrganTrack& track = organs_.tracks[t];
        if (track.labels.plant != plant) continue;
        if (options_.instancing == Instancing::Gpu &&
            gpuInstanced(organs_.shapes[onlyPlacement(track).shape], options_.instancing))
            instances.push_back(t);
        else
            shoots[track.labels.shoot].push_back(t);
    }
    for (const auto& [shoot, tracks] : shoots) {
        if (shoot < 0) {
            path_ = "/plantarch/" + name;
            for (std::size_t t : tracks) organ(t, base);
            continue;
        }
        path_ = "/plantarch/" + name + "/shoot_" + std::to_string(shoot);
        out_ << "\n        def Xform \"shoot_" << std::to_string(shoot)
             << "\" (\n            customData = {\n                int shootID = "
             << std::to_string(shoot) << "\n                int rank = "
             << std::to_string(organs_.tracks[tracks.front()].labels.rank)
             << "\n            }\n        )\n        {";
        for (std::size_t t : tracks) organ(t, base);
        out_ << "        }\n";
    }
    writePointInstancer(out_, organs_, instances, base, "/plantarch/" + name, shapePaths_);
    out_ << "    }\n";
}

}  // namespace

void writeOrganPrims(Text& out, const std::vector<const Context*>& frames,
                     const std::vector<std::vector<GltfPlant>>& plants, const UsdOptions& options,
                     const UsdLooks& looks, bool animated) {
    OrganPrims prims(out, frames, options, looks, animated);
    prims.shapes();
    // Each plant as in its last frame: plants in ID order, the objects of no plant last.
    std::map<std::int32_t, const GltfPlant*> info;
    for (const std::vector<GltfPlant>& frame : plants)
        for (const GltfPlant& p : frame) info[p.id] = &p;
    std::set<std::int32_t> ids;
    for (const Context* ctx : frames) {
        const LabelReader labelsOf(*ctx);
        for (ObjectID id : exportedObjects(*ctx, options.includeHidden))
            ids.insert(labelsOf(id).plant);
    }
    for (std::int32_t id : ids)
        if (id >= 0) prims.plant(id, info.count(id) ? info.at(id) : nullptr);
    if (ids.count(-1)) prims.plant(-1, nullptr);
    prims.finish();
}

}  // namespace plantarch::io
