// The plant state (PlantState.h) as Python objects: what rule functions see and change, and
// what PlantArchitecture.plant() shows. Fields keep their C++ names.

#include "bindings.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantState.h"

namespace plantarch::python {

namespace {

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
        .def_readwrite("state", &VegetativeBud::state)
        .def_readwrite("breakTime", &VegetativeBud::breakTime, "plant age when it breaks, days")
        .def_readonly("childShoot", &VegetativeBud::childShoot, "shoot grown from it, -1: none")
        .def_readwrite("shootType", &VegetativeBud::shootType);
    py::class_<FlowerOrgan>(m, "FlowerOrgan", "One flower or fruit on a peduncle.")
        .def_readwrite("position", &FlowerOrgan::position)
        .def_readwrite("azimuth", &FlowerOrgan::azimuth)
        .def_readwrite("pitch", &FlowerOrgan::pitch)
        .def_readwrite("roll", &FlowerOrgan::roll)
        .def_readwrite("flowerScale", &FlowerOrgan::flowerScale, "flower length, m")
        .def_readwrite("fruitScale", &FlowerOrgan::fruitScale, "full-grown fruit length, m")
        .def_readonly("objects", &FlowerOrgan::objects);
    py::class_<FloralBud>(m, "FloralBud", "A floral bud and the flowers or fruit it bears.")
        .def_readwrite("stage", &FloralBud::stage)
        .def_readwrite("state", &FloralBud::state)
        .def_readonly("terminal", &FloralBud::terminal)
        .def_readwrite("fruitGrowth", &FloralBud::fruitGrowth)
        .def_readonly("stageTime", &FloralBud::stageTime)
        .def_readwrite("peduncleLength", &FloralBud::peduncleLength)
        .def_readwrite("pedunclePitch", &FloralBud::pedunclePitch)
        .def_readonly("flowers", &FloralBud::flowers);
    py::class_<LeafOrgan>(m, "LeafOrgan", "A leaf (or leaflet) on a petiole.")
        .def_readonly("leafletIndex", &LeafOrgan::leafletIndex)
        .def_readwrite("position", &LeafOrgan::position)
        .def_readwrite("scale", &LeafOrgan::scale, "full-grown length, m")
        .def_readwrite("pitch", &LeafOrgan::pitch)
        .def_readwrite("yaw", &LeafOrgan::yaw)
        .def_readwrite("roll", &LeafOrgan::roll)
        .def_readonly("leafID", &LeafOrgan::leafID)
        .def_readonly("age", &LeafOrgan::age)
        .def_readonly("removed", &LeafOrgan::removed)
        .def_readonly("objects", &LeafOrgan::objects);
    py::class_<Petiole>(m, "Petiole", "A petiole with its leaves and axillary buds.")
        .def_readwrite("pitch", &Petiole::pitch)
        .def_readwrite("length", &Petiole::length)
        .def_readwrite("radius", &Petiole::radius)
        .def_readwrite("curvature", &Petiole::curvature)
        .def_readonly("azimuth", &Petiole::azimuth)
        .def_readwrite("leaves", &Petiole::leaves)
        .def_readwrite("vegetativeBuds", &Petiole::vegetativeBuds)
        .def_readwrite("floralBuds", &Petiole::floralBuds)
        .def_readonly("object", &Petiole::object);
    py::class_<Internode>(m, "Internode", "An internode.")
        .def_readonly("direction", &Internode::direction)
        .def_readwrite("length", &Internode::length, "full-grown length, m")
        .def_readwrite("radius", &Internode::radius, "current radius, m")
        .def_readonly("pitch", &Internode::pitch)
        .def_readonly("phyllotacticAngle", &Internode::phyllotacticAngle)
        .def_readonly("object", &Internode::object);
    py::class_<Phytomer>(m, "Phytomer",
                         "A phytomer: internode, petioles with leaves and buds. Lists such as "
                         "petioles are views: phytomer.petioles[0].vegetativeBuds[0].state = "
                         "BudState.dead changes the plant.")
        .def_readwrite("internode", &Phytomer::internode)
        .def_property_readonly(
            "petioles", [](Phytomer& p) -> std::vector<Petiole>& { return p.petioles; },
            py::return_value_policy::reference_internal)
        .def_readonly("age", &Phytomer::age)
        .def_readonly("birth", &Phytomer::birth)
        .def_readwrite("internodeFraction", &Phytomer::internodeFraction)
        .def_readwrite("leafFraction", &Phytomer::leafFraction)
        .def_readonly("parametersLabel", &Phytomer::parametersLabel)
        .def(
            "killVegetativeBuds",
            [](Phytomer& p) {
                for (Petiole& pt : p.petioles)
                    for (VegetativeBud& b : pt.vegetativeBuds)
                        if (b.state == BudState::Dormant || b.state == BudState::Active)
                            b.state = BudState::Dead;
            },
            "Kills the phytomer's axillary vegetative buds that have not broken.")
        .def(
            "killFloralBuds",
            [](Phytomer& p) {
                for (Petiole& pt : p.petioles)
                    for (FloralBud& b : pt.floralBuds)
                        if (b.stage == FloralStage::Bud) b.state = BudState::Dead;
            },
            "Kills the phytomer's floral buds that have not flowered.")
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
        .def_readonly("id", &Shoot::id)
        .def_readonly("type", &Shoot::type)
        .def_readonly("parent", &Shoot::parent)
        .def_readonly("parentNode", &Shoot::parentNode)
        .def_readonly("rank", &Shoot::rank)
        .def_readonly("maxNodes", &Shoot::maxNodes)
        .def_readonly("phyllochron", &Shoot::phyllochron)
        .def_readonly("apicalBud", &Shoot::apicalBud)
        .def_property_readonly(
            "phytomers", [](Shoot& s) -> std::vector<Phytomer>& { return s.phytomers; },
            py::return_value_policy::reference_internal)
        .def_readonly("children", &Shoot::children)
        .def_readonly("removed", &Shoot::removed);
    py::class_<PlantInstance>(m, "PlantInstance",
                              "A plant's whole state (read it; change it "
                              "through PlantArchitecture's methods).")
        .def_readonly("id", &PlantInstance::id)
        .def_readonly("name", &PlantInstance::name)
        .def_readonly("base", &PlantInstance::base)
        .def_readonly("age", &PlantInstance::age)
        .def_readonly("shoots", &PlantInstance::shoots, py::return_value_policy::reference_internal)
        .def_readonly("phenology", &PlantInstance::phenology)
        .def_readonly("stage", &PlantInstance::stage)
        .def_readonly("season", &PlantInstance::season);

    py::class_<FloralPrototypeRequest>(m, "FloralPrototypeRequest",
                                       "What a flower or fruit prototype function is asked for.")
        .def_readonly("fruit", &FloralPrototypeRequest::fruit, "a fruit (else a flower)")
        .def_readonly("open", &FloralPrototypeRequest::open, "for flowers: open (else closed)")
        .def_readonly("parameters", &FloralPrototypeRequest::parameters,
                      "the species' shape parameters of the family")
        .def_readonly("color", &FloralPrototypeRequest::color)
        .def_readonly("subdivisions", &FloralPrototypeRequest::subdivisions);

    py::class_<PhytomerCreationContext>(
        m, "PhytomerCreationContext",
        "What a phytomer creation function sees: the new phytomer (change it: kill buds, scale "
        "organs) and where it stands. Valid only during the call.")
        .def_property_readonly(
            "phytomer", [](PhytomerCreationContext& c) -> Phytomer& { return c.phytomer; },
            py::return_value_policy::reference)
        .def_property_readonly(
            "shoot", [](PhytomerCreationContext& c) -> Shoot& { return c.shoot; },
            py::return_value_policy::reference)
        .def_readonly("nodeIndex", &PhytomerCreationContext::nodeIndex)
        .def_readonly("parentNodeIndex", &PhytomerCreationContext::parentNodeIndex)
        .def_readonly("shootMaxNodes", &PhytomerCreationContext::shootMaxNodes)
        .def_readonly("plantAge", &PhytomerCreationContext::plantAge)
        .def_property_readonly("rank", [](PhytomerCreationContext& c) { return c.shoot.rank; });
    py::class_<PhytomerCallbackContext>(
        m, "PhytomerCallbackContext",
        "What a phytomer callback sees, once per phytomer every whole day of plant age. Valid "
        "only during the call.")
        .def_property_readonly(
            "phytomer", [](PhytomerCallbackContext& c) -> Phytomer& { return c.phytomer; },
            py::return_value_policy::reference)
        .def_property_readonly(
            "shoot", [](PhytomerCallbackContext& c) -> Shoot& { return c.shoot; },
            py::return_value_policy::reference)
        .def_readonly("nodeIndex", &PhytomerCallbackContext::nodeIndex)
        .def_readonly("plantAge", &PhytomerCallbackContext::plantAge)
        .def_readonly("nodeBase", &PhytomerCallbackContext::nodeBase);
}

}  // namespace plantarch::python
