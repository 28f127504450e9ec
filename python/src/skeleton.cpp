// Measured plants (plantarch/Skeleton.h): shoots on measured points, skeletons read from node
// tables, JSON and MTG files, plants rebuilt on them and written back.

#include "plantarch/Skeleton.h"

#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

void bindSkeleton(py::module_& m) {
    py::class_<MeasuredLeaf>(m, "MeasuredLeaf",
                             "The leaves measured at one node of a measured shoot.")
        .def(py::init([](unsigned node, std::optional<vec3> normal, float length) {
                 return MeasuredLeaf{node, normal, length};
             }),
             py::arg("node"), py::arg("normal") = py::none(), py::arg("length") = 0.0f)
        .def_readwrite("node", &MeasuredLeaf::node, "the phytomer, 0-based")
        .def_readwrite("normal", &MeasuredLeaf::normal, "the way the blades face, or None")
        .def_readwrite("length", &MeasuredLeaf::length,
                       "the largest blade's length, m (0: the species')");
    py::class_<MeasuredShootOptions>(m, "MeasuredShootOptions",
                                     "Options of PlantArchitecture.addShootFromNodePositions.")
        .def(py::init<>())
        .def_readwrite("leafScale", &MeasuredShootOptions::leafScale,
                       "leaf size on the measured nodes, fraction of full size, (0, 1]")
        .def_readwrite("attachTolerance", &MeasuredShootOptions::attachTolerance,
                       "how far the first point may be from where the shoot starts, m")
        .def_readwrite("continueParent", &MeasuredShootOptions::continueParent,
                       "continue the parent's tip instead of growing from an axil")
        .def_readwrite("petioleIndex", &MeasuredShootOptions::petioleIndex,
                       "the axil of a lateral shoot")
        .def_readwrite("bareNodes", &MeasuredShootOptions::bareNodes,
                       "phytomers (0-based) measured without leaves")
        .def_readwrite("leaves", &MeasuredShootOptions::leaves, "list of MeasuredLeaf");
    auto cls = py::reinterpret_borrow<py::class_<PlantArchitecture>>(m.attr("PlantArchitecture"));
    cls.def("addShootFromNodePositions", &PlantArchitecture::addShootFromNodePositions,
            py::arg("plantID"), py::arg("parent_shoot_ID"), py::arg("parent_node_index"),
            py::arg("node_positions"), py::arg("node_radii"), py::arg("shoot_type_label"),
            py::arg("options") = MeasuredShootOptions{},
            inPython(docs::PlantArchitecture_addShootFromNodePositions,
                     "node_positions: a sequence of vec3 (or of (x, y, z)); node_radii: a list "
                     "of floats or []. parent_shoot_ID -1 makes the base stem."))
        .def("getBaseStemShootType", &PlantArchitecture::getBaseStemShootType,
             docs::PlantArchitecture_getBaseStemShootType);

    py::enum_<SkeletonLink>(m, "SkeletonLink", "How a skeleton node continues from its parent.")
        .value("auto", SkeletonLink::Auto, "not given: the first child continues, others branch")
        .value("continues", SkeletonLink::Continue, "continues the parent's axis (MTG '<')")
        .value("branch", SkeletonLink::Branch, "starts a lateral axis (MTG '+')");
    py::class_<SkeletonNode>(m, "SkeletonNode", "One measured point of a skeleton.")
        .def(py::init<>())
        .def(py::init([](long id, long parent, vec3 position, float radius,
                         const std::string& shootType, SkeletonLink link) {
                 SkeletonNode n;
                 n.id = id;
                 n.parent = parent;
                 n.position = position;
                 n.radius = radius;
                 n.shootType = shootType;
                 n.link = link;
                 return n;
             }),
             py::arg("id"), py::arg("parent"), py::arg("position"), py::arg("radius") = 0.0f,
             py::arg("shoot_type") = "", py::arg("link") = SkeletonLink::Auto)
        .def_readwrite("id", &SkeletonNode::id, "unique in the skeleton")
        .def_readwrite("parent", &SkeletonNode::parent, "its parent's id, -1 for a root")
        .def_readwrite("position", &SkeletonNode::position, "m (or the skeleton's unit)")
        .def_readwrite("radius", &SkeletonNode::radius,
                       "radius of the internode ending here (0: not measured)")
        .def_readwrite("link", &SkeletonNode::link, "SkeletonLink")
        .def_readwrite("shootType", &SkeletonNode::shootType,
                       "shoot type of the axis this node starts ('': chosen)")
        .def_readwrite("organs", &SkeletonNode::organs, "tags: bare, flower, fruit")
        .def_readwrite("leafNormal", &SkeletonNode::leafNormal,
                       "the way the node's leaf blades face, or None")
        .def_readwrite("leafLength", &SkeletonNode::leafLength,
                       "the node's largest blade's length (0: the species')")
        .def_readwrite("line", &SkeletonNode::line, "line of the file it was read from");
    py::class_<Skeleton>(m, "Skeleton", "Measured nodes of one or more plants (one per root).")
        .def(py::init<>())
        .def_readwrite("nodes", &Skeleton::nodes, "list of SkeletonNode")
        .def_readwrite("source", &Skeleton::source, "the file it was read from");
    py::class_<ReconstructOptions>(m, "ReconstructOptions",
                                   "How reconstructPlants builds plants on a skeleton.")
        .def(py::init<>())
        .def_readwrite("age", &ReconstructOptions::age, "the plants' age, days")
        .def_readwrite("baseShootType", &ReconstructOptions::baseShootType,
                       "base stem type ('': the loaded species')")
        .def_readwrite("branchShootType", &ReconstructOptions::branchShootType,
                       "type of branches naming none ('': the parent's likeliest child type)")
        .def_readwrite("spacing", &ReconstructOptions::spacing,
                       "resample axes to internodes of about this length, m (0: every point)")
        .def_readwrite("unit", &ReconstructOptions::unit, "metres per unit of the skeleton")
        .def_readwrite("shoot", &ReconstructOptions::shoot, "MeasuredShootOptions of every shoot");
    m.def("readSkeletonFile", &readSkeletonFile, py::arg("path"), docs::readSkeletonFile);
    m.def("readSkeletonString", &readSkeletonString, py::arg("text"), py::arg("format"),
          py::arg("name") = "skeleton", docs::readSkeletonString);
    m.def("checkSkeleton", &checkSkeleton, py::arg("skeleton"), docs::checkSkeleton);
    m.def("reconstructPlants", &reconstructPlants, py::arg("architecture"), py::arg("skeleton"),
          py::arg("options") = ReconstructOptions{}, docs::reconstructPlants);
    m.def("plantSkeleton", &plantSkeleton, py::arg("architecture"), py::arg("plant_ids"),
          docs::plantSkeleton);
    m.def("skeletonCSV", &skeletonCSV, py::arg("skeleton"), docs::skeletonCSV);
    m.def("plantsMTG", &plantsMTG, py::arg("architecture"), py::arg("plant_ids"), docs::plantsMTG);
}

}  // namespace plantarch::python
