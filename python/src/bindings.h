#pragma once
// Shared pieces of the Python module: conversions of the library's small value types and the
// functions that bind each part of the library (one file per part).

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Mesh.h"

namespace py = pybind11;

namespace plantarch::python {

/// A docstring: the C++ declaration's comment (docs::..., generated from the public headers),
/// then what differs in Python (its argument forms, its return values). The text lives as long
/// as the module.
const char* inPython(const char* cpp, const char* python);

/// A value as Python shows it (its repr), for messages; "?" when its repr raises.
std::string shown(py::handle value);

/// Whether a value is a number a field takes: an int or float (a numpy one too), not a bool.
bool isNumber(py::handle v);

/// A vec3 from any sequence of three numbers (plantarch.vec3, tuple, list, numpy array).
/// Throws plantarch::Error naming `what` otherwise.
vec3 toVec3(py::handle value, const char* what);
/// A vec2 from any sequence of two numbers.
vec2 toVec2(py::handle value, const char* what);
/// IDs from one whole number or a sequence of them; anything else, or a number no ID can be
/// (negative, past 2^32 - 1), throws plantarch::Error naming `what`.
std::vector<unsigned> idList(py::handle value, const char* what);

/// `with T(...) as x:` for a bound class: __enter__ gives the object itself and __exit__ lets
/// the block's exception through; the object stays usable after the block and is freed with
/// its last reference. `what` names it in the help ("the Context").
template <class T>
void bindWithBlock(py::class_<T>& cls, const std::string& what) {
    cls.def(
           "__enter__", [](T& self) -> T& { return self; }, py::return_value_policy::reference,
           ("`with` gives " + what + " itself.").c_str())
        .def(
            "__exit__", [](T&, const py::args&) { return false; },
            ("Ends a with block and lets its exception through; " + what +
             " stays usable and is freed when its last reference goes.")
                .c_str());
}

void bindValues(py::module_& m);        // values.cpp: vec3, vec2, AxisRotation, errors
void bindParameters(py::module_& m);    // parameters.cpp: the parameter table's structs
void bindState(py::module_& m);         // state.cpp: plant state (shoots, phytomers, organs)
void bindContext(py::module_& m);       // context.cpp: Context, Mesh, Material
void bindGeometry(py::module_& m);      // geometry.cpp: numpy views of the mesh
void bindArchitecture(py::module_& m);  // architecture.cpp: PlantArchitecture
void bindLight(py::module_& m);         // light.cpp: weather, sun, light model, photosynthesis
void bindPhysiology(py::module_& m);    // physiology.cpp: carbon and nitrogen
void bindSkeleton(py::module_& m);      // skeleton.cpp: measured plants, skeletons, MTG
void bindLeafAngles(py::module_& m);    // leaf_angles.cpp: leaf inclination histograms
void bindBending(py::module_& m);       // bending.cpp: shoots bending under load
void bindCalibration(py::module_& m);   // calibration.cpp: fitting species to measurements
void bindOutput(py::module_& m);        // output.cpp: exporters, renderer, species files
void bindField(py::module_& m);         // field.cpp: fields built in tiles
void bindDataset(py::module_& m);       // dataset.cpp: synthetic datasets

}  // namespace plantarch::python

namespace pybind11::detail {

/// glm vectors cross as plantarch.vec3 / vec2 objects and are read from any sequence of
/// numbers of the right length.
template <>
struct type_caster<glm::vec3> {
    PYBIND11_TYPE_CASTER(glm::vec3, const_name("vec3"));
    bool load(handle src, bool);
    static handle cast(const glm::vec3& v, return_value_policy, handle);
};
template <>
struct type_caster<glm::vec2> {
    PYBIND11_TYPE_CASTER(glm::vec2, const_name("vec2"));
    bool load(handle src, bool);
    static handle cast(const glm::vec2& v, return_value_policy, handle);
};

}  // namespace pybind11::detail
