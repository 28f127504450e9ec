// Leaf angles (plantarch/LeafAngles.h): the leaf inclination histogram and mean of plants and
// canopies, and the distributions leaves draw from.

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

namespace {

std::vector<double> edgesOr(const std::optional<std::vector<double>>& edges) {
    return edges ? *edges : defaultInclinationEdges();
}

}  // namespace

void bindLeafAngles(py::module_& m) {
    py::class_<LeafInclinationHistogram>(m, "LeafInclinationHistogram",
                                         "The leaf area of one or more plants by inclination.")
        .def_readonly("edges", &LeafInclinationHistogram::edges,
                      "the bins' edges, degrees (one more than the bins)")
        .def_readonly("fractions", &LeafInclinationHistogram::fractions,
                      "share of the leaf area in each bin (all 0 without any)")
        .def_readonly("leafArea", &LeafInclinationHistogram::leafArea,
                      "one-sided leaf area of the triangles measured, m^2")
        .def_readonly("meanInclination", &LeafInclinationHistogram::meanInclination,
                      "area-weighted mean inclination, degrees")
        .def("__repr__", [](const LeafInclinationHistogram& h) {
            return "LeafInclinationHistogram(" + std::to_string(h.fractions.size()) +
                   " bins, leafArea=" + std::to_string(h.leafArea) +
                   ", meanInclination=" + std::to_string(h.meanInclination) + ")";
        });
    m.def("defaultInclinationEdges", &defaultInclinationEdges, docs::defaultInclinationEdges);
    m.def(
        "leafInclinationHistogram",
        [](const PlantArchitecture& arch, py::handle plants,
           const std::optional<std::vector<double>>& edges) {
            return leafInclinationHistogram(arch, idList(plants, "plants"), edgesOr(edges));
        },
        py::arg("architecture"), py::arg("plants"), py::arg("edges") = py::none(),
        inPython(docs::leafInclinationHistogram,
                 "`plants`: one plant ID or a list of them (a canopy); `edges`: None for "
                 "defaultInclinationEdges()."));
    m.def(
        "meanLeafInclination",
        [](const PlantArchitecture& arch, py::handle plants) {
            return meanLeafInclination(arch, idList(plants, "plants"));
        },
        py::arg("architecture"), py::arg("plants"),
        inPython(docs::meanLeafInclination, "`plants`: one plant ID or a list of them."));
    m.def(
        "leafInclinationFractions",
        [](const LeafAngleParameters& p, const std::optional<std::vector<double>>& edges) {
            return leafInclinationFractions(p, edgesOr(edges));
        },
        py::arg("parameters"), py::arg("edges") = py::none(),
        inPython(docs::leafInclinationFractions,
                 "`parameters`: a LeafAngleParameters (PhenologyParameters.leaf_angles); "
                 "`edges`: None for defaultInclinationEdges()."));
    m.def("leafInclinationDensity", &leafInclinationDensity, py::arg("parameters"),
          py::arg("degrees"), docs::leafInclinationDensity);
    m.def("leafProjection", &leafProjection, py::arg("parameters"), py::arg("zenith"),
          docs::leafProjection);
}

}  // namespace plantarch::python
