// The plantarch Python module (imported as plantarch._plantarch; plantarch/__init__.py is
// the package users import).

#include "bindings.h"
#include "callbacks.h"
#include "plantarch/Version.h"

PYBIND11_MODULE(_plantarch, m) {
    using namespace plantarch::python;
    m.doc() = "plantarch: builds and grows 3D plants from a phytomer-based parameter model.";
    bindValues(m);  // first: the Error translator (PythonError's below is tried before it)
    bindCallbacks(m);
    bindParameters(m);
    bindState(m);
    bindContext(m);
    bindArchitecture(m);
    bindGeometry(m);
    bindOutput(m);
#ifdef PLANTARCH_VERSION_STRING
    m.attr("__version__") = PLANTARCH_VERSION_STRING;
#endif
}
