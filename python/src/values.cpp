// Small value types (vec3, vec2, AxisRotation) and the translation of plantarch::Error.

#include <climits>
#include <cmath>
#include <deque>
#include <string>

#include "bindings.h"
#include "plantarch/PlantState.h"

namespace plantarch::python {

namespace {

// The named tuples plantarch/__init__.py defines (looked up once, on first use).
py::object pythonType(const char* name) {
    return py::module_::import("plantarch").attr(name);
}

// The type, looked up on first use. Not a function-local static: its initialisation would hold
// a C++ lock across the import, which can let another thread run, and that thread would wait
// for the lock with the GIL held (a deadlock). Under the GIL the worst race imports twice.
py::object* vec3Type = nullptr;
py::object* vec2Type = nullptr;

py::handle cachedType(py::object*& slot, const char* name) {
    if (!slot) {
        py::object type = pythonType(name);
        if (!slot) slot = new py::object(std::move(type));
    }
    return *slot;
}

template <int N>
bool readNumbers(py::handle value, float (&out)[N]) {
    if (!value || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
        !PySequence_Check(value.ptr()))
        return false;
    const Py_ssize_t n = PySequence_Size(value.ptr());
    if (n != N) {
        PyErr_Clear();
        return false;
    }
    for (int i = 0; i < N; ++i) {
        py::object item = py::reinterpret_steal<py::object>(PySequence_GetItem(value.ptr(), i));
        if (!item) {
            PyErr_Clear();
            return false;
        }
        const double d = PyFloat_AsDouble(item.ptr());
        if (d == -1.0 && PyErr_Occurred()) {
            PyErr_Clear();
            return false;
        }
        out[i] = float(d);
    }
    return true;
}

}  // namespace

const char* inPython(const char* cpp, const char* python) {
    static std::deque<std::string> texts;  // filled while the module is made, then read only
    return texts.emplace_back(std::string(cpp) + "\n\nIn Python: " + python).c_str();
}

std::string shown(py::handle value) {
    try {
        return py::repr(value).cast<std::string>();
    } catch (const py::error_already_set&) {
        return "?";
    }
}

bool isNumber(py::handle v) {
    return !py::isinstance<py::bool_>(v) &&
           (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v) ||
            (PyNumber_Check(v.ptr()) && py::hasattr(v, "__float__")));
}

vec3 toVec3(py::handle value, const char* what) {
    float v[3];
    if (!readNumbers(value, v))
        throw Error("not three numbers",
                    {.parameter = what, .value = shown(value), .validRange = "vec3(x, y, z)"});
    return {v[0], v[1], v[2]};
}

vec2 toVec2(py::handle value, const char* what) {
    float v[2];
    if (!readNumbers(value, v))
        throw Error("not two numbers",
                    {.parameter = what, .value = shown(value), .validRange = "vec2(x, y)"});
    return {v[0], v[1]};
}

std::vector<unsigned> idList(py::handle value, const char* what) {
    auto one = [&](py::handle v) {
        if (PyLong_Check(v.ptr()) && !PyBool_Check(v.ptr())) {
            int overflow = 0;
            const long long x = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
            if (overflow == 0 && x >= 0 && x <= (long long)UINT_MAX) return unsigned(x);
        }
        throw Error("not an ID", {.parameter = what,
                                  .value = shown(v),
                                  .validRange = "a whole number from 0 to 4294967295"});
    };
    if (PyLong_Check(value.ptr())) return {one(value)};
    if (py::isinstance<py::str>(value) || !PySequence_Check(value.ptr()))
        throw Error("not an ID or a list of IDs", {.parameter = what, .value = shown(value)});
    std::vector<unsigned> out;
    for (py::handle v : value) out.push_back(one(v));
    return out;
}

void bindValues(py::module_& m) {
    // plantarch::Error becomes plantarch.Error, a ValueError carrying the same one line and
    // its parts (file, line, parameter, value, valid_range).
    static py::exception<Error>& error = *new py::exception<Error>(m, "Error", PyExc_ValueError);
    error.doc() =
        "Bad input or failed I/O, with one line naming the file, line, parameter, value and "
        "valid range. Attributes: file, line, parameter, value, valid_range.";
    // TriangleBudgetError, a plantarch.Error with the estimate and the limit.
    static py::exception<TriangleBudgetError>& budget =
        *new py::exception<TriangleBudgetError>(m, "TriangleBudgetError", error.ptr());
    budget.doc() =
        "A job that needs more triangles than the triangle limit (setTriangleLimit) allows, "
        "refused before it starts or stopped as it passes the limit; its estimate and limit "
        "count triangles. Attributes: file, line, parameter, value, valid_range, estimate, "
        "limit.";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const TriangleBudgetError& e) {
            py::object instance = py::handle(budget.ptr())(py::str(e.what()));
            instance.attr("file") = e.file();
            instance.attr("line") = e.line();
            instance.attr("parameter") = e.parameter();
            instance.attr("value") = e.value();
            instance.attr("valid_range") = e.validRange();
            instance.attr("estimate") = e.estimate();
            instance.attr("limit") = e.limit();
            PyErr_SetObject(budget.ptr(), instance.ptr());
        } catch (const Error& e) {
            py::object instance = py::handle(error.ptr())(py::str(e.what()));
            instance.attr("file") = e.file();
            instance.attr("line") = e.line();
            instance.attr("parameter") = e.parameter();
            instance.attr("value") = e.value();
            instance.attr("valid_range") = e.validRange();
            PyErr_SetObject(error.ptr(), instance.ptr());
        }
    });

    py::class_<AxisRotation>(m, "AxisRotation",
                             "A rotation as pitch, yaw and roll, degrees (the specification's "
                             "make_AxisRotation).")
        .def(py::init<>())
        .def(py::init([](float pitch, float yaw, float roll) {
                 return AxisRotation{pitch, yaw, roll};
             }),
             py::arg("pitch"), py::arg("yaw"), py::arg("roll"))
        .def_readwrite("pitch", &AxisRotation::pitch, "degrees")
        .def_readwrite("yaw", &AxisRotation::yaw, "degrees")
        .def_readwrite("roll", &AxisRotation::roll, "degrees")
        .def("__repr__",
             [](const AxisRotation& r) {
                 return "AxisRotation(pitch=" + py::repr(py::float_(r.pitch)).cast<std::string>() +
                        ", yaw=" + py::repr(py::float_(r.yaw)).cast<std::string>() +
                        ", roll=" + py::repr(py::float_(r.roll)).cast<std::string>() + ")";
             })
        .def("__eq__", [](const AxisRotation& a, const AxisRotation& b) {
            return a.pitch == b.pitch && a.yaw == b.yaw && a.roll == b.roll;
        });
    m.def(
        "make_AxisRotation",
        [](float pitch, float yaw, float roll) {
            return AxisRotation{pitch, yaw, roll};
        },
        py::arg("pitch"), py::arg("yaw"), py::arg("roll"),
        "An AxisRotation from pitch, yaw and roll in degrees.");
}

}  // namespace plantarch::python

namespace pybind11::detail {

bool type_caster<glm::vec3>::load(handle src, bool) {
    float v[3];
    if (!plantarch::python::readNumbers(src, v)) return false;
    value = glm::vec3(v[0], v[1], v[2]);
    return true;
}

handle type_caster<glm::vec3>::cast(const glm::vec3& v, return_value_policy, handle) {
    return plantarch::python::cachedType(plantarch::python::vec3Type, "vec3")(v.x, v.y, v.z)
        .release();
}

bool type_caster<glm::vec2>::load(handle src, bool) {
    float v[2];
    if (!plantarch::python::readNumbers(src, v)) return false;
    value = glm::vec2(v[0], v[1]);
    return true;
}

handle type_caster<glm::vec2>::cast(const glm::vec2& v, return_value_policy, handle) {
    return plantarch::python::cachedType(plantarch::python::vec2Type, "vec2")(v.x, v.y).release();
}

}  // namespace pybind11::detail
