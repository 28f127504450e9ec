// Calibration to field data (plantarch/Calibration.h): fitSpecies on a species (library name or
// file) and a target file, its result as a dict, and the report's JSON.

#include "plantarch/Calibration.h"

#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::python {

namespace {

py::dict residualDict(const FitResidual& r) {
    py::dict d;
    d["age"] = r.age;
    d["statistic"] = r.statistic;
    d["measured"] = r.measured;
    d["simulated_start"] = r.simulatedStart;
    d["simulated"] = r.simulated;
    d["residual"] = r.residual;
    return d;
}

py::dict fitInPython(const std::string& species, const std::string& target, int threads,
                     const py::object& onImprovement) {
    const FitTarget t = readFitTargetFile(target);
    const SpeciesModel model = loadSpecies(species);
    FitOptions options;
    options.threads = threads;
    if (!onImprovement.is_none())
        // Called on this thread (the one holding the GIL) between evaluations; a Python
        // exception it raises ends the fit and is raised from fitSpecies.
        options.onImprovement = [onImprovement](const FitEvaluation& e) {
            onImprovement(e.number, e.objective, e.values);
        };
    const FitResult r = fitSpecies(model, t, options);
    py::dict d;
    d["paths"] = r.paths;
    d["start"] = r.start;
    d["fitted"] = r.best;
    d["start_objective"] = r.startObjective;
    d["objective"] = r.bestObjective;
    d["stop"] = r.stopReason;
    d["algorithm"] = r.algorithm;
    py::list evaluations;
    for (const FitEvaluation& e : r.evaluations)
        evaluations.append(py::make_tuple(e.number, e.objective, e.values));
    d["evaluations"] = evaluations;
    py::list residuals;
    for (const FitResidual& x : r.residuals) residuals.append(residualDict(x));
    d["residuals"] = residuals;
    d["species_xml"] = writeSpeciesString(r.fitted);
    d["report"] = fitReportJson(r, t);
    return d;
}

}  // namespace

void bindCalibration(py::module_& m) {
    m.def("fitSpecies", &fitInPython, py::arg("species"), py::arg("target"), py::arg("threads") = 0,
          py::arg("onImprovement") = py::none(),
          inPython(docs::fitSpecies,
                   "In Python: fitSpecies(species, target, threads=0, onImprovement=None) takes a "
                   "library species name or species file and a target file (JSON, "
                   "docs/measured-plants.md); onImprovement(evaluation, objective, values) is "
                   "called at each improvement. Returns a dict: paths, start, fitted, "
                   "start_objective, objective, stop, algorithm, evaluations [(number, "
                   "objective, values)], residuals [dicts], species_xml (the fitted species "
                   "file's text) and report (the JSON of plantarch fit --report)."));
    m.def("readPointCloudFile", &readPointCloudFile, py::arg("path"),
          inPython(docs::readPointCloudFile,
                   "In Python: a list of vec3 (the points of a .ply, .xyz, .txt or .pts file)."));
}

}  // namespace plantarch::python
