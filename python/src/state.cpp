// The plant state (PlantState.h) as Python objects: what rule functions see and change, and
// what PlantArchitecture.plant() shows. Fields keep their C++ names.

#include "bindings.h"
#include "callbacks.h"
#include "plantarch/PhytomerActions.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantState.h"

namespace plantarch::python {

namespace {

// A rule's shoot: copied on first use (the copy outlives the call).
template <class View>
Shoot& shootOf(View& v) {
    const auto& live = v.context();  // raises after the call
    if (!v.shoot) v.shoot = live.shoot;
    return *v.shoot;
}

template <class E>
void nameEnum(py::enum_<E>& e, std::initializer_list<E> values, const char* (*name)(E)) {
    for (E v : values) e.value(name(v), v);
}

}  // namespace

void bindState(py::module_& m) {
    py::enum_<BudState> bud(m, "BudState", "State of a vegetative or floral bud.");
    nameEnum(bud, {BudState::Dormant, BudState::Active, BudState::Broken, BudState::Dead},
             budStateName);
    py::enum_<FloralStage> stage(m, "FloralStage", "Stage of a floral bud.");
    nameEnum(stage,
             {FloralStage::Bud, FloralStage::FlowerClosed, FloralStage::FlowerOpen,
              FloralStage::Fruit, FloralStage::Removed},
             floralStageName);
    py::enum_<OrganKind> organ(m, "OrganKind", "Kind of organ (the 'organ' object data).");
    nameEnum(organ,
             {OrganKind::Internode, OrganKind::Petiole, OrganKind::Leaf, OrganKind::Peduncle,
              OrganKind::FlowerClosed, OrganKind::FlowerOpen, OrganKind::Fruit},
             organName);
    py::enum_<PhenologyStage> pheno(m, "PhenologyStage", "Where a plant is in its yearly cycle.");
    nameEnum(pheno,
             {PhenologyStage::Dormant, PhenologyStage::Vegetative, PhenologyStage::Reproductive,
              PhenologyStage::Senescent},
             phenologyStageName);

    py::class_<VegetativeBud>(m, "VegetativeBud", "An axillary or apical vegetative bud.")
        .def_readwrite("state", &VegetativeBud::state,
                       "BudState: dormant (waiting), active, broken (grew a shoot) or dead")
        .def_readwrite("breakTime", &VegetativeBud::breakTime, "plant age when it breaks, days")
        .def_readonly("childShoot", &VegetativeBud::childShoot, "shoot grown from it, -1: none")
        .def_readwrite("shootType", &VegetativeBud::shootType, "shoot type the bud grows into");
    py::class_<FlowerOrgan>(m, "FlowerOrgan", "One flower or fruit on a peduncle.")
        .def_readwrite("position", &FlowerOrgan::position,
                       "along the peduncle from its base, fraction of its length")
        .def_readwrite("azimuth", &FlowerOrgan::azimuth, "side of the peduncle, degrees")
        .def_readwrite("pitch", &FlowerOrgan::pitch, "from the peduncle axis, degrees")
        .def_readwrite("roll", &FlowerOrgan::roll, "about its own axis, degrees")
        .def_readwrite("flowerScale", &FlowerOrgan::flowerScale, "flower length, m")
        .def_readwrite("fruitScale", &FlowerOrgan::fruitScale, "full-grown fruit length, m")
        .def_readonly("objects", &FlowerOrgan::objects,
                      "Context objects of the flower or fruit (one per prototype part)");
    py::class_<FloralBud>(m, "FloralBud", "A floral bud and the flowers or fruit it bears.")
        .def_readwrite("stage", &FloralBud::stage,
                       "FloralStage: bud, flower_closed, flower_open, fruit or removed")
        .def_readwrite("state", &FloralBud::state, "BudState of the bud")
        .def_readonly("terminal", &FloralBud::terminal, "at the shoot tip (else axillary)")
        .def_readwrite("fruitGrowth", &FloralBud::fruitGrowth,
                       "current fruit size / full-grown size")
        .def_readonly("stageTime", &FloralBud::stageTime,
                      "plant age when the current stage began, days")
        .def_readwrite("peduncleLength", &FloralBud::peduncleLength, "m")
        .def_readwrite("pedunclePitch", &FloralBud::pedunclePitch,
                       "from the internode axis, toward its petiole's side, degrees")
        .def_readonly("flowers", &FloralBud::flowers,
                      "the flowers or fruit on its peduncle (FlowerOrgan)");
    py::class_<LeafOrgan>(m, "LeafOrgan", "A leaf (or leaflet) on a petiole.")
        .def_readonly("leafletIndex", &LeafOrgan::leafletIndex,
                      "0 tip, negative left, positive right")
        .def_readwrite("position", &LeafOrgan::position,
                       "along the petiole from its base, fraction of its length")
        .def_readwrite("scale", &LeafOrgan::scale, "full-grown length, m")
        .def_readwrite("pitch", &LeafOrgan::pitch, "degrees")
        .def_readwrite("yaw", &LeafOrgan::yaw, "degrees")
        .def_readwrite("roll", &LeafOrgan::roll, "degrees")
        .def_readonly("leafID", &LeafOrgan::leafID,
                      "unique within the plant (the leafID object data)")
        .def_readonly("age", &LeafOrgan::age, "days")
        .def_readonly("removed", &LeafOrgan::removed, "shed or removed")
        .def_readonly("objects", &LeafOrgan::objects, "Context objects of the leaf");
    py::class_<Petiole>(m, "Petiole", "A petiole with its leaves and axillary buds.")
        .def_readwrite("pitch", &Petiole::pitch, "from the internode axis, degrees")
        .def_readwrite("length", &Petiole::length, "full-grown length, m")
        .def_readwrite("radius", &Petiole::radius, "base radius, m")
        .def_readwrite("curvature", &Petiole::curvature, "degrees per m")
        .def_readonly("azimuth", &Petiole::azimuth, "about the internode axis, degrees")
        .def_readwrite("leaves", &Petiole::leaves, "its leaves (LeafOrgan), views")
        .def_readwrite("vegetativeBuds", &Petiole::vegetativeBuds,
                       "its axillary vegetative buds, views")
        .def_readwrite("floralBuds", &Petiole::floralBuds, "its floral buds, views")
        .def_readonly("object", &Petiole::object, "Context object of the petiole tube");
    py::class_<Internode>(m, "Internode", "An internode.")
        .def_readonly("direction", &Internode::direction, "unit axis of the internode")
        .def_readwrite("length", &Internode::length, "full-grown length, m")
        .def_readwrite("radius", &Internode::radius, "current radius, m")
        .def_readonly("pitch", &Internode::pitch, "realized zig-zag pitch, degrees")
        .def_readonly("phyllotacticAngle", &Internode::phyllotacticAngle,
                      "realized roll from the previous phytomer, degrees")
        .def_readonly("object", &Internode::object, "Context object of the internode tube");
    py::class_<Phytomer>(m, "Phytomer",
                         "A phytomer: internode, petioles with leaves and buds. Lists such as "
                         "petioles are views of the phytomer: in a rule, "
                         "ctx.phytomer.petioles[0].vegetativeBuds[0].state = BudState.dead "
                         "changes the plant.")
        .def_readwrite("internode", &Phytomer::internode, "its internode")
        .def_property_readonly(
            "petioles", [](Phytomer& p) -> std::vector<Petiole>& { return p.petioles; },
            py::return_value_policy::reference_internal,
            "its petioles with their leaves and buds (views: changes reach the plant)")
        .def_readonly("age", &Phytomer::age, "days")
        .def_readonly("birth", &Phytomer::birth, "plant age when it was made, days")
        .def_readwrite("internodeFraction", &Phytomer::internodeFraction,
                       "current internode length / full length")
        .def_readwrite("leafFraction", &Phytomer::leafFraction,
                       "current petiole and leaf size / full size")
        .def_readonly("parametersLabel", &Phytomer::parametersLabel,
                      "shoot type whose phytomer template built it")
        .def("killVegetativeBuds", &killVegetativeBuds,
             "Marks the dormant axillary vegetative buds dead (the remove_vegetative_buds "
             "rule): no branch grows from this node; an active or broken bud keeps growing.")
        .def("killFloralBuds", &killFloralBuds,
             "Marks the unopened floral buds dead and removed (the remove_floral_buds rule): "
             "no flowers from this node; open flowers and fruit stay.")
        .def("removeLeaves", &removeLeaves,
             "Removes the leaves, with their petioles' length and radius (the remove_leaves "
             "rule).")
        .def(
            "scaleLeaves",
            [](Phytomer& p, float factor) {
                if (!(factor >= 0.0f))
                    throw Error("out of range", {.parameter = "factor",
                                                 .value = std::to_string(factor),
                                                 .validRange = ">= 0"});
                for (Petiole& pt : p.petioles) {
                    pt.length *= factor;
                    for (LeafOrgan& l : pt.leaves) l.scale *= factor;
                }
            },
            py::arg("factor"), "Multiplies the full-grown size of its petioles and leaves.");
    py::class_<Shoot>(m, "Shoot", "A shoot: a chain of phytomers.")
        .def_readonly("id", &Shoot::id, "shoot ID within the plant")
        .def_readonly("type", &Shoot::type, "shoot type label")
        .def_readonly("parent", &Shoot::parent, "parent shoot ID, -1 for the base stem")
        .def_readonly("parentNode", &Shoot::parentNode, "node index on the parent")
        .def_readonly("rank", &Shoot::rank, "0 base stem, 1 its children, ...")
        .def_readonly("maxNodes", &Shoot::maxNodes, "realized max_nodes")
        .def_readonly("phyllochron", &Shoot::phyllochron, "realized days between phytomers")
        .def_readonly("apicalBud", &Shoot::apicalBud, "the apical bud (VegetativeBud)")
        .def_property_readonly(
            "phytomers", [](Shoot& s) -> std::vector<Phytomer>& { return s.phytomers; },
            py::return_value_policy::reference_internal, "its phytomers from the base (views)")
        .def_readonly("children", &Shoot::children, "IDs of the shoots growing from it")
        .def_readonly("removed", &Shoot::removed, "pruned away");
    py::class_<PlantInstance>(m, "PlantInstance",
                              "A copy of a plant's whole state (read it; change the plant "
                              "through PlantArchitecture's methods).")
        .def_readonly("id", &PlantInstance::id, "plant ID")
        .def_readonly("name", &PlantInstance::name, "species or user label")
        .def_readonly("base", &PlantInstance::base, "where its base stands, m")
        .def_readonly("age", &PlantInstance::age, "days")
        .def_readonly("shoots", &PlantInstance::shoots, py::return_value_policy::reference_internal,
                      "its shoots, indexed by shoot ID")
        .def_readonly("phenology", &PlantInstance::phenology,
                      "its phenological thresholds (PhenologyParameters)")
        .def_readonly("stage", &PlantInstance::stage, "PhenologyStage now")
        .def_readonly("season", &PlantInstance::season, "growing seasons begun");

    py::class_<FloralPrototypeRequest>(m, "FloralPrototypeRequest",
                                       "What a flower or fruit prototype function is asked for.")
        .def_readonly("fruit", &FloralPrototypeRequest::fruit, "a fruit (else a flower)")
        .def_readonly("open", &FloralPrototypeRequest::open, "for flowers: open (else closed)")
        .def_readonly("parameters", &FloralPrototypeRequest::parameters,
                      "the species' shape parameters of the family")
        .def_readonly("color", &FloralPrototypeRequest::color, "main colour from the species")
        .def_readonly("subdivisions", &FloralPrototypeRequest::subdivisions, "mesh resolution");

    // Rules get views (callbacks.h): copies that stay valid, and accessors that raise once
    // the rule has returned.
    py::class_<CreationView>(
        m, "PhytomerCreationContext",
        "What a phytomer creation function sees: the new phytomer (change it: kill buds, scale "
        "organs) and where it stands. Valid only during the call: its attributes raise "
        "plantarch.Error after it.")
        .def_property_readonly(
            "phytomer",
            [](CreationView& v) -> Phytomer& {
                v.context();
                return v.phytomer;
            },
            py::return_value_policy::reference_internal,
            "the new phytomer (change it: kill buds, scale organs); a copy written back to the "
            "plant when the function returns")
        .def_property_readonly("shoot", &shootOf<CreationView>,
                               py::return_value_policy::reference_internal,
                               "a copy of the shoot it is on, as the call began (read it)")
        .def_property_readonly(
            "nodeIndex", [](const CreationView& v) { return v.context().nodeIndex; },
            "index of the new phytomer on its shoot")
        .def_property_readonly(
            "parentNodeIndex", [](const CreationView& v) { return v.context().parentNodeIndex; },
            "node of the parent shoot this shoot grows from (-1: none)")
        .def_property_readonly(
            "shootMaxNodes", [](const CreationView& v) { return v.context().shootMaxNodes; },
            "the shoot's realized max_nodes")
        .def_property_readonly(
            "plantAge", [](const CreationView& v) { return v.context().plantAge; }, "days")
        .def_property_readonly(
            "rank", [](const CreationView& v) { return v.context().shoot.rank; },
            "rank of its shoot (0: base stem)");
    py::class_<CallbackView>(
        m, "PhytomerCallbackContext",
        "What a phytomer callback sees, once per phytomer every whole day of plant age. Valid "
        "only during the call: its attributes raise plantarch.Error after it.")
        .def_property_readonly(
            "phytomer",
            [](CallbackView& v) -> Phytomer& {
                v.context();
                return v.phytomer;
            },
            py::return_value_policy::reference_internal,
            "the phytomer (change it); a copy written back to the plant when the function "
            "returns")
        .def_property_readonly("shoot", &shootOf<CallbackView>,
                               py::return_value_policy::reference_internal,
                               "a copy of the shoot it is on, as the call began (read it)")
        .def_property_readonly(
            "nodeIndex", [](const CallbackView& v) { return v.context().nodeIndex; },
            "index of the phytomer on its shoot")
        .def_property_readonly(
            "plantAge", [](const CallbackView& v) { return v.context().plantAge; }, "days")
        .def_property_readonly(
            "nodeBase", [](const CallbackView& v) { return v.context().nodeBase; },
            "world position of the base of its internode today, m");
}

}  // namespace plantarch::python
