#pragma once
// One call at a time on a Context and the PlantArchitectures built into it. Every function the
// module binds is wrapped once, after all are defined (guardFunctions): a call whose arguments
// include a Context or a PlantArchitecture takes that Context's lock first. A second thread
// waits for the lock with the GIL released; a call made from inside a rule or callback of a
// running call (or otherwise nested in one on the same thread) is refused with plantarch.Error.

#include <memory>
#include <string>
#include <vector>

#include "bindings.h"

namespace plantarch::python {

class PythonError;

/// The lock of one Context (shared by every PlantArchitecture built into it).
struct CallLock;

/// The lock of `context`, made on first use.
std::shared_ptr<CallLock> callLockOf(const Context& context);

/// Marks the current thread as running Python code for a call (a rule, a callback, a
/// prototype function): calls on a locked object from here are refused, never waited for.
/// `kind` names it in the refusal ("rule", "progress callback").
class CallbackScope {
public:
    explicit CallbackScope(const char* kind);
    ~CallbackScope();
    CallbackScope(const CallbackScope&) = delete;
    CallbackScope& operator=(const CallbackScope&) = delete;

private:
    const char* previous_;
};

/// Remembers a Python exception raised in a callback of `lock`'s running call: when the call
/// fails with a C++ error that quotes it (a canopy names the plant it stopped), the exception
/// itself is raised, with the C++ line as a note.
void recordPythonError(CallLock& lock, const PythonError& error);

/// Wraps every bound function of the module and of its classes (call at the end of module
/// initialisation).
void guardFunctions(py::module_& m);

}  // namespace plantarch::python
