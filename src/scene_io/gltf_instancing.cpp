// glTF with Instancing::Gpu (gltf_instancing.h).
//
// A shape that several organs of one plant place becomes one node under the plant with the
// shape's mesh and EXT_mesh_gpu_instancing: instance i is organ i placed as its organ node
// would place it (translation relative to the plant's base, rotation, uniform scale), so the
// vertices land where a file with a node per organ puts them. The organs' numeric labels are
// per-instance attributes; their names and object IDs are listed in the node's extras, in
// instance order. A viewer that ignored the extension would draw one instance where there are
// many, so it is listed as required.

#include "scene_io/gltf_instancing.h"

#include <map>
#include <memory>

#include "scene_io/instancing.h"

namespace plantarch::gltf {

namespace {

// An accessor of per-instance values (a view with no target: not vertex data).
template <class T>
std::size_t instanceAccessor(GltfArrays& d, Buffer& buffer, std::vector<T> values,
                             std::size_t count, const char* type) {
    auto shared = std::make_shared<std::vector<T>>(std::move(values));
    const int view = buffer.add(d.views, shared->size() * sizeof(T), 0, [shared](Sink& out) {
        out.write(shared->data(), shared->size() * sizeof(T));
    });
    d.accessors.push_back(accessor(view, kFloat, count, type));
    return d.accessors.size() - 1;
}

}  // namespace

void addInstanceNodes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                      const std::vector<std::size_t>& tracks, vec3 base,
                      const std::function<std::size_t(std::size_t)>& mesh, json& children) {
    if (options.instancing != Instancing::Gpu) return;
    std::map<std::size_t, std::vector<std::size_t>> instancesOf;  // shape: tracks, in order
    for (std::size_t t : tracks) {
        const std::size_t k = io::onlyPlacement(s.organs.tracks[t]).shape;
        if (io::gpuInstanced(s.organs.shapes[k], options.instancing)) instancesOf[k].push_back(t);
    }
    for (const auto& [k, users] : instancesOf) {
        const std::size_t n = users.size();
        std::vector<float> translation, rotation, scale;
        std::map<std::string, std::vector<float>> labels;
        json names = json::array(), ids = json::array();
        for (std::size_t t : users) {
            const io::OrganTrack& track = s.organs.tracks[t];
            const io::OrganPlacement& p = io::onlyPlacement(track);
            const vec3 at = p.translation - base;
            translation.insert(translation.end(), {at.x, at.y, at.z});
            rotation.insert(rotation.end(),
                            {p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w});
            scale.insert(scale.end(), {p.scale, p.scale, p.scale});
            const ObjectRecord& r = s.records[t];
            labels["_OBJECT_ID"].push_back(float(r.id));
            labels["_FEATURE_ID_0"].push_back(float(t));
            labels["_SHOOT"].push_back(float(r.shoot));
            labels["_RANK"].push_back(float(r.rank));
            labels["_NODE"].push_back(float(r.node));
            labels["_LEAF"].push_back(float(r.leaf));
            labels["_AGE"].push_back(r.age);
            names.push_back(io::organName(track));
            ids.push_back(r.id);
        }
        json attributes = {
            {"TRANSLATION", instanceAccessor(d, buffer, std::move(translation), n, "VEC3")},
            {"ROTATION", instanceAccessor(d, buffer, std::move(rotation), n, "VEC4")},
            {"SCALE", instanceAccessor(d, buffer, std::move(scale), n, "VEC3")}};
        json node = {{"mesh", mesh(k)}};
        if (options.labels) {
            for (const char* name :
                 {"_OBJECT_ID", "_FEATURE_ID_0", "_SHOOT", "_RANK", "_NODE", "_LEAF", "_AGE"})
                attributes[name] =
                    instanceAccessor(d, buffer, std::move(labels[name]), n, "SCALAR");
            node["extensions"]["EXT_instance_features"] = {
                {"featureIds", {{{"featureCount", n}, {"attribute", 0}, {"propertyTable", 0}}}}};
        }
        node["extensions"]["EXT_mesh_gpu_instancing"] = {{"attributes", attributes}};
        const io::ObjectLabels& l = s.organs.tracks[users.front()].labels;
        const std::string organ(kOrganLabels[l.organ]);
        node["name"] = organ + "_instances_" + std::to_string(k);
        node["extras"] = {
            {"plantID", l.plant}, {"organ", organ}, {"instances", names}, {"objectIDs", ids}};
        d.nodes.push_back(std::move(node));
        children.push_back(d.nodes.size() - 1);
    }
}

void declareInstancing(json& doc, const json& nodes) {
    bool gpu = false, features = false;
    for (const json& n : nodes)
        if (n.contains("extensions")) {
            gpu = gpu || n["extensions"].contains("EXT_mesh_gpu_instancing");
            features = features || n["extensions"].contains("EXT_instance_features");
        }
    if (!gpu) return;
    auto add = [&doc](const char* list, const char* name) {
        json& l = doc[list];
        if (!l.is_array()) l = json::array();
        l.push_back(name);
    };
    add("extensionsUsed", "EXT_mesh_gpu_instancing");
    add("extensionsRequired", "EXT_mesh_gpu_instancing");
    if (features) add("extensionsUsed", "EXT_instance_features");
}

}  // namespace plantarch::gltf
