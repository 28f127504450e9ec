#pragma once
// Python functions called from C++: rule functions, the progress callback, and the watch for
// Ctrl-C during long calls.

#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "bindings.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

/// A Python exception raised inside a function C++ called: its one-line text for C++ (a
/// canopy build reports it for its plant), and the exception itself, raised again when it
/// reaches the interpreter.
class PythonError : public std::runtime_error {
public:
    explicit PythonError(py::error_already_set&& e);
    /// Raises the original exception in the interpreter (the GIL must be held).
    void restore() const;

private:
    std::shared_ptr<py::error_already_set> original_;
};

/// A phytomer creation or callback function that calls `fn` with the GIL held.
PhytomerCreationFunction creationFunction(const py::function& fn);
PhytomerCallbackFunction callbackFunction(const py::function& fn);

/// Organ prototype builders that call `fn` with the GIL held. The function returns a Mesh, or
/// a list of (Mesh, Material) parts.
LeafPrototypeFunction leafPrototypeFunction(const py::function& fn);
FloralPrototypeFunction floralPrototypeFunction(const py::function& fn);

/// Installs the progress callback of `arch`: it calls `fn` (None: no user callback) and, on
/// the interpreter's main thread, checks for Ctrl-C, stopping the call with KeyboardInterrupt.
void setUserProgress(PlantArchitecture& arch, const py::object& fn);

/// Runs f() with the GIL released (rule functions and progress take it back).
template <class F>
auto interruptible(F&& f) -> decltype(f()) {
    py::gil_scoped_release release;
    return f();
}

void bindCallbacks(py::module_& m);

}  // namespace plantarch::python
