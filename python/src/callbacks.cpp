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

// Runs `call` (the GIL held) as a callback of a call holding `lock`: a Python exception it
// raises becomes a PythonError, remembered by the lock (see recordPythonError).
template <class F>
auto asCallback(const char* kind, CallLock* lock, F&& call) -> decltype(call()) {
    CallbackScope scope(kind);
    try {
        return call();
    } catch (py::error_already_set& e) {
        PythonError error(std::move(e));
        if (lock) recordPythonError(*lock, error);
        throw error;
    }
}

// A C++ rule that calls the Python function with a view of the context it is given, the GIL
// held; the view's phytomer is written back when the function returns.
template <class Context>
std::function<void(Context&)> pythonRule(const py::function& fn, std::shared_ptr<CallLock> lock) {
    auto f = held(fn);
    return [f, lock](Context& c) {
        py::gil_scoped_acquire gil;
        asCallback("rule", lock.get(), [&] {
            py::object view = py::cast(std::make_unique<RuleView<Context>>(c));
            auto* v = view.cast<RuleView<Context>*>();
            struct Expire {  // the view is dead once the rule returns, however it returns
                RuleView<Context>* v;
                ~Expire() { v->live = nullptr; }
            } expire{v};
            (*f)(view);
            c.phytomer = v->phytomer;
        });
    };
}

}  // namespace

PhytomerCreationFunction creationFunction(const py::function& fn, std::shared_ptr<CallLock> lock) {
    return pythonRule<PhytomerCreationContext>(fn, std::move(lock));
}

PhytomerCallbackFunction callbackFunction(const py::function& fn, std::shared_ptr<CallLock> lock) {
    return pythonRule<PhytomerCallbackContext>(fn, std::move(lock));
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

LeafPrototypeFunction leafPrototypeFunction(const py::function& fn,
                                            std::shared_ptr<CallLock> lock) {
    auto f = held(fn);
    return [f, lock](const LeafPrototype& params, Rng&, int leafletIndex) {
        py::gil_scoped_acquire gil;
        return asCallback("prototype function", lock.get(),
                          [&] { return prototypeFrom((*f)(params, leafletIndex)); });
    };
}

FloralPrototypeFunction floralPrototypeFunction(const py::function& fn,
                                                std::shared_ptr<CallLock> lock) {
    auto f = held(fn);
    return [f, lock](const FloralPrototypeRequest& request, Rng&) {
        py::gil_scoped_acquire gil;
        return asCallback("prototype function", lock.get(),
                          [&] { return prototypeFrom((*f)(request)); });
    };
}

bool onMainThread() {
    return std::this_thread::get_id() == mainThread;
}

void setUserProgress(PlantArchitecture& arch, const py::object& fn) {
    std::shared_ptr<py::object> user = fn.is_none() ? nullptr : held(fn);
    std::shared_ptr<CallLock> lock = callLockOf(arch.context());
    arch.setProgressCallback([user, lock](std::string_view stage, double fraction) {
        const bool onMain = onMainThread();
        if (!onMain && !user) return;
        py::gil_scoped_acquire gil;
        asCallback("progress callback", lock.get(), [&] {
            if (onMain && PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (user) (*user)(std::string(stage), fraction);
        });
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
