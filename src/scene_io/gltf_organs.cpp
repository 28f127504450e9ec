// A glTF node per organ (NodeLevel::Organ, and every growth animation).
//
// Each plant's node holds a node per shoot ("shoot_<S>") and under it a node per organ, named by
// its organ, shoot, node and leaf and labelled in its extras. An organ node places a shape (the
// geometry stored once, io::trackOrgans) by its translation, rotation and uniform scale; shapes of
// one topology share their index, UV and label arrays. In an animation the organ node's
// transform is keyed per frame (STEP), scale 0 where the organ does not exist yet; an organ whose
// geometry changed otherwise has a child node per shape, each shown on its frames by a sparse
// scale key (1 where shown, 0 elsewhere), so a frame costs a few numbers where the organ only
// grew and moved, and a new mesh only where its shape changed.

#include <algorithm>
#include <map>
#include <memory>

#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "scene_io/export_common.h"
#include "scene_io/gltf_instancing.h"
#include "scene_io/gltf_internal.h"
#include "scene_io/instancing.h"

namespace plantarch::gltf {

namespace {

bool uvsMatter(const Material& m, const GltfOptions& options) {
    return options.uvs &&
           (!m.texture.empty() || options.appearance.style == MaterialStyle::Textured);
}

std::array<float, 4> xyzw(const glm::quat& q) {
    return {q.x, q.y, q.z, q.w};
}

// The keys of one organ: its transform at each key (frames, then the last frame again so that
// it is held for a whole frame time), scale 0 where it does not exist.
struct OrganKeys {
    std::vector<vec3> translation;
    std::vector<std::array<float, 4>> rotation;
    std::vector<vec3> scale;
};

OrganKeys organKeys(const io::OrganTrack& track, vec3 base, std::size_t keys) {
    const std::size_t frames = track.frames.size();
    OrganKeys k;
    std::optional<io::OrganPlacement> held;  // the nearest placement, for the absent frames
    for (const auto& p : track.frames)
        if (p) {
            held = p;
            break;
        }
    for (std::size_t i = 0; i < keys; ++i) {
        const auto& p = track.frames[std::min(i, frames - 1)];
        if (p) held = p;
        k.translation.push_back(held->translation - base);
        k.rotation.push_back(xyzw(held->rotation));
        k.scale.push_back(p ? vec3(p->scale) : vec3(0.0f));
    }
    return k;
}

template <class T>
bool constant(const std::vector<T>& values) {
    return std::all_of(values.begin(), values.end(), [&](const T& v) { return v == values[0]; });
}

// Builds the organ nodes, their meshes and the animation's channels.
class OrganWriter {
public:
    OrganWriter(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer)
        : d_(d), s_(s), options_(options), buffer_(buffer) {
        if (s.animated) keys_ = s.frames.size() + 1;
    }

    json plantNodes();
    json animation();

private:
    std::size_t organNode(std::size_t track, vec3 base);
    std::size_t mesh(std::size_t shape);
    // Whether shape k's mesh carries tangents: its material has a normal map.
    bool tangents(std::size_t k) const {
        const json& material = d_.materials[s_.shapeMaterials[k]];
        return options_.normals && material.contains("normalTexture") &&
               !s_.frames[s_.organs.shapes[k].frame]->object(s_.organs.shapes[k].id).uvs.empty();
    }
    std::size_t sharedAccessor(std::map<std::pair<std::size_t, std::size_t>, std::size_t>& cache,
                               std::pair<std::size_t, std::size_t> key,
                               const std::function<std::size_t()>& make);
    template <class T>
    std::size_t keyAccessor(std::vector<T> values, const char* type);
    void channel(std::size_t node, const char* path, std::size_t output);
    std::size_t visibility(const io::OrganTrack& track, std::size_t shape);
    std::size_t morphMesh(std::size_t base, const std::vector<std::size_t>& targets);
    std::size_t morphWeights(const io::OrganTrack& track, const std::vector<std::size_t>& targets);

    GltfArrays& d_;
    const Scene& s_;
    const GltfOptions& options_;
    Buffer& buffer_;
    std::size_t keys_ = 0;  // keys per channel (animations)
    std::optional<std::size_t> times_;
    json channels_ = json::array(), samplers_ = json::array();
    std::map<std::size_t, std::size_t> meshOf_;
    // Arrays shared by shapes: indices, UVs, plant and organ labels by topology; object labels
    // by (topology, track).
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> indices_, uvs_, plantLabels_,
        organLabels_, objectLabels_, featureLabels_;
};

std::size_t OrganWriter::sharedAccessor(
    std::map<std::pair<std::size_t, std::size_t>, std::size_t>& cache,
    std::pair<std::size_t, std::size_t> key, const std::function<std::size_t()>& make) {
    auto at = cache.find(key);
    if (at == cache.end()) at = cache.emplace(key, make()).first;
    return at->second;
}

std::size_t OrganWriter::mesh(std::size_t k) {
    if (auto at = meshOf_.find(k); at != meshOf_.end()) return at->second;
    const io::OrganShape& shape = s_.organs.shapes[k];
    const Context* frame = s_.frames[shape.frame];
    const ObjectID id = shape.id;
    const ObjectView o = frame->object(id);
    const std::size_t vertices = o.positions.size(), topology = shape.topology;
    const vec3 centre = shape.centre;
    auto vertexAccessor = [&](std::size_t bytes, const char* type, Buffer::Fill fill) {
        const int view = buffer_.add(d_.views, vertices * bytes, kArrayBuffer, std::move(fill));
        d_.accessors.push_back(accessor(view, kFloat, vertices, type));
        return d_.accessors.size() - 1;
    };
    json attributes;
    vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const vec3& p : o.positions) {
        lo = glm::min(lo, p - centre);
        hi = glm::max(hi, p - centre);
    }
    attributes["POSITION"] = vertexAccessor(12, "VEC3", [frame, id, centre](Sink& out) {
        const ObjectView v = frame->object(id);
        writeValues<vec3>(out, v.positions.size(),
                          [&](std::size_t i) { return v.positions[i] - centre; });
    });
    d_.accessors.back()["min"] = {lo.x, lo.y, lo.z};
    d_.accessors.back()["max"] = {hi.x, hi.y, hi.z};
    if (options_.normals)
        attributes["NORMAL"] = vertexAccessor(12, "VEC3", [frame, id](Sink& out) {
            std::vector<vec3> normals;
            smoothNormals(frame->object(id), normals);
            out.write(normals.data(), normals.size() * sizeof(vec3));
        });
    if (!o.uvs.empty() && uvsMatter(s_.materials[s_.shapeMaterials[k]], options_))
        attributes["TEXCOORD_0"] = sharedAccessor(uvs_, {topology, 0}, [&] {
            return vertexAccessor(8, "VEC2", [frame, id](Sink& out) {
                const ObjectView v = frame->object(id);
                out.write(v.uvs.data(), v.uvs.size_bytes());
            });
        });
    if (tangents(k))
        attributes["TANGENT"] = vertexAccessor(16, "VEC4", [frame, id](Sink& out) {
            std::vector<vec3> normals;
            std::vector<glm::vec4> tangents;
            const ObjectView v = frame->object(id);
            smoothNormals(v, normals);
            objectTangents(v, normals.data(), tangents);
            out.write(tangents.data(), tangents.size() * sizeof(glm::vec4));
        });
    json primitive;
    if (options_.labels) {
        auto constantLabel = [&](float value) {
            return vertexAccessor(4, "SCALAR", [vertices, value](Sink& out) {
                writeValues<float>(out, vertices, [value](std::size_t) { return value; });
            });
        };
        const io::ObjectLabels& l = s_.organs.tracks[shape.users.front()].labels;
        attributes["_PLANT_ID"] = sharedAccessor(plantLabels_, {topology, 0},
                                                 [&] { return constantLabel(float(l.plant)); });
        attributes["_ORGAN"] = sharedAccessor(organLabels_, {topology, 0},
                                              [&] { return constantLabel(float(l.organ)); });
        if (shape.users.size() == 1) {  // the object and its row in the property table
            const std::size_t t = shape.users.front();
            attributes["_OBJECT_ID"] = sharedAccessor(objectLabels_, {topology, t}, [&] {
                return constantLabel(float(s_.records[t].id));
            });
            attributes["_FEATURE_ID_0"] = sharedAccessor(featureLabels_, {topology, t},
                                                         [&] { return constantLabel(float(t)); });
            primitive["extensions"]["EXT_mesh_features"] = {
                {"featureIds", {{{"featureCount", 1}, {"attribute", 0}, {"propertyTable", 0}}}}};
        }
    }
    const std::size_t triangles = o.triangleCount();
    primitive["indices"] = sharedAccessor(indices_, {topology, 0}, [&] {
        const int view =
            buffer_.add(d_.views, triangles * 12, kElementArrayBuffer, [frame, id](Sink& out) {
                const ObjectView v = frame->object(id);
                out.write(v.indices.data(), v.indices.size_bytes());
            });
        d_.accessors.push_back(accessor(view, kUInt, triangles * 3, "SCALAR"));
        return d_.accessors.size() - 1;
    });
    primitive["attributes"] = attributes;
    primitive["material"] = s_.shapeMaterials[k];
    primitive["mode"] = 4;
    const io::ObjectLabels& l = s_.organs.tracks[shape.users.front()].labels;
    d_.meshes.push_back(
        {{"name", std::string(kOrganLabels[l.organ])}, {"primitives", json::array({primitive})}});
    meshOf_.emplace(k, d_.meshes.size() - 1);
    return d_.meshes.size() - 1;
}

template <class T>
std::size_t OrganWriter::keyAccessor(std::vector<T> values, const char* type) {
    const std::size_t count = values.size();
    auto shared = std::make_shared<std::vector<T>>(std::move(values));
    const int view = buffer_.add(d_.views, count * sizeof(T), 0, [shared](Sink& out) {
        out.write(shared->data(), shared->size() * sizeof(T));
    });
    d_.accessors.push_back(accessor(view, kFloat, count, type));
    return d_.accessors.size() - 1;
}

void OrganWriter::channel(std::size_t node, const char* path, std::size_t output) {
    if (!times_) {
        std::vector<float> times;
        for (std::size_t i = 0; i < keys_; ++i)
            times.push_back(float(double(i) / s_.framesPerSecond));
        const float first = times.front(), last = times.back();
        times_ = keyAccessor(std::move(times), "SCALAR");
        d_.accessors[*times_]["min"] = {first};
        d_.accessors[*times_]["max"] = {last};
    }
    samplers_.push_back({{"input", *times_}, {"output", output}, {"interpolation", "STEP"}});
    channels_.push_back(
        {{"sampler", samplers_.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
}

// The scale keys of one shape of an organ: 1 on the frames that show it, 0 elsewhere, as a
// sparse accessor (zeros but for the frames shown).
std::size_t OrganWriter::visibility(const io::OrganTrack& track, std::size_t shape) {
    auto shown = std::make_shared<std::vector<std::uint32_t>>();
    for (std::size_t i = 0; i < keys_; ++i) {
        const auto& p = track.frames[std::min(i, track.frames.size() - 1)];
        if (p && p->shape == shape) shown->push_back(std::uint32_t(i));
    }
    const std::size_t n = shown->size();
    const int indices = buffer_.add(
        d_.views, n * 4, 0, [shown](Sink& out) { out.write(shown->data(), shown->size() * 4); });
    const int values = buffer_.add(d_.views, n * 12, 0, [n](Sink& out) {
        writeValues<vec3>(out, n, [](std::size_t) { return vec3(1.0f); });
    });
    d_.accessors.push_back({{"componentType", kFloat},
                            {"count", keys_},
                            {"type", "VEC3"},
                            {"sparse",
                             {{"count", n},
                              {"indices", {{"bufferView", indices}, {"componentType", kUInt}}},
                              {"values", {{"bufferView", values}}}}}});
    return d_.accessors.size() - 1;
}

// A mesh showing shape `base` with the other shapes of its topology as morph targets: target
// k holds shape k's vertices (about its centre) minus the base's, and its normals' and
// tangents' change.
std::size_t OrganWriter::morphMesh(std::size_t base, const std::vector<std::size_t>& targets) {
    json primitive = d_.meshes[mesh(base)]["primitives"][0];
    const io::OrganShape& b = s_.organs.shapes[base];
    const std::size_t vertices = s_.frames[b.frame]->object(b.id).positions.size();
    const std::size_t count = targets.size(), bytes = count * vertices * sizeof(vec3);
    // Called while the file is written, after this writer is gone: captures the scene only.
    enum Of { Positions, Normals, Tangents };
    auto deltas = [&s = s_, base, targets](Sink& out, Of of) {
        auto values = [&](std::size_t k, std::vector<vec3>& v) {
            const io::OrganShape& shape = s.organs.shapes[k];
            const ObjectView o = s.frames[shape.frame]->object(shape.id);
            if (of != Positions) smoothNormals(o, v);
            if (of == Normals) return;
            if (of == Tangents) {
                std::vector<glm::vec4> t;
                objectTangents(o, v.data(), t);
                for (std::size_t i = 0; i < v.size(); ++i) v[i] = vec3(t[i]);
                return;
            }
            v.resize(o.positions.size());
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = o.positions[i] - shape.centre;
        };
        std::vector<vec3> from, to;
        values(base, from);
        for (std::size_t k : targets) {
            values(k, to);
            writeValues<vec3>(out, to.size(), [&](std::size_t i) { return to[i] - from[i]; });
        }
    };
    auto view = [&](bool wanted, Of of) {
        if (!wanted) return -1;
        const int v = buffer_.add(d_.views, bytes, kArrayBuffer,
                                  [deltas, of](Sink& out) { deltas(out, of); });
        d_.views[std::size_t(v)]["byteStride"] = sizeof(vec3);
        return v;
    };
    const int positions = view(true, Positions), normals = view(options_.normals, Normals),
              tangents = view(primitive["attributes"].contains("TANGENT"), Tangents);
    const ObjectView from = s_.frames[b.frame]->object(b.id);
    json list = json::array();
    for (std::size_t t = 0; t < count; ++t) {
        const io::OrganShape& shape = s_.organs.shapes[targets[t]];
        const ObjectView to = s_.frames[shape.frame]->object(shape.id);
        vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (std::size_t i = 0; i < vertices; ++i) {
            const vec3 d = (to.positions[i] - shape.centre) - (from.positions[i] - b.centre);
            lo = glm::min(lo, d);
            hi = glm::max(hi, d);
        }
        json position = accessor(positions, kFloat, vertices, "VEC3");
        position["byteOffset"] = t * vertices * sizeof(vec3);
        position["min"] = {lo.x, lo.y, lo.z};
        position["max"] = {hi.x, hi.y, hi.z};
        d_.accessors.push_back(std::move(position));
        json target = {{"POSITION", d_.accessors.size() - 1}};
        for (const auto& [view, name] : {std::pair{normals, "NORMAL"}, {tangents, "TANGENT"}}) {
            if (view < 0) continue;
            json delta = accessor(view, kFloat, vertices, "VEC3");
            delta["byteOffset"] = t * vertices * sizeof(vec3);
            d_.accessors.push_back(std::move(delta));
            target[name] = d_.accessors.size() - 1;
        }
        list.push_back(std::move(target));
    }
    primitive["targets"] = list;
    d_.meshes.push_back({{"name", d_.meshes[mesh(base)]["name"]},
                         {"primitives", json::array({primitive})},
                         {"weights", std::vector<float>(count, 0.0f)}});
    return d_.meshes.size() - 1;
}

// The morph weights of an organ at each key: 1 for the target shown, all 0 where the base (its
// last shape) is shown; a sparse accessor holding the ones.
std::size_t OrganWriter::morphWeights(const io::OrganTrack& track,
                                      const std::vector<std::size_t>& targets) {
    auto ones = std::make_shared<std::vector<std::uint32_t>>();
    for (std::size_t i = 0; i < keys_; ++i) {
        const auto& p = track.frames[std::min(i, track.frames.size() - 1)];
        if (!p) continue;
        const auto at = std::find(targets.begin(), targets.end(), p->shape);
        if (at != targets.end())
            ones->push_back(std::uint32_t(i * targets.size() + std::size_t(at - targets.begin())));
    }
    const std::size_t n = ones->size();
    const int indices = buffer_.add(
        d_.views, n * 4, 0, [ones](Sink& out) { out.write(ones->data(), ones->size() * 4); });
    const int values = buffer_.add(d_.views, n * 4, 0, [n](Sink& out) {
        writeValues<float>(out, n, [](std::size_t) { return 1.0f; });
    });
    d_.accessors.push_back({{"componentType", kFloat},
                            {"count", keys_ * targets.size()},
                            {"type", "SCALAR"},
                            {"sparse",
                             {{"count", n},
                              {"indices", {{"bufferView", indices}, {"componentType", kUInt}}},
                              {"values", {{"bufferView", values}}}}}});
    return d_.accessors.size() - 1;
}

std::size_t OrganWriter::organNode(std::size_t t, vec3 base) {
    const io::OrganTrack& track = s_.organs.tracks[t];
    const io::OrganPlacement& last = *track.frames[track.lastFrame];
    std::vector<std::size_t> shapes;  // in order of first use
    for (const auto& p : track.frames)
        if (p && std::find(shapes.begin(), shapes.end(), p->shape) == shapes.end())
            shapes.push_back(p->shape);
    const ObjectRecord& r = s_.records[t];
    json node = {{"name", io::organName(track)},
                 {"extras",
                  {{"plantID", r.plant},
                   {"objectID", r.id},
                   {"organ", std::string(kOrganLabels[r.organ])},
                   {"shoot", r.shoot},
                   {"rank", r.rank},
                   {"node", r.node},
                   {"leaf", r.leaf},
                   {"age", r.age},
                   {"feature", t}}}};
    const vec3 at = last.translation - base;
    if (at != vec3(0.0f)) node["translation"] = {at.x, at.y, at.z};
    if (last.rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) {
        const auto q = xyzw(last.rotation);
        node["rotation"] = {q[0], q[1], q[2], q[3]};
    }
    if (last.scale != 1.0f) node["scale"] = {last.scale, last.scale, last.scale};
    std::vector<std::pair<std::size_t, std::size_t>> variants;  // (node, shape)
    std::vector<std::size_t> targets;                           // morph targets: shapes
    const std::size_t topology = s_.organs.shapes[last.shape].topology;
    const bool oneTopology = std::all_of(shapes.begin(), shapes.end(), [&](std::size_t k) {
        return s_.organs.shapes[k].topology == topology;
    });
    if (shapes.size() == 1) {
        node["mesh"] = mesh(shapes.front());
    } else if (oneTopology) {  // the other shapes as morph targets of the last one
        for (std::size_t k : shapes)
            if (k != last.shape) targets.push_back(k);
        node["mesh"] = morphMesh(last.shape, targets);
    } else {
        json children = json::array();
        for (std::size_t k = 0; k < shapes.size(); ++k) {
            json child = {{"name", io::organName(track) + "_v" + std::to_string(k)},
                          {"mesh", mesh(shapes[k])}};
            if (shapes[k] != last.shape) child["scale"] = {0.0, 0.0, 0.0};
            d_.nodes.push_back(std::move(child));
            children.push_back(d_.nodes.size() - 1);
            variants.emplace_back(d_.nodes.size() - 1, shapes[k]);
        }
        node["children"] = children;
    }
    d_.nodes.push_back(std::move(node));
    const std::size_t index = d_.nodes.size() - 1;
    if (s_.animated) {
        OrganKeys k = organKeys(track, base, keys_);
        if (!constant(k.translation))
            channel(index, "translation", keyAccessor(std::move(k.translation), "VEC3"));
        if (!constant(k.rotation))
            channel(index, "rotation", keyAccessor(std::move(k.rotation), "VEC4"));
        if (!constant(k.scale)) channel(index, "scale", keyAccessor(std::move(k.scale), "VEC3"));
        for (const auto& [child, shape] : variants)
            channel(child, "scale", visibility(track, shape));
        if (!targets.empty()) channel(index, "weights", morphWeights(track, targets));
    }
    return index;
}

json OrganWriter::plantNodes() {
    // Each plant's node as in its last frame; plants in ID order, the objects of no plant last.
    std::map<std::pair<bool, std::int32_t>, const Node*> plants;
    for (const Node& n : s_.nodes) plants[{n.plant < 0, n.plant}] = &n;
    std::map<std::int32_t, std::vector<std::size_t>> tracksOf;
    for (std::size_t t = 0; t < s_.organs.tracks.size(); ++t)
        tracksOf[s_.organs.tracks[t].labels.plant].push_back(t);
    json roots = json::array();
    for (const auto& [key, plant] : plants) {
        json children = json::array();
        std::map<std::int32_t, std::pair<std::int32_t, json>> shoots;  // rank, nodes
        for (std::size_t t : tracksOf[plant->plant]) {
            if (options_.instancing == Instancing::Gpu &&
                io::gpuInstanced(s_.organs.shapes[io::onlyPlacement(s_.organs.tracks[t]).shape],
                                 options_.instancing))
                continue;  // an instance (gltf_instancing.cpp)
            const std::size_t node = organNode(t, plant->base);
            const io::ObjectLabels& l = s_.organs.tracks[t].labels;
            if (l.shoot < 0) {
                children.push_back(node);
                continue;
            }
            auto& [rank, nodes] = shoots[l.shoot];
            rank = l.rank;
            nodes.push_back(node);
        }
        for (auto& [shoot, content] : shoots) {
            d_.nodes.push_back({{"name", "shoot_" + std::to_string(shoot)},
                                {"extras", {{"shoot", shoot}, {"rank", content.first}}},
                                {"children", content.second}});
            children.push_back(d_.nodes.size() - 1);
        }
        addInstanceNodes(
            d_, s_, options_, buffer_, tracksOf[plant->plant], plant->base,
            [this](std::size_t k) { return mesh(k); }, children);
        d_.nodes.push_back(plantNode(*plant, children));
        roots.push_back(d_.nodes.size() - 1);
    }
    return roots;
}

json OrganWriter::animation() {
    if (!s_.animated) return json();
    json days = json::array();
    for (double day : s_.days) days.push_back(day);
    return {{"name", "growth"},
            {"channels", channels_},
            {"samplers", samplers_},
            {"extras", {{"days", days}}}};
}

}  // namespace

void collectOrgans(Scene& s, const GltfOptions& options) {
    s.organNodes = true;
    // UVs matter only where a texture maps them: shapes of flat colours are shared whatever
    // their UVs, and written without them.
    s.organs =
        io::trackOrgans(s.frames, options.includeHidden, options.instancing != Instancing::None,
                        [&options](const Material& m) { return uvsMatter(m, options); });
    std::map<std::pair<std::uint32_t, ObjectID>, std::size_t> recordOf;
    for (std::size_t i = 0; i < s.records.size(); ++i)
        recordOf[{s.records[i].frame, s.records[i].id}] = i;
    for (const io::OrganShape& shape : s.organs.shapes)
        s.shapeMaterials.push_back(s.records[recordOf.at({shape.frame, shape.id})].material);
    std::vector<ObjectRecord> records;
    for (const io::OrganTrack& t : s.organs.tracks)
        records.push_back(s.records[recordOf.at({t.lastFrame, t.lastID})]);
    s.records = std::move(records);
    s.primitives.clear();
}

json addOrganNodes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                   json& roots) {
    OrganWriter writer(d, s, options, buffer);
    roots = writer.plantNodes();
    return writer.animation();
}

}  // namespace plantarch::gltf
