// Geometry as numpy arrays without a second copy: the triangles of the chosen objects are
// gathered once into one C++ buffer, and every array is a view of it kept alive by a capsule
// that owns the buffer.

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

namespace {

// The gathered mesh. Triangle indices are global (into vertices). Arrays are left
// uninitialized when made, so that their pages are first touched by the threads that fill
// them.
struct MeshBuffer {
    template <class T>
    struct Array {
        std::unique_ptr<T[]> data;
        std::size_t size = 0;
        void make(std::size_t n) {
            data.reset(new T[n]);
            size = n;
        }
    };
    Array<float> vertices;           // N x 3
    Array<float> normals;            // N x 3 (empty without normals)
    Array<float> uvs;                // N x 2, 0 where an object has none (empty: no UVs)
    Array<std::uint32_t> triangles;  // M x 3
    Array<std::int32_t> plantID;     // M (-1: not a plant organ)
    Array<std::uint32_t> objectID;   // M
    Array<std::uint8_t> organ;       // M, index into plantarch.ORGAN_LABELS
};

std::uint8_t organCode(const std::optional<std::string>& organ) {
    if (!organ) return 0;  // unlabelled
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        if (*organ == kOrganLabels[i]) return std::uint8_t(i);
    if (*organ == "trellis") return std::uint8_t(9);  // obstacle
    return 0;
}

std::unique_ptr<MeshBuffer> gather(const Context& ctx, const std::vector<ObjectID>& ids,
                                   bool normals) {
    auto buf = std::make_unique<MeshBuffer>();
    // Where each object's vertices and triangles go.
    std::vector<std::size_t> firstVertex(ids.size() + 1, 0), firstTriangle(ids.size() + 1, 0);
    bool anyUVs = false;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectView o = ctx.object(ids[i]);
        firstVertex[i + 1] = firstVertex[i] + o.positions.size();
        firstTriangle[i + 1] = firstTriangle[i] + o.triangleCount();
        anyUVs = anyUVs || !o.uvs.empty();
    }
    const std::size_t nv = firstVertex.back(), nt = firstTriangle.back();
    buf->vertices.make(3 * nv);
    if (normals) buf->normals.make(3 * nv);
    if (anyUVs) buf->uvs.make(2 * nv);
    buf->triangles.make(3 * nt);
    buf->plantID.make(nt);
    buf->objectID.make(nt);
    buf->organ.make(nt);
    const bool hasPlant = ctx.objectDataType("plantID") == DataType::Int;
    const bool hasOrgan = ctx.objectDataType("organ") == DataType::String;
    const std::ptrdiff_t n = std::ptrdiff_t(ids.size());
    std::exception_ptr failure;
#pragma omp parallel
    {
        std::vector<vec3> smooth;
#pragma omp for schedule(dynamic, 64)
        for (std::ptrdiff_t i = 0; i < n; ++i) {
            try {
                const ObjectID id = ids[std::size_t(i)];
                const ObjectView o = ctx.object(id);
                const std::size_t v0 = firstVertex[std::size_t(i)],
                                  t0 = firstTriangle[std::size_t(i)];
                std::copy_n(&o.positions.data()->x, 3 * o.positions.size(),
                            &buf->vertices.data[3 * v0]);
                if (anyUVs) {
                    if (o.uvs.empty())
                        std::fill_n(&buf->uvs.data[2 * v0], 2 * o.positions.size(), 0.0f);
                    else
                        std::copy_n(&o.uvs.data()->x, 2 * o.uvs.size(), &buf->uvs.data[2 * v0]);
                }
                if (normals) {
                    smoothNormals(o, smooth);
                    std::copy_n(&smooth.data()->x, 3 * smooth.size(), &buf->normals.data[3 * v0]);
                }
                std::uint32_t* tri = &buf->triangles.data[3 * t0];
                for (std::size_t k = 0; k < o.indices.size(); ++k)
                    tri[k] = std::uint32_t(v0 + o.indices[k]);
                const std::size_t count = o.triangleCount();
                const std::int32_t plant =
                    hasPlant ? ctx.objectDataInt(id, "plantID").value_or(-1) : -1;
                const std::uint8_t organ =
                    hasOrgan ? organCode(ctx.objectDataString(id, "organ")) : 0;
                std::fill_n(&buf->plantID.data[t0], count, plant);
                std::fill_n(&buf->objectID.data[t0], count, id);
                std::fill_n(&buf->organ.data[t0], count, organ);
            } catch (...) {  // an exception must not leave the parallel region
#pragma omp critical(plantarch_mesh_arrays_error)
                if (!failure) failure = std::current_exception();
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
    return buf;
}

template <class T>
py::array view(MeshBuffer::Array<T>& a, std::size_t columns, py::handle owner) {
    if (columns == 0) return py::array_t<T>({a.size}, {sizeof(T)}, a.data.get(), owner);
    return py::array_t<T>({a.size / columns, columns}, {columns * sizeof(T), sizeof(T)},
                          a.data.get(), owner);
}

py::dict asArrays(std::unique_ptr<MeshBuffer> buf) {
    MeshBuffer* raw = buf.release();
    py::capsule owner(raw, [](void* p) { delete static_cast<MeshBuffer*>(p); });
    py::dict out;
    out["vertices"] = view(raw->vertices, 3, owner);
    out["triangles"] = view(raw->triangles, 3, owner);
    out["plant_id"] = view(raw->plantID, 0, owner);
    out["object_id"] = view(raw->objectID, 0, owner);
    out["organ"] = view(raw->organ, 0, owner);
    out["normals"] = raw->normals.data ? view(raw->normals, 3, owner) : py::object(py::none());
    out["uvs"] = raw->uvs.data ? view(raw->uvs, 2, owner) : py::object(py::none());
    return out;
}

const char* kMeshDoc =
    "as a dict of numpy arrays that view one C++ buffer (no second copy; the arrays keep it "
    "alive): vertices (N x 3 float32, m), triangles (M x 3 uint32 into vertices), plant_id (M "
    "int32, -1 for objects of no plant), object_id (M uint32), organ (M uint8, an index into "
    "plantarch.ORGAN_LABELS), normals (N x 3 float32, smooth per object; None with "
    "normals=False) and uvs (N x 2 float32, 0 where an object has none; None when no object "
    "has UVs).";

}  // namespace

void bindGeometry(py::module_& m) {
    py::list labels;
    for (std::string_view l : kOrganLabels) labels.append(py::str(std::string(l)));
    m.attr("ORGAN_LABELS") = py::tuple(labels);

    py::class_<Context> ctx = py::reinterpret_borrow<py::class_<Context>>(m.attr("Context"));
    ctx.def(
        "getMeshArrays",
        [](const Context& c, py::object objectIDs, bool includeHidden, bool normals) {
            std::vector<ObjectID> ids;
            if (objectIDs.is_none()) {
                for (ObjectID id : c.objectIDs())
                    if (includeHidden || !c.isObjectHidden(id)) ids.push_back(id);
            } else {
                ids = idList(objectIDs, "objectIDs");
                for (ObjectID id : ids)
                    if (!c.doesObjectExist(id))
                        throw Error("no such object",
                                    {.parameter = "objectIDs", .value = std::to_string(id)});
            }
            std::unique_ptr<MeshBuffer> buf;
            {
                py::gil_scoped_release release;
                buf = gather(c, ids, normals);
            }
            return asArrays(std::move(buf));
        },
        py::arg("objectIDs") = py::none(), py::arg("includeHidden") = false,
        py::arg("normals") = true,
        (std::string("The geometry of the given objects (all visible ones by default), ") +
         kMeshDoc)
            .c_str());

    py::class_<PlantArchitecture> arch =
        py::reinterpret_borrow<py::class_<PlantArchitecture>>(m.attr("PlantArchitecture"));
    arch.def(
        "getMeshArrays",
        [](PlantArchitecture& a, py::object plantIDs, bool normals) {
            const std::vector<unsigned> plants =
                plantIDs.is_none() ? a.getAllPlantIDs() : idList(plantIDs, "plantIDs");
            std::vector<ObjectID> ids;
            for (unsigned p : plants) {
                const std::vector<ObjectID> own = a.getAllPlantObjectIDs(p);
                ids.insert(ids.end(), own.begin(), own.end());
            }
            std::sort(ids.begin(), ids.end());
            std::vector<ObjectID> shown;
            for (ObjectID id : ids)
                if (!a.context().isObjectHidden(id)) shown.push_back(id);
            std::unique_ptr<MeshBuffer> buf;
            {
                py::gil_scoped_release release;
                buf = gather(a.context(), shown, normals);
            }
            return asArrays(std::move(buf));
        },
        py::arg("plantIDs") = py::none(), py::arg("normals") = true,
        (std::string("The geometry of a plant (an ID), some plants (a list) or all of them "
                     "(None), ") +
         kMeshDoc)
            .c_str());
}

}  // namespace plantarch::python
