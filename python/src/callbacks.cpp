// Python functions called from C++ (see callbacks.h).

#include "callbacks.h"

#include <string_view>
#include <thread>

namespace plantarch::python {

namespace {

std::thread::id mainThread;

// A Python object that is released with the GIL held, whichever thread drops it last.
std::shared_ptr<py::object> held(const py::object& o) {
    return std::shared_ptr<py::object>(new py::object(o), [](py::object* p) {
        py::gil_scoped_acquire gil;
        delete p;
    });
}

// "KeyError: 'my rule failed'": the exception's type and text on one line (computed here,
// with the GIL held).
std::string describe(py::error_already_set& e) {
    std::string text;
    try {
        text = py::str(e.type().attr("__name__")).cast<std::string>();
        const std::string value = py::str(e.value()).cast<std::string>();
        if (!value.empty()) text += ": " + value;
    } catch (const py::error_already_set&) {
        text = "Python exception";
    }
    for (char& c : text)
        if (c == '\n') c = ' ';
    return text;
}

}  // namespace

PythonError::PythonError(py::error_already_set&& e)
    : std::runtime_error(describe(e)),
      original_(new py::error_already_set(std::move(e)), [](py::error_already_set* p) {
          py::gil_scoped_acquire gil;
          delete p;
      }) {}

void PythonError::restore() const {
    original_->restore();
}

namespace {

// A C++ rule that calls the Python function with the context it is given, the GIL held.
template <class Context>
std::function<void(Context&)> pythonRule(const py::function& fn) {
    auto f = held(fn);
    return [f](Context& c) {
        py::gil_scoped_acquire gil;
        try {
            (*f)(py::cast(&c, py::return_value_policy::reference));
        } catch (py::error_already_set& e) {
            throw PythonError(std::move(e));
        }
    };
}

}  // namespace

PhytomerCreationFunction creationFunction(const py::function& fn) {
    return pythonRule<PhytomerCreationContext>(fn);
}

PhytomerCallbackFunction callbackFunction(const py::function& fn) {
    return pythonRule<PhytomerCallbackContext>(fn);
}

namespace {

OrganPrototype prototypeFrom(py::handle result) {
    if (py::isinstance<Mesh>(result)) return {PrototypePart{result.cast<Mesh>(), Material{}}};
    OrganPrototype parts;
    try {
        for (py::handle part : result) {
            auto pair = part.cast<std::pair<Mesh, Material>>();
            parts.push_back({std::move(pair.first), std::move(pair.second)});
        }
    } catch (const std::exception&) {  // not iterable, or parts of the wrong kind
        throw Error("a prototype function must return a Mesh or a list of (Mesh, Material)",
                    {.parameter = "prototype function", .value = std::string(py::repr(result))});
    }
    return parts;
}

}  // namespace

LeafPrototypeFunction leafPrototypeFunction(const py::function& fn) {
    auto f = held(fn);
    return [f](const LeafPrototype& params, Rng&, int leafletIndex) {
        py::gil_scoped_acquire gil;
        try {
            return prototypeFrom((*f)(params, leafletIndex));
        } catch (py::error_already_set& e) {
            throw PythonError(std::move(e));
        }
    };
}

FloralPrototypeFunction floralPrototypeFunction(const py::function& fn) {
    auto f = held(fn);
    return [f](const FloralPrototypeRequest& request, Rng&) {
        py::gil_scoped_acquire gil;
        try {
            return prototypeFrom((*f)(request));
        } catch (py::error_already_set& e) {
            throw PythonError(std::move(e));
        }
    };
}

void setUserProgress(PlantArchitecture& arch, const py::object& fn) {
    std::shared_ptr<py::object> user = fn.is_none() ? nullptr : held(fn);
    arch.setProgressCallback([user](std::string_view stage, double fraction) {
        const bool onMain = std::this_thread::get_id() == mainThread;
        if (!onMain && !user) return;
        py::gil_scoped_acquire gil;
        try {
            if (onMain && PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (user) (*user)(std::string(stage), fraction);
        } catch (py::error_already_set& e) {
            throw PythonError(std::move(e));
        }
    });
}

void bindCallbacks(py::module_&) {
    mainThread = std::this_thread::get_id();
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const PythonError& e) {
            e.restore();
        }
    });
}

}  // namespace plantarch::python
