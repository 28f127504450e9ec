#pragma once
// plantarch::Context: the geometry database shared by the user and the plant model.
//
// Geometry is stored as objects (one per organ: a leaf, an internode tube, a fruit...),
// each an indexed triangle mesh with a material and labelled data. Storage is a handful of
// contiguous pools (positions, UVs, indices, per-triangle object index), never one heap
// object per triangle.
//
// IDs. Object IDs and primitive (triangle) IDs are never reused. The triangles of an object
// have consecutive primitive IDs starting at objectPrimitives(id).first. Replacing an
// object's mesh keeps its object ID; it also keeps its primitive IDs when the new mesh has
// the same triangle count (the usual case for a growing organ), otherwise the object gets a
// fresh run of primitive IDs and the old ones cease to exist.
//
// Data. Objects and primitives carry values by label: int, float, string or vec3. A label
// has one type for all objects; setting a value of another type is an error.
//
// Threads. const methods may be called concurrently; mutating methods may not.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch {

using ObjectID = std::uint32_t;
using PrimitiveID = std::uint32_t;
using MaterialID = std::uint32_t;

enum class DataType { Int, Float, String, Vec3 };
using DataValue = std::variant<std::int32_t, float, std::string, vec3>;
const char* dataTypeName(DataType type);

/// A run of consecutive primitive IDs.
struct PrimitiveRange {
    PrimitiveID first = 0;
    std::uint32_t count = 0;
    PrimitiveID end() const { return first + count; }
};

/// Read-only view of one object's geometry. The spans stay valid until the next mutating
/// call on the Context.
struct ObjectView {
    ObjectID id = 0;
    std::span<const vec3> positions;
    std::span<const vec2> uvs;               ///< empty when the object has no UVs
    std::span<const std::uint32_t> indices;  ///< into positions (object-local)
    MaterialID material = 0;
    PrimitiveRange primitives;
    bool hidden = false;

    std::size_t triangleCount() const { return indices.size() / 3; }
};

class Context;

/// An object-data label looked up once (Context::dataColumn), for setting it on many objects
/// without finding the label by name each time. Valid in the Context that made it and in
/// copies of that Context, until clear().
struct DataColumn {
    std::uint32_t index = 0;
    DataType type = DataType::Int;
};

/// Objects of one Context to copy with Context::appendObjects.
struct ObjectSource {
    const Context* context = nullptr;
    std::span<const ObjectID> objects;  ///< live objects of *context, copied in this order
};

class Context {
public:
    Context();
    ~Context();
    Context(const Context&);
    Context& operator=(const Context&);
    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;

    // ---- materials -----------------------------------------------------------------
    /// Adds a material, or returns the ID of an equal one already present.
    MaterialID addMaterial(const Material& material);
    const Material& material(MaterialID id) const;
    std::size_t materialCount() const;

    // ---- objects -------------------------------------------------------------------
    /// Adds an object made of `mesh` (validated) with the given material.
    ObjectID addObject(const Mesh& mesh, MaterialID material = 0);
    ObjectID addObject(const Mesh& mesh, const Material& material);
    /// Adds an object from raw arrays (uvs may be empty).
    ObjectID addObject(std::span<const vec3> positions, std::span<const vec2> uvs,
                       std::span<const std::uint32_t> indices, MaterialID material = 0);
    /// Adds `mesh` placed by `transform` (its positions transformed as points), checked as
    /// addObject(mesh) checks a mesh, without copying the mesh first.
    ObjectID addObject(const Mesh& mesh, const mat4& transform, MaterialID material = 0);
    /// Replaces the object's geometry, keeping its ID, material and data.
    void setObjectMesh(ObjectID id, const Mesh& mesh);
    /// Replaces the object's geometry with `mesh` placed by `transform`.
    void setObjectMesh(ObjectID id, const Mesh& mesh, const mat4& transform);
    void setObjectMaterial(ObjectID id, MaterialID material);
    /// A new object with the same geometry, material and object data.
    ObjectID copyObject(ObjectID id);
    /// Applies `transform` to the object's positions.
    void transformObject(ObjectID id, const mat4& transform);
    void setObjectHidden(ObjectID id, bool hidden);
    bool isObjectHidden(ObjectID id) const;
    /// Removes the object, its primitives and their data. Unknown IDs are an error.
    void deleteObject(ObjectID id);
    void deleteObjects(std::span<const ObjectID> ids);
    /// Copies objects of other Contexts in one step: each object gets the next object ID, in
    /// order (the sources in turn, each source's objects in the order given), with its
    /// geometry, material (added here unless an equal one is present), hidden flag, object
    /// data and primitive data. The geometry is not validated again (the source Context did
    /// that), the pools grow once, and the copy runs on all threads, with the same result
    /// for any thread count. All or nothing: an unknown object, a source that is this
    /// Context, or a label holding another type here throws before anything is added.
    /// Returns the new IDs in the order of the copied objects.
    std::vector<ObjectID> appendObjects(std::span<const ObjectSource> sources);

    bool doesObjectExist(ObjectID id) const;
    bool doesPrimitiveExist(PrimitiveID id) const;
    /// Live objects, in increasing ID order.
    std::vector<ObjectID> objectIDs() const;
    std::size_t objectCount() const;
    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
    /// One past the largest object ID ever issued (for sizing lookup tables).
    ObjectID objectIDLimit() const;
    /// Moves objectIDLimit() up to `limit` (nothing when it is there already) as if objects
    /// with the IDs below it had been added and deleted, so that the next object added gets
    /// ID `limit` (a file's recorded IDs kept on reading). Throws Error when `limit` is
    /// beyond the ID space.
    void skipObjectIDs(ObjectID limit);

    ObjectView object(ObjectID id) const;
    PrimitiveRange objectPrimitives(ObjectID id) const;
    MaterialID objectMaterial(ObjectID id) const;
    /// The object a primitive belongs to.
    ObjectID primitiveObject(PrimitiveID id) const;
    /// The three corners of a primitive, in world coordinates.
    std::array<vec3, 3> primitiveVertices(PrimitiveID id) const;
    /// Copy of the object's mesh.
    Mesh objectMesh(ObjectID id) const;

    AABB objectBoundingBox(ObjectID id) const;
    /// Box around every live object (hidden ones too when includeHidden).
    AABB boundingBox(bool includeHidden = false) const;
    double objectArea(ObjectID id) const;

    /// Calls f(const ObjectView&) for every live object in ID order.
    template <class F>
    void forEachObject(F&& f) const {
        for (ObjectID id = 0; id < objectIDLimit(); ++id)
            if (doesObjectExist(id)) f(object(id));
    }

    // ---- labelled data -------------------------------------------------------------
    void setObjectData(ObjectID id, std::string_view label, DataValue value);
    /// The column of `label`, made for `type` values if the label is new (an Error when it
    /// holds another type). A new label is listed by objectDataLabels() from then on.
    DataColumn dataColumn(std::string_view label, DataType type);
    /// As setObjectData by label; the value must have the column's type.
    void setObjectData(ObjectID id, DataColumn column, const DataValue& value);
    std::optional<DataValue> objectData(ObjectID id, std::string_view label) const;
    bool hasObjectData(ObjectID id, std::string_view label) const;
    void clearObjectData(ObjectID id, std::string_view label);
    /// Typed getters: nullopt when unset; an Error when the label has another type.
    std::optional<std::int32_t> objectDataInt(ObjectID id, std::string_view label) const;
    std::optional<float> objectDataFloat(ObjectID id, std::string_view label) const;
    std::optional<std::string> objectDataString(ObjectID id, std::string_view label) const;
    std::optional<vec3> objectDataVec3(ObjectID id, std::string_view label) const;
    /// Labels used by any object, sorted; and the type of one (nullopt if never used).
    std::vector<std::string> objectDataLabels() const;
    std::optional<DataType> objectDataType(std::string_view label) const;

    void setPrimitiveData(PrimitiveID id, std::string_view label, DataValue value);
    std::optional<DataValue> primitiveData(PrimitiveID id, std::string_view label) const;
    std::vector<std::string> primitiveDataLabels() const;

    // ---- housekeeping --------------------------------------------------------------
    /// Removes every object and material (IDs restart at 0). With releaseMemory false the
    /// pools keep their capacity, for a Context filled again with as much.
    void clear(bool releaseMemory = true);
    /// Makes room for this many more objects, vertices and triangles, so that adding them
    /// grows no pool (a hint: adding more is fine).
    void reserve(std::size_t objects, std::size_t vertices, std::size_t triangles);
    /// Packs the pools after deletions. Called automatically when over half is unused;
    /// never changes IDs.
    void compact();
    /// At most this many live triangles (0, the default: no limit). Adding geometry past it
    /// throws TriangleBudgetError and changes nothing, so a job too large for the machine
    /// stops with a message instead of running out of memory. Lowering it below the triangles
    /// already held is allowed (later additions throw).
    void setTriangleLimit(std::size_t limit);
    std::size_t triangleLimit() const;
    /// Reserves `count` consecutive plant IDs and returns the first. Every PlantArchitecture
    /// on this Context takes its plants' IDs here, so an ID (and the plant_ID label of its
    /// objects) names one plant in the whole scene; IDs are never handed out twice, not even
    /// after clear() or the plant's deletion.
    unsigned reservePlantIDs(unsigned count);

    /// Bytes held by the Context's storage (capacity, not just size).
    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace plantarch
