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

constexpr const char* kInstanceLabels[] = {"_OBJECT_ID", "_FEATURE_ID_0", "_SHOOT", "_RANK",
                                           "_NODE",      "_LEAF",         "_AGE"};

// The per-instance values of one plant's instancing nodes, all in one buffer view (each
// attribute an accessor at its offset): a view per attribute would cost more JSON than the
// values themselves where a shape has few instances.
struct InstanceData {
    struct Attribute {
        std::string name;
        std::size_t offset, count;  // in floats; count in elements
        const char* type;
    };
    std::vector<float> values;
    std::vector<std::vector<Attribute>> nodes;  // per instancing node

    void add(const char* name, std::vector<float> v, std::size_t count, const char* type) {
        nodes.back().push_back({name, values.size(), count, type});
        values.insert(values.end(), v.begin(), v.end());
    }
};

// Adds the accessors of node k's attributes over `view`.
json attributesOf(GltfArrays& d, const InstanceData& data, std::size_t k, int view) {
    json attributes = json::object();
    for (const InstanceData::Attribute& a : data.nodes[k]) {
        json acc = accessor(view, kFloat, a.count, a.type);
        if (a.offset) acc["byteOffset"] = a.offset * sizeof(float);
        d.accessors.push_back(std::move(acc));
        attributes[a.name] = d.accessors.size() - 1;
    }
    return attributes;
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
    if (instancesOf.empty()) return;
    auto data = std::make_shared<InstanceData>();
    std::vector<json> nodes;
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
            const float values[] = {float(r.id),   float(t),      float(r.shoot), float(r.rank),
                                    float(r.node), float(r.leaf), r.age};
            for (std::size_t i = 0; i < std::size(kInstanceLabels); ++i)
                labels[kInstanceLabels[i]].push_back(values[i]);
            names.push_back(io::organName(track));
            ids.push_back(r.id);
        }
        data->nodes.emplace_back();
        data->add("TRANSLATION", std::move(translation), n, "VEC3");
        data->add("ROTATION", std::move(rotation), n, "VEC4");
        data->add("SCALE", std::move(scale), n, "VEC3");
        json node = {{"mesh", mesh(k)}};
        if (options.labels) {
            for (const char* name : kInstanceLabels)
                data->add(name, std::move(labels[name]), n, "SCALAR");
            node["extensions"]["EXT_instance_features"] = {
                {"featureIds", {{{"featureCount", n}, {"attribute", 0}, {"propertyTable", 0}}}}};
        }
        const io::ObjectLabels& l = s.organs.tracks[users.front()].labels;
        const std::string organ(kOrganLabels[l.organ]);
        node["name"] = organ + "_instances_" + std::to_string(k);
        node["extras"] = {
            {"plantID", l.plant}, {"organ", organ}, {"instances", names}, {"objectIDs", ids}};
        nodes.push_back(std::move(node));
    }
    const int view = buffer.add(d.views, data->values.size() * sizeof(float), 0, [data](Sink& out) {
        out.write(data->values.data(), data->values.size() * sizeof(float));
    });
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        nodes[i]["extensions"]["EXT_mesh_gpu_instancing"] = {
            {"attributes", attributesOf(d, *data, i, view)}};
        d.nodes.push_back(std::move(nodes[i]));
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
