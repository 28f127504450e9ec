// Context (the geometry database), Mesh and Material.

#include <cstring>
#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"

namespace plantarch::python {

namespace {

using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IndexRows = py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>;

template <class V, int N>
std::vector<V> rowsOf(const FloatRows& a, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != N)
        throw Error("wrong array shape", {.parameter = what,
                                          .value = std::to_string(a.ndim()) + "-d array",
                                          .validRange = "an n x " + std::to_string(N) + " array"});
    std::vector<V> out(std::size_t(a.shape(0)));
    if (!out.empty()) std::memcpy(out.data(), a.data(), out.size() * sizeof(V));
    return out;
}

Mesh meshFrom(const FloatRows& positions, const IndexRows& triangles, py::object uvs) {
    Mesh mesh;
    mesh.positions = rowsOf<vec3, 3>(positions, "positions");
    if (triangles.ndim() != 2 || triangles.shape(1) != 3)
        throw Error("wrong array shape",
                    {.parameter = "triangles", .validRange = "an m x 3 array"});
    mesh.indices.assign(triangles.data(), triangles.data() + triangles.size());
    if (!uvs.is_none()) mesh.uvs = rowsOf<vec2, 2>(uvs.cast<FloatRows>(), "uvs");
    mesh.validate();
    return mesh;
}

py::array_t<float> floatRows(const float* data, std::size_t rows, std::size_t columns) {
    py::array_t<float> out({rows, columns});
    if (rows) std::memcpy(out.mutable_data(), data, rows * columns * sizeof(float));
    return out;
}

py::object dataValue(const std::optional<DataValue>& v) {
    if (!v) return py::none();
    return std::visit([](const auto& x) -> py::object { return py::cast(x); }, *v);
}

DataValue toDataValue(py::handle v) {
    if (py::isinstance<py::bool_>(v)) return std::int32_t(v.cast<bool>());
    if (py::isinstance<py::int_>(v)) return v.cast<std::int32_t>();
    if (py::isinstance<py::float_>(v)) return v.cast<float>();
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    return toVec3(v, "value");
}

}  // namespace

void bindContext(py::module_& m) {
    py::class_<Material>(m, "Material", "Surface appearance: RGB colour, optional texture.")
        .def(py::init<>())
        .def(py::init([](vec3 color, std::string texture, std::string name) {
                 return Material{color, std::move(texture), std::move(name)};
             }),
             py::arg("color"), py::arg("texture") = "", py::arg("name") = "")
        .def_readwrite("color", &Material::color, "RGB, 0 to 1")
        .def_readwrite("texture", &Material::texture, "image file path; empty for a colour")
        .def_readwrite("name", &Material::name, "name used by exporters (generated when empty)")
        .def("__eq__", [](const Material& a, const Material& b) { return a == b; });

    py::class_<Mesh>(m, "Mesh", "An indexed triangle mesh (arrays are copies).")
        .def(py::init<>())
        .def(py::init(&meshFrom), py::arg("positions"), py::arg("triangles"),
             py::arg("uvs") = py::none(),
             "From an n x 3 array of positions, an m x 3 array of vertex indices and optional "
             "n x 2 UVs (validated).")
        .def_property_readonly(
            "positions",
            [](const Mesh& mesh) {
                return floatRows(&mesh.positions.data()->x, mesh.positions.size(), 3);
            },
            "n x 3 float32 positions (a copy)")
        .def_property_readonly(
            "uvs",
            [](const Mesh& mesh) { return floatRows(&mesh.uvs.data()->x, mesh.uvs.size(), 2); },
            "n x 2 float32 UVs (a copy; empty without UVs)")
        .def_property_readonly(
            "triangles",
            [](const Mesh& mesh) {
                py::array_t<std::uint32_t> out({mesh.indices.size() / 3, std::size_t(3)});
                if (!mesh.indices.empty())
                    std::memcpy(out.mutable_data(), mesh.indices.data(), mesh.indices.size() * 4);
                return out;
            },
            "m x 3 uint32 vertex indices (a copy)")
        .def("triangleCount", &Mesh::triangleCount, "Triangles of the mesh.")
        .def("vertexCount", &Mesh::vertexCount, "Vertices of the mesh.")
        .def("area", &Mesh::area, "Sum of triangle areas, m^2.");

    py::class_<Context> context(
        m, "Context",
        "The geometry database: objects (one per organ), each a triangle mesh with a material "
        "and labelled data (plantID, organ, shootID, rank, age, leafID ...).");
    bindWithBlock(context, "the Context");
    context.def(py::init<>())
        .def("addMaterial", &Context::addMaterial, py::arg("material"), docs::Context_addMaterial)
        .def(
            "addObject",
            [](Context& c, const FloatRows& positions, const IndexRows& triangles, py::object uvs,
               std::optional<Material> material) {
                const Mesh mesh = meshFrom(positions, triangles, uvs);
                return material ? c.addObject(mesh, *material) : c.addObject(mesh);
            },
            py::arg("positions"), py::arg("triangles"), py::arg("uvs") = py::none(),
            py::arg("material") = py::none(),
            inPython(docs::Context_addObject,
                     "Adds an object (e.g. an obstacle) from numpy arrays; returns its ID."))
        .def("copyObject", &Context::copyObject, py::arg("objectID"), docs::Context_copyObject)
        .def("deleteObject", &Context::deleteObject, py::arg("objectID"),
             docs::Context_deleteObject)
        .def("setObjectHidden", &Context::setObjectHidden, py::arg("objectID"), py::arg("hidden"),
             "Hides or shows an object (exporters and the renderer leave hidden ones out).")
        .def("isObjectHidden", &Context::isObjectHidden, py::arg("objectID"),
             "Whether the object is hidden.")
        .def("doesObjectExist", &Context::doesObjectExist, py::arg("objectID"),
             "Whether an object of that ID is alive.")
        .def("getAllObjectIDs", &Context::objectIDs, "Live objects, in increasing ID order.")
        .def("getObjectCount", &Context::objectCount, "Live objects (the same as objectCount).")
        .def("getTriangleCount", &Context::triangleCount,
             "Triangles of the live objects (the same as triangleCount).")
        .def("getVertexCount", &Context::vertexCount,
             "Vertices of the live objects (the same as vertexCount).")
        .def("getObjectMesh", &Context::objectMesh, py::arg("objectID"), "A copy of its mesh.")
        .def(
            "getObjectMaterial",
            [](const Context& c, ObjectID id) { return c.material(c.objectMaterial(id)); },
            py::arg("objectID"), "The object's Material.")
        .def("getObjectArea", &Context::objectArea, py::arg("objectID"), "m^2")
        .def(
            "getObjectBoundingBox",
            [](const Context& c, ObjectID id) {
                const AABB b = c.objectBoundingBox(id);
                return py::make_tuple(py::cast(b.min), py::cast(b.max));
            },
            py::arg("objectID"), "(min, max) corners.")
        .def(
            "getBoundingBox",
            [](const Context& c, bool includeHidden) {
                const AABB b = c.boundingBox(includeHidden);
                if (b.empty()) return py::object(py::none());
                return py::object(py::make_tuple(py::cast(b.min), py::cast(b.max)));
            },
            py::arg("includeHidden") = false, "(min, max) of every object; None when empty.")
        .def(
            "transformObject",
            [](Context& c, ObjectID id, const FloatRows& matrix) {
                if (matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4)
                    throw Error("wrong array shape",
                                {.parameter = "transform", .validRange = "a 4 x 4 array"});
                mat4 t;
                for (int r = 0; r < 4; ++r)
                    for (int k = 0; k < 4; ++k) t[k][r] = matrix.at(r, k);  // row-major in
                c.transformObject(id, t);
            },
            py::arg("objectID"), py::arg("transform"), docs::Context_transformObject)
        .def(
            "getObjectData",
            [](const Context& c, ObjectID id, const std::string& label) {
                return dataValue(c.objectData(id, label));
            },
            py::arg("objectID"), py::arg("label"), "The value, or None when unset.")
        .def(
            "setObjectData",
            [](Context& c, ObjectID id, const std::string& label, py::handle value) {
                c.setObjectData(id, label, toDataValue(value));
            },
            py::arg("objectID"), py::arg("label"), py::arg("value"),
            inPython(docs::Context_setObjectData,
                     "Sets int, float, text or vec3 data (a label keeps one type)."))
        .def("listObjectDataLabels", &Context::objectDataLabels,
             "Labels used by any object, sorted (the same as objectDataLabels).")
        .def("clear", &Context::clear, py::arg("release_memory") = true, docs::Context_clear)
        .def("memoryBytes", &Context::memoryBytes, docs::Context_memoryBytes)
        .def("setTriangleLimit", &Context::setTriangleLimit, py::arg("limit"),
             docs::Context_setTriangleLimit)
        .def("triangleLimit", &Context::triangleLimit, "The triangle limit (0: none).")
        // The C++ names (the get... names above are those the specification's users know).
        .def("objectIDs", &Context::objectIDs, docs::Context_objectIDs)
        .def("objectCount", &Context::objectCount, "Live objects.")
        .def("triangleCount", &Context::triangleCount, "Triangles of the live objects.")
        .def("vertexCount", &Context::vertexCount, "Vertices of the live objects.")
        .def("objectIDLimit", &Context::objectIDLimit, docs::Context_objectIDLimit)
        .def("objectMesh", &Context::objectMesh, py::arg("objectID"), docs::Context_objectMesh)
        .def("setObjectMesh", py::overload_cast<ObjectID, const Mesh&>(&Context::setObjectMesh),
             py::arg("objectID"), py::arg("mesh"), docs::Context_setObjectMesh)
        .def("objectArea", &Context::objectArea, py::arg("objectID"), "m^2")
        .def("material", &Context::material, py::arg("materialID"), "A material by ID.")
        .def("materialCount", &Context::materialCount, "Materials in the Context.")
        .def("objectMaterial", &Context::objectMaterial, py::arg("objectID"),
             "The object's material ID.")
        .def("setObjectMaterial", &Context::setObjectMaterial, py::arg("objectID"),
             py::arg("materialID"), "Gives the object another material (by ID).")
        .def(
            "deleteObjects", [](Context& c, std::vector<ObjectID> ids) { c.deleteObjects(ids); },
            py::arg("objectIDs"), "Removes several objects.")
        .def("hasObjectData", &Context::hasObjectData, py::arg("objectID"), py::arg("label"),
             "Whether the object has data under that label.")
        .def("clearObjectData", &Context::clearObjectData, py::arg("objectID"), py::arg("label"),
             "Removes the object's data under that label.")
        .def(
            "objectData",
            [](const Context& c, ObjectID id, const std::string& label) {
                return dataValue(c.objectData(id, label));
            },
            py::arg("objectID"), py::arg("label"), "The value, or None when unset.")
        .def("objectDataLabels", &Context::objectDataLabels, docs::Context_objectDataLabels)
        .def(
            "objectDataType",
            [](const Context& c, const std::string& label) -> py::object {
                const auto t = c.objectDataType(label);
                return t ? py::object(py::str(dataTypeName(*t))) : py::object(py::none());
            },
            py::arg("label"), "'int', 'float', 'string' or 'vec3'; None when never used.")
        .def(
            "objectPrimitives",
            [](const Context& c, ObjectID id) {
                const PrimitiveRange r = c.objectPrimitives(id);
                return py::make_tuple(r.first, r.count);
            },
            py::arg("objectID"), "(first primitive ID, count) of the object's triangles.")
        .def("primitiveObject", &Context::primitiveObject, py::arg("primitiveID"),
             docs::Context_primitiveObject)
        .def("doesPrimitiveExist", &Context::doesPrimitiveExist, py::arg("primitiveID"),
             "Whether a triangle of that ID is alive.")
        .def(
            "primitiveVertices",
            [](const Context& c, PrimitiveID id) {
                const auto v = c.primitiveVertices(id);
                return py::make_tuple(py::cast(v[0]), py::cast(v[1]), py::cast(v[2]));
            },
            py::arg("primitiveID"), docs::Context_primitiveVertices)
        .def(
            "setPrimitiveData",
            [](Context& c, PrimitiveID id, const std::string& label, py::handle value) {
                c.setPrimitiveData(id, label, toDataValue(value));
            },
            py::arg("primitiveID"), py::arg("label"), py::arg("value"),
            "Sets data on one triangle (int, float, text or vec3).")
        .def(
            "primitiveData",
            [](const Context& c, PrimitiveID id, const std::string& label) {
                return dataValue(c.primitiveData(id, label));
            },
            py::arg("primitiveID"), py::arg("label"), "A triangle's data, or None when unset.")
        .def("primitiveDataLabels", &Context::primitiveDataLabels,
             "Labels used by any triangle, sorted.")
        .def("compact", &Context::compact, docs::Context_compact);
}

}  // namespace plantarch::python
