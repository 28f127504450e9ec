// The Context's storage: contiguous pools for positions, UVs and indices, one record per
// object, a primitive-to-object table, columnar object data and sparse primitive data.

#include "plantarch/Context.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

#include "core/pool_allocator.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// Pools whose writers fill every element they add are grown without zeroing first.
template <class T>
using WrittenPool = std::vector<T, core::PoolAllocator<T, true>>;

struct ObjectRecord {
    std::uint32_t firstVertex = 0;
    std::uint32_t vertexCount = 0;
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    PrimitiveID firstPrimitive = 0;
    MaterialID material = 0;
    bool alive = false;
    bool hidden = false;
    bool hasUVs = false;
};

// One object-data label: values indexed by object ID, with a presence flag.
struct Column {
    DataType type = DataType::Int;
    std::uint32_t index = 0;  // position in Impl::columnByIndex (a DataColumn's index)
    // The last string set and its string-table index, so that setting the same string on
    // object after object skips the table's hash look-up.
    std::string lastString;
    std::int32_t lastStringIndex = -1;
    std::vector<std::int32_t> ints;  // Int values, or string-table indices for String
    std::vector<float> floats;
    std::vector<vec3> vecs;
    std::vector<std::uint8_t> present;
};

struct PrimitiveColumn {
    DataType type = DataType::Int;
    std::unordered_map<PrimitiveID, DataValue> values;
};

DataType typeOf(const DataValue& v) {
    return static_cast<DataType>(v.index());
}

std::string objectText(ObjectID id) {
    return std::to_string(id);
}

}  // namespace

const char* dataTypeName(DataType type) {
    switch (type) {
        case DataType::Int:
            return "int";
        case DataType::Float:
            return "float";
        case DataType::String:
            return "string";
        case DataType::Vec3:
            return "vec3";
    }
    return "?";
}

struct Context::Impl {
    WrittenPool<vec3> positions;
    WrittenPool<vec2> uvs;  // parallel to positions once any object has UVs (else empty);
                            // zeros for objects without UVs
    bool uvsEnabled = false;
    WrittenPool<std::uint32_t> indices;
    std::vector<ObjectRecord> objects;
    WrittenPool<ObjectID> primitiveOwner;  // PrimitiveID -> ObjectID or kNone
    std::vector<Material> materials;
    std::map<std::string, Column, std::less<>> columns;
    std::vector<Column*> columnByIndex;  // DataColumn::index -> column (map nodes stay put)
    std::map<std::string, PrimitiveColumn, std::less<>> primitiveColumns;
    std::vector<std::string> strings;
    std::unordered_map<std::string, std::int32_t> stringIndex;

    std::size_t liveObjects = 0;
    std::size_t liveTriangles = 0;
    std::size_t liveVertices = 0;
    std::size_t liveIndices = 0;
    std::size_t triangleLimit = 0;  // 0: none
    unsigned nextPlantID = 0;       // reservePlantIDs: kept through clear()

    Impl() { materials.push_back(Material{}); }

    // Throws if `added` more (and `removed` fewer) live triangles would pass the limit.
    void checkTriangleLimit(std::size_t added, std::size_t removed = 0) const {
        if (triangleLimit == 0 || added <= removed) return;
        const std::size_t total = liveTriangles - removed + added;
        if (total > triangleLimit)
            throw TriangleBudgetError("the scene", total, triangleLimit,
                                      "adding " + std::to_string(added - removed) + " to " +
                                          std::to_string(liveTriangles));
    }

    const ObjectRecord& record(ObjectID id, const char* what) const {
        if (id >= objects.size() || !objects[id].alive)
            throw Error(std::string(what) + ": no such object",
                        {.parameter = "objectID", .value = objectText(id)});
        return objects[id];
    }
    ObjectRecord& record(ObjectID id, const char* what) {
        return const_cast<ObjectRecord&>(std::as_const(*this).record(id, what));
    }

    void checkMaterial(MaterialID m) const {
        if (m >= materials.size())
            throw Error("no such material",
                        {.parameter = "materialID",
                         .value = std::to_string(m),
                         .validRange = "0 to " + std::to_string(materials.size() - 1)});
    }

    // The index count, UV count and index range of a mesh of `vertices` vertices.
    static void checkStructure(std::size_t vertices, std::size_t uvCount,
                               std::span<const std::uint32_t> idx) {
        if (idx.size() % 3 != 0 || (uvCount != 0 && uvCount != vertices)) {
            Mesh probe;  // reuse Mesh::validate's messages
            probe.indices.assign(idx.begin(), idx.end());
            probe.positions.resize(vertices);
            probe.uvs.resize(uvCount);
            probe.validate();
        }
        std::uint32_t largest = 0;
        for (std::uint32_t i : idx) largest = std::max(largest, i);
        if (!idx.empty() && largest >= vertices)
            for (std::size_t i = 0; i < idx.size(); ++i)
                if (idx[i] >= vertices)
                    throw Error(
                        "vertex index out of range",
                        {.parameter = "mesh.indices[" + std::to_string(i) + "]",
                         .value = std::to_string(idx[i]),
                         .validRange = "0 to " + std::to_string(vertices) + " (exclusive)"});
    }

    // Throws unless every coordinate is finite; returns the largest magnitude. (A float's
    // magnitude orders as its bits without the sign; infinity and NaN are the largest.)
    static float checkFinite(std::span<const vec3> pos) {
        static_assert(sizeof(vec3) == 3 * sizeof(float));
        const auto* bits = reinterpret_cast<const std::uint32_t*>(pos.data());
        std::uint32_t largest = 0;
        for (std::size_t i = 0; i < 3 * pos.size(); ++i)
            largest = std::max(largest, bits[i] & 0x7fffffffu);
        if (largest >= 0x7f800000u)
            for (std::size_t i = 0; i < pos.size(); ++i)
                if (!std::isfinite(pos[i].x) || !std::isfinite(pos[i].y) ||
                    !std::isfinite(pos[i].z))
                    throw Error("vertex position is not finite",
                                {.parameter = "mesh.positions[" + std::to_string(i) + "]",
                                 .validRange = "finite coordinates"});
        return std::bit_cast<float>(largest);
    }

    static void checkSize(std::size_t vertices, std::size_t indices) {
        if (vertices >= kNone || indices >= kNone)
            throw Error("mesh too large", {.value = std::to_string(vertices) + " vertices"});
    }

    static void checkGeometry(std::span<const vec3> pos, std::span<const vec2> uv,
                              std::span<const std::uint32_t> idx) {
        checkStructure(pos.size(), uv.size(), idx);
        checkFinite(pos);
        checkSize(pos.size(), idx.size());
    }

    // Checks a mesh to be placed by `xf`; false when the placed positions might not be finite
    // (the caller then places a copy and checks that).
    static bool checkPlaced(const Mesh& mesh, const mat4& xf) {
        checkStructure(mesh.positions.size(), mesh.uvs.size(), mesh.indices);
        const float largest = checkFinite(mesh.positions);
        checkSize(mesh.positions.size(), mesh.indices.size());
        float entries = 0.0f;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                if (!std::isfinite(xf[c][r])) return false;
                entries = std::max(entries, std::abs(xf[c][r]));
            }
        // Each placed coordinate is a sum of four products, none above largest x entries.
        return double(std::max(largest, 1.0f)) * double(entries) * 4.0 < 1e37;
    }

    PrimitiveID allocatePrimitives(ObjectID owner, std::uint32_t count) {
        const auto first = static_cast<PrimitiveID>(primitiveOwner.size());
        if (primitiveOwner.size() + count >= kNone)
            throw Error("primitive ID space exhausted (4 billion triangles ever created)");
        primitiveOwner.resize(primitiveOwner.size() + count, owner);
        return first;
    }

    void releasePrimitives(const ObjectRecord& r) {
        const std::uint32_t n = r.indexCount / 3;
        for (std::uint32_t i = 0; i < n; ++i) primitiveOwner[r.firstPrimitive + i] = kNone;
        for (auto& [label, col] : primitiveColumns)
            if (!col.values.empty())
                for (std::uint32_t i = 0; i < n; ++i) col.values.erase(r.firstPrimitive + i);
    }

    // Writes geometry into the pools: in place when it fits the object's current ranges,
    // else at the end of the pools (the old ranges become garbage until compact()).
    void storeGeometry(ObjectRecord& r, std::span<const vec3> pos, std::span<const vec2> uv,
                       std::span<const std::uint32_t> idx, const mat4* xf = nullptr) {
        const auto nv = static_cast<std::uint32_t>(pos.size());
        const auto ni = static_cast<std::uint32_t>(idx.size());
        if (!uv.empty() && !uvsEnabled) {
            uvsEnabled = true;
            uvs.resize(positions.size(), vec2(0.0f));
        }
        const bool fits = r.alive && nv <= r.vertexCount && ni <= r.indexCount;
        if (!fits) {
            r.firstVertex = static_cast<std::uint32_t>(positions.size());
            r.firstIndex = static_cast<std::uint32_t>(indices.size());
            if (positions.size() + nv >= kNone || indices.size() + ni >= kNone)
                throw Error("Context is full (more than 4 billion vertices or indices)");
            positions.resize(positions.size() + nv);
            if (uvsEnabled) uvs.resize(positions.size());
            indices.resize(indices.size() + ni);
        }
        if (xf) {
            auto out = positions.begin() + r.firstVertex;
            for (std::size_t i = 0; i < pos.size(); ++i)
                out[i] = vec3(*xf * glm::vec4(pos[i], 1.0f));
        } else {
            std::copy(pos.begin(), pos.end(), positions.begin() + r.firstVertex);
        }
        if (!uv.empty())
            std::copy(uv.begin(), uv.end(), uvs.begin() + r.firstVertex);
        else if (uvsEnabled)
            std::fill_n(uvs.begin() + r.firstVertex, nv, vec2(0.0f));
        std::copy(idx.begin(), idx.end(), indices.begin() + r.firstIndex);
        r.vertexCount = nv;
        r.indexCount = ni;
        r.hasUVs = !uv.empty();
    }

    std::size_t garbage() const {
        return (positions.size() - liveVertices) * sizeof(vec3) +
               (indices.size() - liveIndices) * sizeof(std::uint32_t);
    }

    void maybeCompact() {
        const std::size_t total =
            positions.size() * sizeof(vec3) + indices.size() * sizeof(std::uint32_t);
        if (total > (1u << 20) && garbage() * 2 > total) compact();
    }

    void compact() {
        WrittenPool<vec3> newPos;
        WrittenPool<vec2> newUV;
        WrittenPool<std::uint32_t> newIdx;
        newPos.reserve(liveVertices);
        newIdx.reserve(liveIndices);
        const bool anyUV = uvsEnabled;
        if (anyUV) newUV.reserve(liveVertices);
        for (ObjectRecord& r : objects) {
            if (!r.alive) continue;
            const auto fv = static_cast<std::uint32_t>(newPos.size());
            const auto fi = static_cast<std::uint32_t>(newIdx.size());
            newPos.insert(newPos.end(), positions.begin() + r.firstVertex,
                          positions.begin() + r.firstVertex + r.vertexCount);
            if (anyUV)
                newUV.insert(newUV.end(), uvs.begin() + r.firstVertex,
                             uvs.begin() + r.firstVertex + r.vertexCount);
            newIdx.insert(newIdx.end(), indices.begin() + r.firstIndex,
                          indices.begin() + r.firstIndex + r.indexCount);
            r.firstVertex = fv;
            r.firstIndex = fi;
        }
        positions = std::move(newPos);
        uvs = std::move(newUV);
        indices = std::move(newIdx);
    }

    std::int32_t intern(const std::string& s) {
        auto [it, inserted] = stringIndex.try_emplace(s, static_cast<std::int32_t>(strings.size()));
        if (inserted) strings.push_back(s);
        return it->second;
    }

    Column& columnFor(std::string_view label, DataType type) {
        auto it = columns.find(label);
        if (it == columns.end()) {
            if (label.empty()) throw Error("data label must not be empty", {.parameter = "label"});
            it = columns.emplace(std::string(label), Column{}).first;
            it->second.type = type;
            it->second.index = static_cast<std::uint32_t>(columnByIndex.size());
            columnByIndex.push_back(&it->second);
        } else if (it->second.type != type) {
            throw Error(std::string("object data label already holds ") +
                            dataTypeName(it->second.type) + " values",
                        {.parameter = std::string(label),
                         .value = dataTypeName(type),
                         .validRange = dataTypeName(it->second.type)});
        }
        return it->second;
    }

    // After a copy, the column pointers must point into this Impl's own map.
    void relinkColumns() {
        for (auto& [label, col] : columns) columnByIndex[col.index] = &col;
    }

    // Sets one value in a column whose type the caller has checked.
    void setValue(Column& col, ObjectID id, const DataValue& value) {
        if (col.present.size() <= id) col.present.resize(objects.size(), 0);
        col.present[id] = 1;
        const std::size_t n = col.present.size();
        switch (col.type) {
            case DataType::Int:
                if (col.ints.size() < n) col.ints.resize(n);
                col.ints[id] = std::get<std::int32_t>(value);
                break;
            case DataType::String: {
                if (col.ints.size() < n) col.ints.resize(n);
                const std::string& text = std::get<std::string>(value);
                if (col.lastStringIndex < 0 || text != col.lastString) {
                    col.lastStringIndex = intern(text);
                    col.lastString = text;
                }
                col.ints[id] = col.lastStringIndex;
                break;
            }
            case DataType::Float:
                if (col.floats.size() < n) col.floats.resize(n);
                col.floats[id] = std::get<float>(value);
                break;
            case DataType::Vec3:
                if (col.vecs.size() < n) col.vecs.resize(n);
                col.vecs[id] = std::get<vec3>(value);
                break;
        }
    }

    // Adds an object from checked geometry, placed by *xf when given.
    ObjectID addChecked(std::span<const vec3> pos, std::span<const vec2> uv,
                        std::span<const std::uint32_t> idx, MaterialID material, const mat4* xf) {
        checkMaterial(material);
        checkTriangleLimit(idx.size() / 3);
        if (objects.size() >= kNone - 1) throw Error("object ID space exhausted");
        const auto id = static_cast<ObjectID>(objects.size());
        ObjectRecord r;
        storeGeometry(r, pos, uv, idx, xf);
        r.alive = true;
        r.material = material;
        r.firstPrimitive = allocatePrimitives(id, static_cast<std::uint32_t>(idx.size() / 3));
        objects.push_back(r);
        ++liveObjects;
        liveTriangles += idx.size() / 3;
        liveVertices += pos.size();
        liveIndices += idx.size();
        return id;
    }

    // Replaces a live object's geometry with checked geometry, placed by *xf when given.
    void replaceChecked(ObjectID id, const Mesh& mesh, const mat4* xf) {
        ObjectRecord& r = objects[id];
        const std::uint32_t oldTris = r.indexCount / 3;
        const auto newTris = static_cast<std::uint32_t>(mesh.triangleCount());
        checkTriangleLimit(newTris, oldTris);
        liveTriangles += newTris;
        liveTriangles -= oldTris;
        liveVertices += mesh.positions.size();
        liveVertices -= r.vertexCount;
        liveIndices += mesh.indices.size();
        liveIndices -= r.indexCount;
        if (newTris != oldTris) {
            releasePrimitives(r);
            r.firstPrimitive = allocatePrimitives(id, newTris);
        }
        storeGeometry(r, mesh.positions, mesh.uvs, mesh.indices, xf);
        maybeCompact();
    }

    void eraseObjectData(ObjectID id) {
        for (auto& [label, col] : columns)
            if (id < col.present.size()) col.present[id] = 0;
    }

    // Where one source's objects go, and how its materials, labels and strings map here.
    struct AppendPlan {
        const Impl* from = nullptr;
        std::span<const ObjectID> objects;
        ObjectID firstObject = 0;
        std::uint32_t firstVertex = 0;
        std::uint32_t firstIndex = 0;
        PrimitiveID firstPrimitive = 0;
        std::vector<MaterialID> materials;                       // source material -> here
        std::vector<std::int32_t> strings;                       // source string -> here
        std::vector<std::pair<const Column*, Column*>> columns;  // (source, here)
    };

    // The columns appended objects carry, sized for `nextObject` objects.
    void resizeAppendedColumns(const std::vector<AppendPlan>& plans, std::size_t nextObject) {
        for (auto& [label, col] : columns) {
            bool touched = false;
            for (const AppendPlan& p : plans)
                for (const auto& [from, to] : p.columns) touched = touched || to == &col;
            if (!touched) continue;
            col.present.resize(nextObject, 0);
            switch (col.type) {
                case DataType::Int:
                case DataType::String:
                    col.ints.resize(nextObject);
                    break;
                case DataType::Float:
                    col.floats.resize(nextObject);
                    break;
                case DataType::Vec3:
                    col.vecs.resize(nextObject);
                    break;
            }
        }
    }

    // Copies one source's objects into the ranges its plan reserved. Nothing here throws.
    void copyAppended(const AppendPlan& p) {
        const Impl& f = *p.from;
        ObjectID id = p.firstObject;
        std::uint32_t v = p.firstVertex, x = p.firstIndex;
        PrimitiveID prim = p.firstPrimitive;
        for (ObjectID o : p.objects) {
            const ObjectRecord& r = f.objects[o];
            std::copy_n(f.positions.begin() + r.firstVertex, r.vertexCount, positions.begin() + v);
            if (r.hasUVs)
                std::copy_n(f.uvs.begin() + r.firstVertex, r.vertexCount, uvs.begin() + v);
            else if (uvsEnabled)
                std::fill_n(uvs.begin() + v, r.vertexCount, vec2(0.0f));
            std::copy_n(f.indices.begin() + r.firstIndex, r.indexCount, indices.begin() + x);
            ObjectRecord& n = objects[id];
            n = r;
            n.firstVertex = v;
            n.firstIndex = x;
            n.firstPrimitive = prim;
            n.material = p.materials[r.material];
            std::fill_n(primitiveOwner.begin() + prim, r.indexCount / 3, id);
            for (const auto& [fromColumn, toColumn] : p.columns) {
                const Column& a = *fromColumn;
                Column& b = *toColumn;
                if (o >= a.present.size() || !a.present[o]) continue;
                b.present[id] = 1;
                switch (a.type) {
                    case DataType::Int:
                        b.ints[id] = a.ints[o];
                        break;
                    case DataType::String:
                        b.ints[id] = p.strings[std::size_t(a.ints[o])];
                        break;
                    case DataType::Float:
                        b.floats[id] = a.floats[o];
                        break;
                    case DataType::Vec3:
                        b.vecs[id] = a.vecs[o];
                        break;
                }
            }
            v += r.vertexCount;
            x += r.indexCount;
            prim += r.indexCount / 3;
            ++id;
        }
    }

    // One source's primitive data (rare: plants carry none), one thread.
    void appendPrimitiveData(const AppendPlan& p) {
        for (const auto& [label, col] : p.from->primitiveColumns) {
            if (col.values.empty()) continue;
            auto it = primitiveColumns.find(label);
            if (it == primitiveColumns.end()) {
                it = primitiveColumns.emplace(label, PrimitiveColumn{}).first;
                it->second.type = col.type;
            }
            ObjectID id = p.firstObject;
            for (ObjectID o : p.objects) {
                const ObjectRecord& r = p.from->objects[o];
                const PrimitiveID to = objects[id++].firstPrimitive;
                for (std::uint32_t t = 0; t < r.indexCount / 3; ++t)
                    if (auto v = col.values.find(r.firstPrimitive + t); v != col.values.end())
                        it->second.values[to + t] = v->second;
            }
        }
    }
};

Context::Context() : impl_(std::make_unique<Impl>()) {}
Context::~Context() = default;
Context::Context(const Context& o) : impl_(std::make_unique<Impl>(*o.impl_)) {
    impl_->relinkColumns();
}
Context& Context::operator=(const Context& o) {
    if (this != &o) {
        impl_ = std::make_unique<Impl>(*o.impl_);
        impl_->relinkColumns();
    }
    return *this;
}
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

// ---- materials -------------------------------------------------------------------------

MaterialID Context::addMaterial(const Material& m) {
    for (std::size_t i = 0; i < impl_->materials.size(); ++i)
        if (impl_->materials[i] == m) return static_cast<MaterialID>(i);
    impl_->materials.push_back(m);
    return static_cast<MaterialID>(impl_->materials.size() - 1);
}

const Material& Context::material(MaterialID id) const {
    impl_->checkMaterial(id);
    return impl_->materials[id];
}

std::size_t Context::materialCount() const {
    return impl_->materials.size();
}

// ---- objects ---------------------------------------------------------------------------

ObjectID Context::addObject(const Mesh& mesh, MaterialID material) {
    return addObject(mesh.positions, mesh.uvs, mesh.indices, material);
}

ObjectID Context::addObject(const Mesh& mesh, const Material& material) {
    return addObject(mesh, addMaterial(material));
}

ObjectID Context::addObject(std::span<const vec3> positions, std::span<const vec2> uvs,
                            std::span<const std::uint32_t> indices, MaterialID material) {
    Impl::checkGeometry(positions, uvs, indices);
    return impl_->addChecked(positions, uvs, indices, material, nullptr);
}

ObjectID Context::addObject(const Mesh& mesh, const mat4& transform, MaterialID material) {
    if (!Impl::checkPlaced(mesh, transform)) {
        Mesh placed = mesh;
        placed.transform(transform);
        return addObject(placed, material);
    }
    return impl_->addChecked(mesh.positions, mesh.uvs, mesh.indices, material, &transform);
}

void Context::setObjectMesh(ObjectID id, const Mesh& mesh) {
    impl_->record(id, "setObjectMesh");
    Impl::checkGeometry(mesh.positions, mesh.uvs, mesh.indices);
    impl_->replaceChecked(id, mesh, nullptr);
}

void Context::setObjectMesh(ObjectID id, const Mesh& mesh, const mat4& transform) {
    impl_->record(id, "setObjectMesh");
    if (!Impl::checkPlaced(mesh, transform)) {
        Mesh placed = mesh;
        placed.transform(transform);
        return setObjectMesh(id, placed);
    }
    impl_->replaceChecked(id, mesh, &transform);
}

void Context::setObjectMaterial(ObjectID id, MaterialID material) {
    impl_->checkMaterial(material);
    impl_->record(id, "setObjectMaterial").material = material;
}

ObjectID Context::copyObject(ObjectID id) {
    Impl& d = *impl_;
    const ObjectRecord src = d.record(id, "copyObject");
    // Copy out first: adding may reallocate the pools the spans point into.
    const std::vector<vec3> pos(d.positions.begin() + src.firstVertex,
                                d.positions.begin() + src.firstVertex + src.vertexCount);
    std::vector<vec2> uv;
    if (src.hasUVs)
        uv.assign(d.uvs.begin() + src.firstVertex,
                  d.uvs.begin() + src.firstVertex + src.vertexCount);
    const std::vector<std::uint32_t> idx(d.indices.begin() + src.firstIndex,
                                         d.indices.begin() + src.firstIndex + src.indexCount);
    const ObjectID copy = addObject(pos, uv, idx, src.material);
    d.objects[copy].hidden = src.hidden;
    for (auto& [label, col] : d.columns) {
        if (id >= col.present.size() || !col.present[id]) continue;
        col.present.resize(std::max<std::size_t>(col.present.size(), copy + 1), 0);
        col.present[copy] = 1;
        switch (col.type) {
            case DataType::Int:
            case DataType::String:
                col.ints.resize(col.present.size());
                col.ints[copy] = col.ints[id];
                break;
            case DataType::Float:
                col.floats.resize(col.present.size());
                col.floats[copy] = col.floats[id];
                break;
            case DataType::Vec3:
                col.vecs.resize(col.present.size());
                col.vecs[copy] = col.vecs[id];
                break;
        }
    }
    return copy;
}

void Context::transformObject(ObjectID id, const mat4& transform) {
    const ObjectRecord& r = impl_->record(id, "transformObject");
    auto first = impl_->positions.begin() + r.firstVertex;
    for (auto it = first; it != first + r.vertexCount; ++it)
        *it = vec3(transform * glm::vec4(*it, 1.0f));
}

void Context::setObjectHidden(ObjectID id, bool hidden) {
    impl_->record(id, "setObjectHidden").hidden = hidden;
}

bool Context::isObjectHidden(ObjectID id) const {
    return impl_->record(id, "isObjectHidden").hidden;
}

void Context::deleteObject(ObjectID id) {
    Impl& d = *impl_;
    ObjectRecord& r = d.record(id, "deleteObject");
    d.releasePrimitives(r);
    d.eraseObjectData(id);
    d.liveTriangles -= r.indexCount / 3;
    d.liveVertices -= r.vertexCount;
    d.liveIndices -= r.indexCount;
    --d.liveObjects;
    r.alive = false;
    r.vertexCount = r.indexCount = 0;
    d.maybeCompact();
}

void Context::deleteObjects(std::span<const ObjectID> ids) {
    for (ObjectID id : ids) impl_->record(id, "deleteObjects");  // all-or-nothing
    for (ObjectID id : ids)
        if (doesObjectExist(id)) deleteObject(id);
}

// ---- bulk append -----------------------------------------------------------------------

namespace {

// Throws unless every label of `from` holds the same type in `to` (or is new there).
template <class Columns>
void checkLabelTypes(const Columns& from, const Columns& to, const char* kind) {
    for (const auto& [label, col] : from) {
        auto it = to.find(label);
        if (it != to.end() && it->second.type != col.type)
            throw Error(std::string(kind) + " data label already holds " +
                            dataTypeName(it->second.type) + " values",
                        {.parameter = label,
                         .value = dataTypeName(col.type),
                         .validRange = dataTypeName(it->second.type)});
    }
}

}  // namespace

std::vector<ObjectID> Context::appendObjects(std::span<const ObjectSource> sources) {
    Impl& d = *impl_;
    // Checks first, so that nothing changes when one fails.
    std::size_t objects = 0, vertices = 0, indices = 0;
    bool anyUVs = false;
    for (const ObjectSource& s : sources) {
        if (!s.context)
            throw Error("appendObjects: a source without a Context", {.parameter = "context"});
        if (s.context == this)
            throw Error("appendObjects: a Context cannot append its own objects",
                        {.parameter = "context", .validRange = "another Context"});
        const Impl& f = *s.context->impl_;
        for (ObjectID o : s.objects) {
            const ObjectRecord& r = f.record(o, "appendObjects");
            vertices += r.vertexCount;
            indices += r.indexCount;
            anyUVs = anyUVs || r.hasUVs;
        }
        objects += s.objects.size();
        checkLabelTypes(f.columns, d.columns, "object");
        checkLabelTypes(f.primitiveColumns, d.primitiveColumns, "primitive");
    }
    if (d.objects.size() + objects >= kNone - 1) throw Error("object ID space exhausted");
    if (d.positions.size() + vertices >= kNone || d.indices.size() + indices >= kNone)
        throw Error("Context is full (more than 4 billion vertices or indices)");
    if (d.primitiveOwner.size() + indices / 3 >= kNone)
        throw Error("primitive ID space exhausted (4 billion triangles ever created)");
    d.checkTriangleLimit(indices / 3);

    // Plan (one thread): offsets, materials, labels, strings; the pools grow once.
    std::vector<Impl::AppendPlan> plans(sources.size());
    std::size_t nextObject = d.objects.size(), nextVertex = d.positions.size();
    std::size_t nextIndex = d.indices.size(), nextPrimitive = d.primitiveOwner.size();
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const Impl& f = *sources[i].context->impl_;
        Impl::AppendPlan& p = plans[i];
        p.from = &f;
        p.objects = sources[i].objects;
        p.firstObject = static_cast<ObjectID>(nextObject);
        p.firstVertex = static_cast<std::uint32_t>(nextVertex);
        p.firstIndex = static_cast<std::uint32_t>(nextIndex);
        p.firstPrimitive = static_cast<PrimitiveID>(nextPrimitive);
        p.materials.assign(f.materials.size(), kNone);
        for (ObjectID o : p.objects) {
            const ObjectRecord& r = f.objects[o];
            if (p.materials[r.material] == kNone)
                p.materials[r.material] = addMaterial(f.materials[r.material]);
            nextVertex += r.vertexCount;
            nextIndex += r.indexCount;
            nextPrimitive += r.indexCount / 3;
        }
        nextObject += p.objects.size();
        bool strings = false;
        for (const auto& [label, col] : f.columns) {
            p.columns.emplace_back(&col, &d.columnFor(label, col.type));
            strings = strings || col.type == DataType::String;
        }
        if (strings)
            for (const std::string& text : f.strings) p.strings.push_back(d.intern(text));
    }
    if (anyUVs && !d.uvsEnabled) {
        d.uvsEnabled = true;
        d.uvs.reserve(d.positions.capacity());
        d.uvs.resize(d.positions.size(), vec2(0.0f));
    }
    d.positions.resize(nextVertex);
    if (d.uvsEnabled) d.uvs.resize(nextVertex);
    d.indices.resize(nextIndex);
    d.objects.resize(nextObject);
    d.primitiveOwner.resize(nextPrimitive);
    d.resizeAppendedColumns(plans, nextObject);

    // Copy (all threads; each source writes its own ranges). Nothing in the loop throws (it
    // copies into pools sized above), so no exception can leave the parallel region.
    const long count = static_cast<long>(plans.size());
#pragma omp parallel for schedule(dynamic, 1) if (vertices > 65536 && count > 1)
    for (long i = 0; i < count; ++i) {
        d.copyAppended(plans[std::size_t(i)]);
    }

    // Primitive data (rare: plants carry none), one thread.
    for (const Impl::AppendPlan& p : plans) d.appendPrimitiveData(p);

    d.liveObjects += objects;
    d.liveVertices += vertices;
    d.liveIndices += indices;
    d.liveTriangles += indices / 3;
    std::vector<ObjectID> ids(objects);
    std::size_t k = 0;
    for (const Impl::AppendPlan& p : plans)
        for (std::size_t j = 0; j < p.objects.size(); ++j) ids[k++] = p.firstObject + ObjectID(j);
    return ids;
}

bool Context::doesObjectExist(ObjectID id) const {
    return id < impl_->objects.size() && impl_->objects[id].alive;
}

bool Context::doesPrimitiveExist(PrimitiveID id) const {
    return id < impl_->primitiveOwner.size() && impl_->primitiveOwner[id] != kNone;
}

std::vector<ObjectID> Context::objectIDs() const {
    std::vector<ObjectID> ids;
    ids.reserve(impl_->liveObjects);
    for (std::size_t i = 0; i < impl_->objects.size(); ++i)
        if (impl_->objects[i].alive) ids.push_back(static_cast<ObjectID>(i));
    return ids;
}

std::size_t Context::objectCount() const {
    return impl_->liveObjects;
}
std::size_t Context::triangleCount() const {
    return impl_->liveTriangles;
}
std::size_t Context::vertexCount() const {
    return impl_->liveVertices;
}
ObjectID Context::objectIDLimit() const {
    return static_cast<ObjectID>(impl_->objects.size());
}

void Context::skipObjectIDs(ObjectID limit) {
    if (limit >= kNone - 1) throw Error("object ID space exhausted");
    if (limit > impl_->objects.size()) impl_->objects.resize(limit);  // records not alive
}

ObjectView Context::object(ObjectID id) const {
    const Impl& d = *impl_;
    const ObjectRecord& r = d.record(id, "object");
    ObjectView v;
    v.id = id;
    v.positions = std::span<const vec3>(d.positions.data() + r.firstVertex, r.vertexCount);
    if (r.hasUVs) v.uvs = std::span<const vec2>(d.uvs.data() + r.firstVertex, r.vertexCount);
    v.indices = std::span<const std::uint32_t>(d.indices.data() + r.firstIndex, r.indexCount);
    v.material = r.material;
    v.primitives = {r.firstPrimitive, r.indexCount / 3};
    v.hidden = r.hidden;
    return v;
}

PrimitiveRange Context::objectPrimitives(ObjectID id) const {
    const ObjectRecord& r = impl_->record(id, "objectPrimitives");
    return {r.firstPrimitive, r.indexCount / 3};
}

MaterialID Context::objectMaterial(ObjectID id) const {
    return impl_->record(id, "objectMaterial").material;
}

ObjectID Context::primitiveObject(PrimitiveID id) const {
    if (!doesPrimitiveExist(id))
        throw Error("no such primitive", {.parameter = "primitiveID", .value = std::to_string(id)});
    return impl_->primitiveOwner[id];
}

std::array<vec3, 3> Context::primitiveVertices(PrimitiveID id) const {
    const ObjectRecord& r = impl_->objects[primitiveObject(id)];
    const std::uint32_t t = (id - r.firstPrimitive) * 3;
    const std::uint32_t* tri = impl_->indices.data() + r.firstIndex + t;
    const vec3* p = impl_->positions.data() + r.firstVertex;
    return {p[tri[0]], p[tri[1]], p[tri[2]]};
}

Mesh Context::objectMesh(ObjectID id) const {
    const ObjectView v = object(id);
    Mesh m;
    m.positions.assign(v.positions.begin(), v.positions.end());
    m.uvs.assign(v.uvs.begin(), v.uvs.end());
    m.indices.assign(v.indices.begin(), v.indices.end());
    return m;
}

AABB Context::objectBoundingBox(ObjectID id) const {
    AABB box;
    for (const vec3& p : object(id).positions) box.add(p);
    return box;
}

AABB Context::boundingBox(bool includeHidden) const {
    AABB box;
    for (const ObjectRecord& r : impl_->objects) {
        if (!r.alive || (r.hidden && !includeHidden)) continue;
        const vec3* p = impl_->positions.data() + r.firstVertex;
        for (std::uint32_t i = 0; i < r.vertexCount; ++i) box.add(p[i]);
    }
    return box;
}

double Context::objectArea(ObjectID id) const {
    const ObjectView v = object(id);
    double total = 0.0;
    for (std::size_t t = 0; t < v.indices.size(); t += 3) {
        const glm::dvec3 a(v.positions[v.indices[t]]), b(v.positions[v.indices[t + 1]]),
            c(v.positions[v.indices[t + 2]]);
        total += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return total;
}

// ---- object data -----------------------------------------------------------------------

void Context::setObjectData(ObjectID id, std::string_view label, DataValue value) {
    Impl& d = *impl_;
    d.record(id, "setObjectData");
    d.setValue(d.columnFor(label, typeOf(value)), id, value);
}

DataColumn Context::dataColumn(std::string_view label, DataType type) {
    const Column& col = impl_->columnFor(label, type);
    return DataColumn{col.index, col.type};
}

void Context::setObjectData(ObjectID id, DataColumn column, const DataValue& value) {
    Impl& d = *impl_;
    d.record(id, "setObjectData");
    if (column.index >= d.columnByIndex.size())
        throw Error("setObjectData: no such data column in this Context",
                    {.parameter = "column",
                     .value = std::to_string(column.index),
                     .validRange = "a column of this Context (Context::dataColumn)"});
    Column& col = *d.columnByIndex[column.index];
    if (col.type != typeOf(value))
        throw Error("object data column holds " + std::string(dataTypeName(col.type)) + " values",
                    {.parameter = "column",
                     .value = dataTypeName(typeOf(value)),
                     .validRange = dataTypeName(col.type)});
    d.setValue(col, id, value);
}

std::optional<DataValue> Context::objectData(ObjectID id, std::string_view label) const {
    const Impl& d = *impl_;
    d.record(id, "objectData");
    auto it = d.columns.find(label);
    if (it == d.columns.end()) return std::nullopt;
    const Column& col = it->second;
    if (id >= col.present.size() || !col.present[id]) return std::nullopt;
    // (made in place: GCC's sanitized builds see a moved-from variant as uninitialised)
    std::optional<DataValue> value;
    switch (col.type) {
        case DataType::Int:
            value.emplace(std::in_place_type<int>, col.ints[id]);
            break;
        case DataType::String:
            value.emplace(std::in_place_type<std::string>, d.strings[std::size_t(col.ints[id])]);
            break;
        case DataType::Float:
            value.emplace(std::in_place_type<float>, col.floats[id]);
            break;
        case DataType::Vec3:
            value.emplace(std::in_place_type<vec3>, col.vecs[id]);
            break;
    }
    return value;
}

bool Context::hasObjectData(ObjectID id, std::string_view label) const {
    return objectData(id, label).has_value();
}

void Context::clearObjectData(ObjectID id, std::string_view label) {
    impl_->record(id, "clearObjectData");
    auto it = impl_->columns.find(label);
    if (it != impl_->columns.end() && id < it->second.present.size()) it->second.present[id] = 0;
}

namespace {
template <class T>
std::optional<T> typedData(const Context& ctx, ObjectID id, std::string_view label, DataType want) {
    auto type = ctx.objectDataType(label);
    if (type && *type != want)
        throw Error(std::string("object data label holds ") + dataTypeName(*type) + " values",
                    {.parameter = std::string(label),
                     .value = dataTypeName(want),
                     .validRange = dataTypeName(*type)});
    auto v = ctx.objectData(id, label);
    if (!v) return std::nullopt;
    return std::get<T>(*v);
}
}  // namespace

std::optional<std::int32_t> Context::objectDataInt(ObjectID id, std::string_view label) const {
    return typedData<std::int32_t>(*this, id, label, DataType::Int);
}
std::optional<float> Context::objectDataFloat(ObjectID id, std::string_view label) const {
    return typedData<float>(*this, id, label, DataType::Float);
}
std::optional<std::string> Context::objectDataString(ObjectID id, std::string_view label) const {
    return typedData<std::string>(*this, id, label, DataType::String);
}
std::optional<vec3> Context::objectDataVec3(ObjectID id, std::string_view label) const {
    return typedData<vec3>(*this, id, label, DataType::Vec3);
}

std::vector<std::string> Context::objectDataLabels() const {
    std::vector<std::string> labels;
    for (const auto& [label, col] : impl_->columns) labels.push_back(label);
    return labels;
}

std::optional<DataType> Context::objectDataType(std::string_view label) const {
    auto it = impl_->columns.find(label);
    if (it == impl_->columns.end()) return std::nullopt;
    return it->second.type;
}

// ---- primitive data --------------------------------------------------------------------

void Context::setPrimitiveData(PrimitiveID id, std::string_view label, DataValue value) {
    primitiveObject(id);  // existence check with a clear error
    if (label.empty()) throw Error("data label must not be empty", {.parameter = "label"});
    auto it = impl_->primitiveColumns.find(label);
    if (it == impl_->primitiveColumns.end()) {
        it = impl_->primitiveColumns.emplace(std::string(label), PrimitiveColumn{}).first;
        it->second.type = typeOf(value);
    } else if (it->second.type != typeOf(value)) {
        throw Error(std::string("primitive data label already holds ") +
                        dataTypeName(it->second.type) + " values",
                    {.parameter = std::string(label),
                     .value = dataTypeName(typeOf(value)),
                     .validRange = dataTypeName(it->second.type)});
    }
    it->second.values[id] = std::move(value);
}

std::optional<DataValue> Context::primitiveData(PrimitiveID id, std::string_view label) const {
    primitiveObject(id);
    auto it = impl_->primitiveColumns.find(label);
    if (it == impl_->primitiveColumns.end()) return std::nullopt;
    auto v = it->second.values.find(id);
    if (v == it->second.values.end()) return std::nullopt;
    return v->second;
}

std::vector<std::string> Context::primitiveDataLabels() const {
    std::vector<std::string> labels;
    for (const auto& [label, col] : impl_->primitiveColumns) labels.push_back(label);
    return labels;
}

// ---- housekeeping ----------------------------------------------------------------------

void Context::clear(bool releaseMemory) {
    if (releaseMemory) {
        const std::size_t limit = impl_->triangleLimit;  // a setting, not content
        const unsigned nextPlant = impl_->nextPlantID;
        impl_ = std::make_unique<Impl>();
        impl_->triangleLimit = limit;
        impl_->nextPlantID = nextPlant;
        return;
    }
    Impl& d = *impl_;
    d.positions.clear();
    d.uvs.clear();
    d.uvsEnabled = false;
    d.indices.clear();
    d.objects.clear();
    d.primitiveOwner.clear();
    d.materials.resize(1);
    d.materials[0] = Material{};
    d.columns.clear();
    d.columnByIndex.clear();
    d.primitiveColumns.clear();
    d.strings.clear();
    d.stringIndex.clear();
    d.liveObjects = d.liveTriangles = d.liveVertices = d.liveIndices = 0;
}

void Context::reserve(std::size_t objects, std::size_t vertices, std::size_t triangles) {
    Impl& d = *impl_;
    d.objects.reserve(d.objects.size() + objects);
    d.positions.reserve(d.positions.size() + vertices);
    if (d.uvsEnabled) d.uvs.reserve(d.uvs.size() + vertices);
    d.indices.reserve(d.indices.size() + 3 * triangles);
    d.primitiveOwner.reserve(d.primitiveOwner.size() + triangles);
}

void Context::compact() {
    impl_->compact();
}

void Context::setTriangleLimit(std::size_t limit) {
    impl_->triangleLimit = limit;
}

std::size_t Context::triangleLimit() const {
    return impl_->triangleLimit;
}

unsigned Context::reservePlantIDs(unsigned count) {
    const unsigned first = impl_->nextPlantID;
    if (count > std::numeric_limits<unsigned>::max() - first)
        throw Error("plant IDs used up",
                    {.parameter = "count",
                     .value = std::to_string(count),
                     .validRange = "at most " +
                                   std::to_string(std::numeric_limits<unsigned>::max() - first)});
    impl_->nextPlantID = first + count;
    return first;
}

std::size_t Context::memoryBytes() const {
    const Impl& d = *impl_;
    std::size_t bytes = sizeof(Impl);
    bytes +=
        d.positions.capacity() * sizeof(vec3) + d.uvs.capacity() * sizeof(vec2) +
        d.indices.capacity() * sizeof(std::uint32_t) + d.objects.capacity() * sizeof(ObjectRecord) +
        d.primitiveOwner.capacity() * sizeof(ObjectID) + d.materials.capacity() * sizeof(Material);
    for (const auto& [label, col] : d.columns)
        bytes += label.capacity() + col.ints.capacity() * 4 + col.floats.capacity() * 4 +
                 col.vecs.capacity() * sizeof(vec3) + col.present.capacity();
    for (const auto& [label, col] : d.primitiveColumns)
        bytes += label.capacity() + col.values.size() * (sizeof(DataValue) + 32);
    for (const std::string& s : d.strings) bytes += s.capacity() + 48;
    return bytes;
}

}  // namespace plantarch
