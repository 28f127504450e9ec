// Shoots bending under load (plantarch/Bending.h): bendPlant, straightenPlant, pullNode,
// displaceNode, bentNodePositions and the PullResult they give.

#include "plantarch/Bending.h"

#include <fmt/format.h>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

void bindBending(py::module_& m) {
    py::class_<PullResult>(m, "PullResult",
                           "What a pull did (pullNode, displaceNode): forces in N, moments in "
                           "N m, positions in m, world axes.")
        .def_readonly("position", &PullResult::position, "where the node is now")
        .def_readonly("displacement", &PullResult::displacement,
                      "how far it moved from where the plant's weight alone holds it")
        .def_readonly("force", &PullResult::force,
                      "the force on the node (given, or the one found to move it)")
        .def_readonly("nodeReaction", &PullResult::nodeReaction,
                      "what the node pushes back with on whatever pulls it (-force)")
        .def_readonly("baseForce", &PullResult::baseForce,
                      "force the pulled shoot's support exerts on it at its base")
        .def_readonly("baseMoment", &PullResult::baseMoment,
                      "moment its support exerts on it, about its base node")
        .def_readonly("groundForce", &PullResult::groundForce,
                      "force the ground exerts on the plant")
        .def_readonly("groundMoment", &PullResult::groundMoment,
                      "moment the ground exerts on the plant, about its base")
        .def_readonly("iterations", &PullResult::iterations,
                      "fixed-point iterations of the last solve")
        .def("__repr__", [](const PullResult& r) {
            auto v = [](const vec3& x) {
                // fmt, not "(" + std::string: GCC 12 warns falsely (-Wrestrict) on that form.
                return fmt::format("({}, {}, {})", x.x, x.y, x.z);
            };
            return "PullResult(force=" + v(r.force) + ", displacement=" + v(r.displacement) +
                   ", baseForce=" + v(r.baseForce) + ")";
        });
    m.def(
        "bendPlant",
        [](PlantArchitecture& a, unsigned id) {
            py::gil_scoped_release release;
            bendPlant(a, id);
        },
        py::arg("architecture"), py::arg("plant_id"), docs::bendPlant);
    m.def(
        "straightenPlant",
        [](PlantArchitecture& a, unsigned id) {
            py::gil_scoped_release release;
            straightenPlant(a, id);
        },
        py::arg("architecture"), py::arg("plant_id"), docs::straightenPlant);
    m.def(
        "pullNode",
        [](PlantArchitecture& a, unsigned id, unsigned shoot, unsigned node, vec3 force) {
            py::gil_scoped_release release;
            return pullNode(a, id, shoot, node, force);
        },
        py::arg("architecture"), py::arg("plant_id"), py::arg("shoot_id"), py::arg("node"),
        py::arg("force"), docs::pullNode);
    m.def(
        "displaceNode",
        [](PlantArchitecture& a, unsigned id, unsigned shoot, unsigned node, vec3 displacement) {
            py::gil_scoped_release release;
            return displaceNode(a, id, shoot, node, displacement);
        },
        py::arg("architecture"), py::arg("plant_id"), py::arg("shoot_id"), py::arg("node"),
        py::arg("displacement"), docs::displaceNode);
    m.def("bentNodePositions", &bentNodePositions, py::arg("architecture"), py::arg("plant_id"),
          py::arg("shoot_id"), docs::bentNodePositions);
}

}  // namespace plantarch::python
