// The plantarch Python module (imported as plantarch._plantarch; plantarch/__init__.py is
// the package users import).

#include "bindings.h"
#include "callbacks.h"
#include "guard.h"
#include "plantarch/Version.h"

PYBIND11_MODULE(_plantarch, m) {
    using namespace plantarch::python;
    m.doc() = "plantarch: builds and grows 3D plants from a phytomer-based parameter model.";
    // numpy's C API now, under the import lock: first set up by two threads at once, inside
    // calls, pybind11's one-time initialiser would wait with the GIL held (a deadlock).
    // Without numpy the module still imports; the calls that return arrays raise its
    // ImportError (no module named 'numpy').
    try {
        py::module_::import("numpy");
        py::detail::npy_api::get();
    } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_ImportError)) throw;
    }
    bindValues(m);  // first: the Error translator (PythonError's below is tried before it)
    bindCallbacks(m);
    bindParameters(m);
    bindState(m);
    bindContext(m);
    bindArchitecture(m);
    bindGeometry(m);
    bindOutput(m);
    bindLight(m);
    bindPhysiology(m);  // after bindArchitecture: adds PlantArchitecture's methods
    bindLeafAngles(m);
    bindBending(m);
    bindCalibration(m);
    bindSkeleton(m);  // after bindArchitecture: adds PlantArchitecture's methods
    bindField(m);
    bindDataset(m);
#ifdef PLANTARCH_VERSION_STRING
    m.attr("__version__") = PLANTARCH_VERSION_STRING;
#endif
    guardFunctions(m);  // last: every function bound above
}
