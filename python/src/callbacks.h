#pragma once
// Python functions called from C++: rule functions, the progress callback, and the watch for
// Ctrl-C during long calls.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "bindings.h"
#include "guard.h"
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
    /// The original exception.
    const std::shared_ptr<py::error_already_set>& original() const { return original_; }

private:
    std::shared_ptr<py::error_already_set> original_;
};

/// What a Python rule is handed in place of the C++ context: a copy of the phytomer, written
/// back when the rule returns, and on first use a copy of its shoot, so that nothing Python
/// keeps points into the plant. Its accessors raise plantarch.Error once the rule returned.
template <class Ctx>
struct RuleView {
    explicit RuleView(Ctx& c) : live(&c), phytomer(c.phytomer) {}
    /// The context while the rule runs; raises after.
    Ctx& context() const {
        if (!live)
            throw Error(
                "a rule's context used after the rule returned; it is valid only during "
                "the call (keep copies of the values you need)");
        return *live;
    }
    Ctx* live;  // null once the rule has returned
    Phytomer phytomer;
    std::optional<Shoot> shoot;
};
using CreationView = RuleView<PhytomerCreationContext>;
using CallbackView = RuleView<PhytomerCallbackContext>;

/// A phytomer creation or callback function that calls `fn` with the GIL held, as a callback
/// of calls holding `lock` (the lock of the PlantArchitecture it is registered with).
PhytomerCreationFunction creationFunction(const py::function& fn, std::shared_ptr<CallLock> lock);
PhytomerCallbackFunction callbackFunction(const py::function& fn, std::shared_ptr<CallLock> lock);

/// Organ prototype builders that call `fn` with the GIL held. The function returns a Mesh, or
/// a list of (Mesh, Material) parts.
LeafPrototypeFunction leafPrototypeFunction(const py::function& fn, std::shared_ptr<CallLock> lock);
FloralPrototypeFunction floralPrototypeFunction(const py::function& fn,
                                                std::shared_ptr<CallLock> lock);

/// Installs the progress callback of `arch`: it calls `fn` (None: no user callback) and, on
/// the interpreter's main thread, checks for Ctrl-C, stopping the call with KeyboardInterrupt.
void setUserProgress(PlantArchitecture& arch, const py::object& fn);

/// Whether this is the interpreter's main thread (the one Python delivers Ctrl-C to).
bool onMainThread();

/// Runs f() with the GIL released (rule functions and progress take it back).
template <class F>
auto interruptible(F&& f) -> decltype(f()) {
    py::gil_scoped_release release;
    return f();
}

void bindCallbacks(py::module_& m);

}  // namespace plantarch::python
