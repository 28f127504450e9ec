// One call at a time on a Context and its PlantArchitectures (see guard.h).
//
// Each bound function's pybind11 record gets guardedImpl in place of its own implementation
// (kept in a table): the wrapper finds the Contexts among the call's arguments, takes their
// locks in address order, runs the original (argument conversion, the call, the result) and
// lets the locks go. Deadlocks are ruled out by two rules: a thread waits for a lock only with
// the GIL released, and only when it holds no lock and runs no callback of a call (there it is
// refused instead, as re-entry).

#include "guard.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <unordered_map>

#include "callbacks.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

struct CallLock {
    std::mutex mutex;
    std::condition_variable freed;
    bool busy = false;      // under mutex
    std::thread::id owner;  // under mutex
    std::string running;    // the call that holds it, under mutex
    // Python exceptions raised in callbacks of the running call (the GIL guards them).
    std::vector<std::pair<std::string, std::shared_ptr<py::error_already_set>>> pythonErrors;
};

namespace {

namespace pyd = py::detail;

// Locks by Context, entries dropped when the Context's Python object goes (the GIL guards the
// table; never destroyed, so nothing runs at exit).
auto& locks = *new std::unordered_map<const Context*, std::shared_ptr<CallLock>>();

// What this thread runs: a callback of a call ("rule" ...; null: none), and how many locks its
// calls hold.
thread_local const char* insideCallback = nullptr;
thread_local int locksHeld = 0;

[[noreturn]] void refuse(const std::string& method, const std::string& running, bool sameThread) {
    if (insideCallback)
        throw Error(method + ": called from inside a " + insideCallback + " while " + running +
                    " is running on its Context; a " + insideCallback +
                    " may change only what it is given, not call its PlantArchitecture or "
                    "Context");
    if (sameThread)
        throw Error(method + ": called while " + running +
                    " is running on this thread (from Python code it ran: a finalizer, a signal "
                    "handler, a conversion); calls on one Context and its PlantArchitectures do "
                    "not nest");
    throw Error(method + ": called inside another plantarch call while " + running +
                " runs on another thread; waiting here could deadlock");
}

// The locks one call takes, in the order it takes them.
class Hold {
public:
    Hold(std::vector<std::shared_ptr<CallLock>> locks, const std::string& method)
        : locks_(std::move(locks)) {
        const bool mayWait = locksHeld == 0 && insideCallback == nullptr;
        try {
            for (const auto& l : locks_) {
                take(*l, method, mayWait);
                ++taken_;
            }
        } catch (...) {
            release();
            throw;
        }
        locksHeld += int(taken_);
    }
    ~Hold() {
        locksHeld -= int(taken_);
        release();
    }
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;

    /// The Python exception, raised in a callback of this call, that `failure` quotes.
    std::shared_ptr<py::error_already_set> quoted(const std::string& failure) const {
        for (const auto& l : locks_)
            for (const auto& [text, error] : l->pythonErrors)
                if (failure.find(text) != std::string::npos) return error;
        return nullptr;
    }

private:
    static void take(CallLock& l, const std::string& method, bool mayWait) {
        const std::thread::id me = std::this_thread::get_id();
        {
            std::unique_lock<std::mutex> g(l.mutex);
            if (!l.busy) return own(l, method, me);
            if (!mayWait || l.owner == me) {
                const std::string running = l.running;
                const bool sameThread = l.owner == me;
                g.unlock();
                refuse(method, running, sameThread);
            }
        }
        py::gil_scoped_release release;
        std::unique_lock<std::mutex> g(l.mutex);
        // On the main thread, Ctrl-C stops the wait (KeyboardInterrupt), as it stops a call.
        while (!l.freed.wait_for(g, std::chrono::milliseconds(50), [&] { return !l.busy; })) {
            if (!onMainThread()) continue;
            g.unlock();
            {
                py::gil_scoped_acquire gil;
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            }
            g.lock();
        }
        own(l, method, me);
    }
    static void own(CallLock& l, const std::string& method, std::thread::id me) {
        l.busy = true;
        l.owner = me;
        l.running = method;
    }
    void release() {
        for (std::size_t i = taken_; i-- > 0;) {
            CallLock& l = *locks_[i];
            l.pythonErrors.clear();
            {
                std::lock_guard<std::mutex> g(l.mutex);
                l.busy = false;
                l.owner = {};
                l.running.clear();
            }
            l.freed.notify_one();
        }
        taken_ = 0;
    }

    std::vector<std::shared_ptr<CallLock>> locks_;
    std::size_t taken_ = 0;
};

// ---- the wrapper ------------------------------------------------------------------------

struct Original {
    py::handle (*impl)(pyd::function_call&);
    std::string name;  // "PlantArchitecture.advanceTime"
};
auto& originals = *new std::unordered_map<const pyd::function_record*, Original>();

const Context* contextOf(py::handle h) {
    try {
        if (py::isinstance<PlantArchitecture>(h)) {
            const auto* a = h.cast<const PlantArchitecture*>();
            return a ? &a->context() : nullptr;
        }
        if (py::isinstance<Context>(h)) return h.cast<const Context*>();
    } catch (const py::cast_error&) {  // an instance never initialised
    }
    return nullptr;
}

std::vector<std::shared_ptr<CallLock>> locksOf(const pyd::function_call& call) {
    std::vector<std::shared_ptr<CallLock>> out;
    // The first argument of __init__ is the bare instance, not an object to look at.
    for (std::size_t i = call.func.is_constructor ? 1 : 0; i < call.args.size(); ++i) {
        if (!call.args[i]) continue;
        if (const Context* c = contextOf(call.args[i])) {
            std::shared_ptr<CallLock> l = callLockOf(*c);
            if (std::find(out.begin(), out.end(), l) == out.end()) out.push_back(std::move(l));
        }
    }
    std::sort(out.begin(), out.end());  // one order for every thread
    return out;
}

// Parameters that hold IDs or indices ("plantID", "objectIDs", "node_index", "plant").
bool namesAnID(const char* name) {
    const std::string_view n(name);
    auto ends = [&](std::string_view s) {
        return n.size() >= s.size() && n.substr(n.size() - s.size()) == s;
    };
    return ends("ID") || ends("IDs") || ends("index") || n == "plant" || n == "node";
}

bool fitsAnID(py::handle v) {
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (x == -1 && PyErr_Occurred()) PyErr_Clear();
    return overflow == 0 && x >= 0 && x <= (long long)UINT_MAX;
}

// An overload refused its arguments: an ID out of any ID's range is named (pybind11 would
// only say that no overload matched).
void refuseBadIDs(const pyd::function_call& call, const std::string& method) {
    const auto& names = call.func.args;
    for (std::size_t i = 0; i < call.args.size() && i < names.size(); ++i) {
        const py::handle v = call.args[i];
        if (!v || !names[i].name || !namesAnID(names[i].name)) continue;
        auto check = [&](py::handle x) {
            if (PyLong_Check(x.ptr()) && !PyBool_Check(x.ptr()) && !fitsAnID(x))
                throw Error("not an ID (" + method + ")",
                            {.parameter = names[i].name,
                             .value = py::str(x).cast<std::string>(),
                             .validRange = "a whole number from 0 to 4294967295"});
        };
        if (PyList_Check(v.ptr()) || PyTuple_Check(v.ptr()))
            for (py::handle x : v) check(x);
        else
            check(v);
    }
}

py::handle guardedImpl(pyd::function_call& call) {
    const Original& original = originals.at(&call.func);
    std::vector<std::shared_ptr<CallLock>> locks = locksOf(call);
    py::handle result;
    if (locks.empty()) {
        result = original.impl(call);
    } else {
        Hold hold(std::move(locks), original.name);
        try {
            result = original.impl(call);
        } catch (const PythonError&) {
            throw;  // raised as itself by its translator
        } catch (const py::error_already_set&) {
            throw;
        } catch (const std::exception& e) {
            // A Python exception the library wrapped (a canopy names the plant): raised as
            // itself, with the library's line as a note.
            const std::shared_ptr<py::error_already_set> python = hold.quoted(e.what());
            if (!python) throw;
            if (py::hasattr(python->value(), "add_note"))
                python->value().attr("add_note")(std::string("plantarch: ") + e.what());
            python->restore();
            throw py::error_already_set();
        }
    }
    if (result.ptr() == PYBIND11_TRY_NEXT_OVERLOAD) refuseBadIDs(call, original.name);
    return result;
}

// The pybind11 function behind a class or module attribute (null: none).
pyd::function_record* recordOf(py::handle attribute) {
    PyObject* f = attribute.ptr();
    if (PyInstanceMethod_Check(f)) f = PyInstanceMethod_GET_FUNCTION(f);
    if (PyMethod_Check(f)) f = PyMethod_GET_FUNCTION(f);
    if (Py_TYPE(f) == &PyStaticMethod_Type) {
        py::object inner = py::reinterpret_borrow<py::object>(attribute).attr("__func__");
        f = inner.ptr();  // kept alive by the staticmethod
    }
    if (!PyCFunction_Check(f)) return nullptr;
    PyObject* self = PyCFunction_GET_SELF(f);
    const char* name = pyd::get_function_record_capsule_name();
    if (!self || !PyCapsule_CheckExact(self) || !PyCapsule_IsValid(self, name)) return nullptr;
    return static_cast<pyd::function_record*>(PyCapsule_GetPointer(self, name));
}

void wrap(py::handle attribute, const std::string& owner) {
    if (PyObject_TypeCheck(attribute.ptr(), &PyProperty_Type)) {  // its getter and setter
        for (const char* part : {"fget", "fset"}) wrap(attribute.attr(part), owner);
        return;
    }
    for (pyd::function_record* r = recordOf(attribute); r; r = r->next) {
        if (r->impl == guardedImpl) continue;
        originals[r] = {r->impl, owner + r->name};
        r->impl = guardedImpl;
    }
}

}  // namespace

std::shared_ptr<CallLock> callLockOf(const Context& context) {
    auto found = locks.find(&context);
    if (found != locks.end()) return found->second;
    auto lock = std::make_shared<CallLock>();
    locks.emplace(&context, lock);
    // Forgotten when the Context's Python object goes (a new Context may get its address).
    const py::handle self = pyd::get_object_handle(&context, pyd::get_type_info(typeid(Context)));
    if (self) {
        const Context* key = &context;
        py::cpp_function forget([key](py::handle ref) {
            locks.erase(key);
            ref.dec_ref();
        });
        py::weakref(self, forget).release();
    }
    return lock;
}

CallbackScope::CallbackScope(const char* kind) : previous_(insideCallback) {
    insideCallback = kind;
}

CallbackScope::~CallbackScope() {
    insideCallback = previous_;
}

void recordPythonError(CallLock& lock, const PythonError& error) {
    lock.pythonErrors.emplace_back(error.what(), error.original());
}

void guardFunctions(py::module_& m) {
    const std::string module = "plantarch.";
    for (auto [name, value] : py::dict(m.attr("__dict__"))) {
        if (PyType_Check(value.ptr())) {
            const std::string owner = py::str(value.attr("__name__")).cast<std::string>() + ".";
            for (auto [member, attribute] : py::dict(value.attr("__dict__")))  // a mappingproxy
                wrap(attribute, owner);
        } else {
            wrap(value, module);
        }
    }
    // Whether every overload of a function is wrapped (for the tests).
    m.def(
        "_guarded",
        [](py::object fn) {
            pyd::function_record* r = recordOf(fn);
            if (!r) return false;
            for (; r; r = r->next)
                if (r->impl != guardedImpl) return false;
            return true;
        },
        py::arg("function"));
}

}  // namespace plantarch::python
