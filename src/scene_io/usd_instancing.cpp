// USD with Instancing::Gpu (usd_instancing.h).
//
// Instance i draws its prototype (a shape stored about its centre) at positions[i] +
// scales[i] * rotate(orientations[i], v), in the plant's frame: the placement the organ's own
// prim would have (io::OrganPlacement), so the points land where a file with a prim per organ
// puts them. `orientations` is half precision, as UsdGeomPointInstancer defines it (a relative
// error of about 5e-4); `orientationsf` holds the same rotations in float for readers that
// know it.

#include "scene_io/usd_instancing.h"

#include <array>
#include <functional>

#include "scene_io/instancing.h"

namespace plantarch::io {

void writePointInstancer(Text& out, const OrganTracks& organs,
                         const std::vector<std::size_t>& tracks, vec3 base,
                         const std::string& plantPath,
                         const std::map<std::size_t, std::string>& shapePaths) {
    std::vector<std::size_t> prototypes;  // shapes, in order of first use
    std::map<std::size_t, int> protoIndex;
    std::vector<std::size_t> instances;  // tracks
    for (std::size_t t : tracks) {
        const std::size_t k = onlyPlacement(organs.tracks[t]).shape;
        if (!gpuInstanced(organs.shapes[k], Instancing::Gpu) || !shapePaths.count(k)) continue;
        if (protoIndex.emplace(k, int(prototypes.size())).second) prototypes.push_back(k);
        instances.push_back(t);
    }
    if (instances.empty()) return;
    const std::string path = plantPath + "/instances";
    auto list = [&](const char* head, const std::function<void(std::size_t)>& write,
                    const char* tail = "\n") {
        out << "            " << head << " = [";
        for (std::size_t i = 0; i < instances.size(); ++i) {
            if (i) out << ", ";
            write(instances[i]);
        }
        out << "]" << tail;
    };
    auto placement = [&](std::size_t t) -> const OrganPlacement& {
        return onlyPlacement(organs.tracks[t]);
    };
    out << "\n        def PointInstancer \"instances\" (\n            customData = {\n";
    out << "                string[] instanceNames = [";
    for (std::size_t i = 0; i < instances.size(); ++i)
        out << (i ? ", " : "") << usdQuoted(organName(organs.tracks[instances[i]]));
    out << "]\n            }\n        )\n        {\n            rel prototypes = [";
    for (std::size_t p = 0; p < prototypes.size(); ++p)
        out << (p ? ", " : "") << "<" << path << "/prototypes/shape_"
            << std::to_string(prototypes[p]) << ">";
    out << "]\n";
    list("int[] protoIndices",
         [&](std::size_t t) { out.integer(protoIndex.at(placement(t).shape)); });
    list("int64[] ids", [&](std::size_t t) { out.integer(organs.tracks[t].lastID); });
    list("point3f[] positions", [&](std::size_t t) {
        const vec3 at = placement(t).translation - base;
        out.tuple(&at.x, 3);
    });
    auto orientation = [&](std::size_t t) {
        const glm::quat& q = placement(t).rotation;
        const std::array<float, 4> wxyz = {q.w, q.x, q.y, q.z};
        out.tuple(wxyz.data(), 4);
    };
    list("quath[] orientations", orientation);
    list("quatf[] orientationsf", orientation);
    list("float3[] scales", [&](std::size_t t) {
        const vec3 s(placement(t).scale);
        out.tuple(&s.x, 3);
    });
    const char* perInstance = " (\n                interpolation = \"vertex\"\n            )\n";
    list(
        "int[] primvars:objectID", [&](std::size_t t) { out.integer(organs.tracks[t].lastID); },
        perInstance);
    list(
        "int[] primvars:shootID",
        [&](std::size_t t) { out.integer(organs.tracks[t].labels.shoot); }, perInstance);
    list(
        "int[] primvars:rank", [&](std::size_t t) { out.integer(organs.tracks[t].labels.rank); },
        perInstance);
    list(
        "int[] primvars:node", [&](std::size_t t) { out.integer(organs.tracks[t].labels.node); },
        perInstance);
    list(
        "int[] primvars:leafID", [&](std::size_t t) { out.integer(organs.tracks[t].labels.leaf); },
        perInstance);
    list(
        "float[] primvars:age", [&](std::size_t t) { out.number(organs.tracks[t].labels.age); },
        perInstance);
    out << "\n            def Scope \"prototypes\"\n            {\n";
    for (std::size_t k : prototypes)
        out << "                def Mesh \"shape_" << std::to_string(k)
            << "\" (\n                    prepend references = <" << shapePaths.at(k)
            << ">\n                )\n                {\n                }\n";
    out << "            }\n        }\n";
}

}  // namespace plantarch::io
