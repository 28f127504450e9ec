// PlantArchitecture: the species library, manual building, growth, phenology, pruning,
// collision avoidance, queries and plant structure files. Long calls release the GIL; Python
// rule functions and the progress callback take it back when they are called.

#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bindings.h"
#include "callbacks.h"
#include "docstrings.h"
#include "plantarch/CollisionStatsFields.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"

namespace plantarch::python {

namespace {

using Release = py::call_guard<py::gil_scoped_release>;

ShootSpec shootSpec(unsigned nodes, const AxisRotation& rotation, float radius, float lengthMax,
                    float lengthScale, float leafScale, float taper, const std::string& type) {
    ShootSpec spec;
    spec.phytomers = nodes;
    spec.baseRotation = rotation;
    spec.size = {radius, lengthMax, lengthScale, leafScale};
    spec.radiusTaper = taper;
    spec.shootType = type;
    return spec;
}

std::vector<vec3> points(const py::object& value) {
    std::vector<vec3> out;
    for (py::handle p : value) out.push_back(toVec3(p, "attraction_points"));
    return out;
}

py::dict statsDict(const CollisionStats& s) {
    py::dict d;
    visitCollisionStats(s, [&](const char* name, auto value) { d[name] = value; });
    return d;
}

CollisionOrgans organs(bool internodes, bool leaves, bool petioles, bool flowers, bool fruit) {
    return {internodes, leaves, petioles, flowers, fruit};
}

bool isWhole(const py::handle& v) {
    return PyLong_Check(v.ptr()) && !PyBool_Check(v.ptr());
}

// A Python int or float (not a bool, not a numpy value): how advanceTime tells its forms
// apart.
bool isPlainNumber(const py::handle& v) {
    return (PyLong_Check(v.ptr()) || PyFloat_Check(v.ptr())) && !PyBool_Check(v.ptr());
}

std::string reprOf(const py::handle& v) {
    return py::repr(v).cast<std::string>();
}

// advanceTime as Python users write it: the days first, then the plants (one ID or a list)
// as a second argument or the keyword plantIDs; the reference package's keywords dt and
// plant_id are read too. Two whole numbers given positionally read two ways (plantarch's C++
// order is plant first), so they are refused with the keyword call that says which; so is a
// whole number followed by a fraction (the C++ order, plant then days).
void advanceTimeCall(PlantArchitecture& a, const py::args& args, const py::kwargs& kwargs) {
    py::object days, plants = py::none();
    bool plantsPositional = false;
    if (args.size() > 2)
        throw Error("advanceTime takes the days and the plants, " + std::to_string(args.size()) +
                        " positional arguments given",
                    {.validRange = "advanceTime(time_step_days, plantIDs=None)"});
    if (!args.empty()) days = args[0];
    if (args.size() == 2) {
        plants = args[1];
        plantsPositional = true;
    }
    for (const auto& [key, value] : kwargs) {
        const std::string name = key.cast<std::string>();
        const bool isDays = name == "time_step_days" || name == "dt";
        const bool isPlants = name == "plantIDs" || name == "plant_id" || name == "plantID";
        if (!isDays && !isPlants)
            throw Error("advanceTime has no argument '" + name + "'",
                        {.validRange = "time_step_days (or dt), plantIDs (or plant_id)"});
        if ((isDays && days) || (isPlants && (plantsPositional || !plants.is_none())))
            throw Error("advanceTime: " + name + " given twice",
                        {.validRange = "advanceTime(time_step_days, plantIDs=None)"});
        (isDays ? days : plants) = py::reinterpret_borrow<py::object>(value);
    }
    if (!days)
        throw Error("advanceTime needs the days to grow",
                    {.validRange = "advanceTime(time_step_days, plantIDs=None)"});
    if (plantsPositional && isWhole(days) && isWhole(plants)) {
        const std::string d = reprOf(days), p = reprOf(plants);
        throw Error("advanceTime(" + d + ", " + p + ") reads two ways: write advanceTime(" + d +
                        ", plantIDs=" + p + ") to grow plant " + p + " by " + d +
                        " days, or advanceTime(" + p + ", plantIDs=" + d + ") to grow plant " + d +
                        " by " + p + " days",
                    {.validRange = "advanceTime(time_step_days, plantIDs=None)"});
    }
    if (!isPlainNumber(days)) {
        const bool oldOrder = plantsPositional && isPlainNumber(plants);
        throw Error(oldOrder ? "advanceTime takes the days first in Python: write advanceTime(" +
                                   reprOf(plants) + ", plantIDs=" + reprOf(days) + ")"
                             : "advanceTime: the days must be a number",
                    {.parameter = "time_step_days", .value = reprOf(days)});
    }
    if (plantsPositional && isWhole(days) && PyFloat_Check(plants.ptr()))
        throw Error("advanceTime takes the days first in Python: write advanceTime(" +
                        reprOf(plants) + ", plantIDs=" + reprOf(days) + ")",
                    {.parameter = "plantIDs", .value = reprOf(plants)});
    const double step = days.cast<double>();
    if (plants.is_none()) {
        interruptible([&] { a.advanceTime(step); });
        return;
    }
    const std::vector<unsigned> ids = idList(plants, "plantIDs");
    if (isWhole(plants)) {
        interruptible([&] { a.advanceTime(ids.front(), step); });
        return;
    }
    interruptible([&] { a.advanceTime(ids, step); });
}

PlantStructureReadOptions readOptions(py::object warnings) {
    PlantStructureReadOptions o;
    if (!warnings.is_none()) {
        auto list = std::make_shared<py::object>(warnings);
        o.onWarning = [list](const std::string& w) {
            py::gil_scoped_acquire gil;
            CallbackScope scope("warnings list");
            (*list).attr("append")(w);
        };
    }
    return o;
}

void bindLibrary(py::class_<PlantArchitecture>& c) {
    c.def("loadPlantModelFromLibrary", &PlantArchitecture::loadPlantModelFromLibrary,
          py::arg("plant_label"), docs::PlantArchitecture_loadPlantModelFromLibrary)
        .def("getAvailablePlantModels", &PlantArchitecture::getAvailablePlantModels,
             docs::PlantArchitecture_getAvailablePlantModels)
        .def("getCurrentPlantModel", &PlantArchitecture::getCurrentPlantModel,
             docs::PlantArchitecture_getCurrentPlantModel)
        .def(
            "buildPlantInstanceFromLibrary",
            [](PlantArchitecture& a, vec3 base, float age, std::map<std::string, float> bp) {
                return interruptible(
                    [&] { return a.buildPlantInstanceFromLibrary(base, age, bp); });
            },
            py::arg("base_position"), py::arg("age"),
            py::arg("build_parameters") = std::map<std::string, float>{},
            docs::PlantArchitecture_buildPlantInstanceFromLibrary)
        .def(
            "buildPlantCanopyFromLibrary",
            [](PlantArchitecture& a, vec3 center, vec2 spacing, std::pair<int, int> count,
               float age, float germination, std::map<std::string, float> bp) {
                return interruptible([&] {
                    return a.buildPlantCanopyFromLibrary(center, spacing,
                                                         glm::ivec2(count.first, count.second), age,
                                                         germination, bp);
                });
            },
            py::arg("canopy_center"), py::arg("plant_spacing"), py::arg("plant_count"),
            py::arg("age"), py::arg("germination_rate") = 1.0f,
            py::arg("build_parameters") = std::map<std::string, float>{},
            inPython(
                docs::PlantArchitecture_buildPlantCanopyFromLibrary,
                "A grid of plant_count (x, y) plants plant_spacing (x, y) m apart centred on "
                "canopy_center, grown to `age` days (in parallel; the same seed gives the same "
                "plants for any thread count). Returns the plant IDs."))
        .def(
            "buildPlantCanopyScatteredFromLibrary",
            [](PlantArchitecture& a, vec3 center, vec2 extent, unsigned plants, float age,
               float germination, std::map<std::string, float> bp) {
                CanopyOptions o;
                o.layout = CanopyOptions::Layout::Scatter;
                o.center = center;
                o.extent = extent;
                o.plants = plants;
                o.germinationRate = germination;
                o.buildParameters = std::move(bp);
                return interruptible([&] { return a.buildPlantCanopyFromLibrary(o, age); });
            },
            py::arg("canopy_center"), py::arg("canopy_extent"), py::arg("plant_count"),
            py::arg("age"), py::arg("germination_rate") = 1.0f,
            py::arg("build_parameters") = std::map<std::string, float>{},
            "plant_count plants scattered at random over a canopy_extent (x, y) rectangle "
            "(buildPlantCanopyFromLibrary with CanopyOptions.Layout.Scatter).")
        .def("setTrellisGeometry", &PlantArchitecture::setTrellisGeometry, py::arg("on"),
             docs::PlantArchitecture_setTrellisGeometry)
        .def("getTrellisGeometry", &PlantArchitecture::getTrellisGeometry,
             "Whether library plants get their species' trellis (posts and wires).")
        .def("setMeshDetail", &PlantArchitecture::setMeshDetail, py::arg("detail"),
             docs::PlantArchitecture_setMeshDetail, Release())
        .def("getMeshDetail", &PlantArchitecture::getMeshDetail,
             "The factor on every organ's mesh resolution (setMeshDetail).")
        .def("setGroundClearance", py::overload_cast<bool>(&PlantArchitecture::setGroundClearance),
             py::arg("on"), docs::PlantArchitecture_setGroundClearance, Release())
        .def("setGroundClearance",
             py::overload_cast<unsigned, bool>(&PlantArchitecture::setGroundClearance),
             py::arg("plant"), py::arg("on"), docs::PlantArchitecture_setGroundClearance, Release())
        .def("getGroundClearance",
             py::overload_cast<>(&PlantArchitecture::getGroundClearance, py::const_),
             docs::PlantArchitecture_getGroundClearance)
        .def("getGroundClearance",
             py::overload_cast<unsigned>(&PlantArchitecture::getGroundClearance, py::const_),
             py::arg("plant"), docs::PlantArchitecture_getGroundClearance)
        .def("setTriangleLimit", &PlantArchitecture::setTriangleLimit, py::arg("limit"),
             docs::PlantArchitecture_setTriangleLimit)
        .def("getTriangleLimit", &PlantArchitecture::getTriangleLimit,
             "The triangle limit (0: none).")
        .def_static("defaultTriangleLimit", &PlantArchitecture::defaultTriangleLimit,
                    docs::PlantArchitecture_defaultTriangleLimit)
        .def("getPlantTrellisObjectIDs", &PlantArchitecture::getPlantTrellisObjectIDs,
             py::arg("plantID"), docs::PlantArchitecture_getPlantTrellisObjectIDs);
}

void bindShootTypes(py::class_<PlantArchitecture>& c) {
    c.def("defineShootType", &PlantArchitecture::defineShootType, py::arg("shoot_type_label"),
          py::arg("shoot_params"), docs::PlantArchitecture_defineShootType)
        .def("getShootType", &PlantArchitecture::shootType, py::arg("shoot_type_label"),
             "A copy of a defined shoot type's parameters.")
        .def("listShootTypeLabels",
             py::overload_cast<>(&PlantArchitecture::listShootTypeLabels, py::const_),
             docs::PlantArchitecture_listShootTypeLabels)
        .def("listShootTypeLabels",
             py::overload_cast<unsigned>(&PlantArchitecture::listShootTypeLabels, py::const_),
             py::arg("plantID"), docs::PlantArchitecture_listShootTypeLabels)
        .def("listShootTypeLabels",
             py::overload_cast<const std::string&>(&PlantArchitecture::listShootTypeLabels,
                                                   py::const_),
             py::arg("plant_label"), docs::PlantArchitecture_listShootTypeLabels)
        .def("getCurrentShootParameters",
             py::overload_cast<const std::string&>(&PlantArchitecture::getCurrentShootParameters,
                                                   py::const_),
             py::arg("shoot_type_label"), docs::PlantArchitecture_getCurrentShootParameters)
        .def("getCurrentShootParameters",
             py::overload_cast<>(&PlantArchitecture::getCurrentShootParameters, py::const_),
             docs::PlantArchitecture_getCurrentShootParameters)
        .def("updateCurrentShootParameters",
             py::overload_cast<const std::string&, const ShootParameters&>(
                 &PlantArchitecture::updateCurrentShootParameters),
             py::arg("shoot_type_label"), py::arg("params"),
             inPython(
                 docs::PlantArchitecture_updateCurrentShootParameters,
                 "Replaces a shoot type's parameters (validated); named rules are kept as named."))
        .def("updateCurrentShootParameters",
             py::overload_cast<const std::map<std::string, ShootParameters>&>(
                 &PlantArchitecture::updateCurrentShootParameters),
             py::arg("params"),
             inPython(docs::PlantArchitecture_updateCurrentShootParameters,
                      "The same for several shoot types at once."));
}

// The option structs of manual building, made with the specification's keyword names.
void bindShootSpec(py::module_& m) {
    py::class_<PhytomerSize>(m, "PhytomerSize",
                             "Size of the phytomers a manual-building call makes.")
        .def(py::init([](float radius, float lengthMax, float lengthScale, float leafScale) {
                 return PhytomerSize{radius, lengthMax, lengthScale, leafScale};
             }),
             py::kw_only(), py::arg("internode_radius") = 0.001f,
             py::arg("internode_length_max") = 0.02f,
             py::arg("internode_length_scale_factor_fraction") = 1.0f,
             py::arg("leaf_scale_factor_fraction") = 1.0f)
        .def_readwrite("internodeRadius", &PhytomerSize::internodeRadius, "m, (0, 10]")
        .def_readwrite("internodeLengthMax", &PhytomerSize::internodeLengthMax,
                       "full-grown internode length, m, [0, 100]")
        .def_readwrite("internodeLengthScale", &PhytomerSize::internodeLengthScale,
                       "current / full internode length, (0, 1]")
        .def_readwrite("leafScale", &PhytomerSize::leafScale,
                       "current / full petiole and leaf size, (0, 1]");
    py::class_<ShootSpec>(m, "ShootSpec",
                          "Where and how a new shoot starts: the options of addBaseStemShoot, "
                          "appendShoot, addChildShoot and addEpicormicShoot.")
        .def(py::init([](const std::string& type, unsigned nodes, AxisRotation rot, float radius,
                         float lengthMax, float lengthScale, float leafScale, float taper) {
                 return shootSpec(nodes, rot, radius, lengthMax, lengthScale, leafScale, taper,
                                  type);
             }),
             py::kw_only(), py::arg("shoot_type_label"), py::arg("current_node_number") = 1,
             py::arg("base_rotation") = AxisRotation{}, py::arg("internode_radius") = 0.001f,
             py::arg("internode_length_max") = 0.02f,
             py::arg("internode_length_scale_factor_fraction") = 1.0f,
             py::arg("leaf_scale_factor_fraction") = 1.0f, py::arg("radius_taper") = 0.0f)
        .def_readwrite("shootType", &ShootSpec::shootType, "shoot type label")
        .def_readwrite("phytomers", &ShootSpec::phytomers, "phytomers to create now, 1 to 100000")
        .def_readwrite("baseRotation", &ShootSpec::baseRotation, "degrees")
        .def_readwrite("size", &ShootSpec::size, "size of the phytomers created (PhytomerSize)")
        .def_readwrite("radiusTaper", &ShootSpec::radiusTaper,
                       "tip radius reduction along the shoot, [0, 1]");
}

void bindManual(py::class_<PlantArchitecture>& c) {
    c.def("addBaseStemShoot",
          py::overload_cast<unsigned, const ShootSpec&>(&PlantArchitecture::addBaseStemShoot),
          py::arg("plantID"), py::arg("spec"), docs::PlantArchitecture_addBaseStemShoot)
        .def("appendShoot",
             py::overload_cast<unsigned, unsigned, const ShootSpec&>(
                 &PlantArchitecture::appendShoot),
             py::arg("plantID"), py::arg("parent_shoot_ID"), py::arg("spec"),
             docs::PlantArchitecture_appendShoot)
        .def("addChildShoot", &PlantArchitecture::addChildShoot, py::arg("plantID"),
             py::arg("parent_shoot_ID"), py::arg("parent_node_index"), py::arg("spec"),
             py::arg("petiole_index") = 0,
             inPython(docs::PlantArchitecture_addChildShoot,
                      "A lateral shoot from a ShootSpec; returns its ID."))
        .def("addEpicormicShoot", &PlantArchitecture::addEpicormicShoot, py::arg("plantID"),
             py::arg("parent_shoot_ID"), py::arg("parent_position_fraction"), py::arg("spec"),
             inPython(docs::PlantArchitecture_addEpicormicShoot,
                      "A water sprout from a ShootSpec; returns its shoot ID."),
             Release());
    c.def("addPlantInstance", &PlantArchitecture::addPlantInstance, py::arg("base_position"),
          py::arg("current_age"), docs::PlantArchitecture_addPlantInstance)
        .def("deletePlantInstance", &PlantArchitecture::deletePlantInstance, py::arg("plantID"),
             docs::PlantArchitecture_deletePlantInstance)
        .def(
            "addBaseStemShoot",
            [](PlantArchitecture& a, unsigned plant, unsigned nodes, AxisRotation rot, float radius,
               float lengthMax, float lengthScale, float leafScale, float taper,
               const std::string& type) {
                return a.addBaseStemShoot(plant, shootSpec(nodes, rot, radius, lengthMax,
                                                           lengthScale, leafScale, taper, type));
            },
            py::arg("plantID"), py::arg("current_node_number"),
            py::arg("base_rotation") = AxisRotation{}, py::arg("internode_radius") = 0.001f,
            py::arg("internode_length_max") = 0.02f,
            py::arg("internode_length_scale_factor_fraction") = 1.0f,
            py::arg("leaf_scale_factor_fraction") = 1.0f, py::arg("radius_taper") = 0.0f,
            py::arg("shoot_type_label"), docs::PlantArchitecture_addBaseStemShoot)
        .def(
            "appendShoot",
            [](PlantArchitecture& a, unsigned plant, unsigned parent, unsigned nodes,
               AxisRotation rot, float radius, float lengthMax, float lengthScale, float leafScale,
               float taper, const std::string& type) {
                return a.appendShoot(
                    plant, parent,
                    shootSpec(nodes, rot, radius, lengthMax, lengthScale, leafScale, taper, type));
            },
            py::arg("plantID"), py::arg("parent_shoot_ID"), py::arg("current_node_number"),
            py::arg("base_rotation") = AxisRotation{}, py::arg("internode_radius") = 0.001f,
            py::arg("internode_length_max") = 0.02f,
            py::arg("internode_length_scale_factor_fraction") = 1.0f,
            py::arg("leaf_scale_factor_fraction") = 1.0f, py::arg("radius_taper") = 0.0f,
            py::arg("shoot_type_label"), docs::PlantArchitecture_appendShoot)
        .def(
            "addChildShoot",
            [](PlantArchitecture& a, unsigned plant, unsigned parent, unsigned node, unsigned nodes,
               AxisRotation rot, float radius, float lengthMax, float lengthScale, float leafScale,
               float taper, const std::string& type, unsigned petiole) {
                return a.addChildShoot(
                    plant, parent, node,
                    shootSpec(nodes, rot, radius, lengthMax, lengthScale, leafScale, taper, type),
                    petiole);
            },
            py::arg("plantID"), py::arg("parent_shoot_ID"), py::arg("parent_node_index"),
            py::arg("current_node_number"), py::arg("shoot_base_rotation") = AxisRotation{},
            py::arg("internode_radius") = 0.001f, py::arg("internode_length_max") = 0.02f,
            py::arg("internode_length_scale_factor_fraction") = 1.0f,
            py::arg("leaf_scale_factor_fraction") = 1.0f, py::arg("radius_taper") = 0.0f,
            py::arg("shoot_type_label"), py::arg("petiole_index") = 0,
            inPython(
                docs::PlantArchitecture_addChildShoot,
                "A lateral shoot from the axil of a petiole at parent_node_index; returns its ID."))
        .def(
            "appendPhytomerToShoot",
            [](PlantArchitecture& a, unsigned plant, unsigned shoot, const PhytomerParameters& pp,
               float radius, float lengthMax, float lengthScale, float leafScale) {
                return a.appendPhytomerToShoot(plant, shoot, pp,
                                               {radius, lengthMax, lengthScale, leafScale});
            },
            py::arg("plantID"), py::arg("shootID"), py::arg("phytomer_parameters"),
            py::arg("internode_radius") = 0.001f, py::arg("internode_length_max") = 0.02f,
            py::arg("internode_length_scale_factor_fraction") = 1.0f,
            py::arg("leaf_scale_factor_fraction") = 1.0f,
            docs::PlantArchitecture_appendPhytomerToShoot)
        .def("addFloralBud", &PlantArchitecture::addFloralBud, py::arg("plantID"),
             py::arg("shootID"), py::arg("node"), py::arg("stage"), py::arg("petiole_index") = 0,
             docs::PlantArchitecture_addFloralBud)
        .def("pruneBranch", &PlantArchitecture::pruneBranch, py::arg("plantID"), py::arg("shootID"),
             py::arg("node_index"), docs::PlantArchitecture_pruneBranch)
        .def("removePlantLeaves", &PlantArchitecture::removePlantLeaves, py::arg("plantID"),
             docs::PlantArchitecture_removePlantLeaves)
        .def("removeShootLeaves", &PlantArchitecture::removeShootLeaves, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_removeShootLeaves)
        .def("removeShootVegetativeBuds", &PlantArchitecture::removeShootVegetativeBuds,
             py::arg("plantID"), py::arg("shootID"),
             docs::PlantArchitecture_removeShootVegetativeBuds)
        .def("removeShootAxillaryVegetativeBuds",
             &PlantArchitecture::removeShootAxillaryVegetativeBuds, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_removeShootAxillaryVegetativeBuds)
        .def("removeShootApex", &PlantArchitecture::removeShootApex, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_removeShootApex)
        .def("removeShootFloralBuds", &PlantArchitecture::removeShootFloralBuds, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_removeShootFloralBuds)
        .def("removePlantFlowers", &PlantArchitecture::removePlantFlowers, py::arg("plantID"),
             docs::PlantArchitecture_removePlantFlowers)
        .def("harvestPlant", &PlantArchitecture::harvestPlant, py::arg("plantID"),
             docs::PlantArchitecture_harvestPlant)
        .def("updateGeometry", &PlantArchitecture::updateGeometry, py::arg("plantID"),
             docs::PlantArchitecture_updateGeometry);
}

void bindGrowth(py::class_<PlantArchitecture>& c) {
    {
        // Its signature is written out (pybind11 would show *args, **kwargs to editors).
        py::options written;
        written.disable_function_signatures();
        c.def("advanceTime", &advanceTimeCall,
              inPython(
                  docs::PlantArchitecture_advanceTime,
                  "advanceTime(self, time_step_days: float, plantIDs: int | Sequence[int] | None = "
                  "None) -> None\n\n"
                  "Grows the plants by time_step_days (any split of the time gives the same "
                  "plants): every plant, or the plant or list of plants plantIDs names "
                  "(positionally or by keyword; dt and plant_id are read too). advanceTime(3, 2), "
                  "two whole numbers, reads two ways and raises plantarch.Error naming the keyword "
                  "call."));
    }
    c.def(
         "writeGrowthAnimation",
         [](PlantArchitecture& a, std::vector<unsigned> plants, double start, double end,
            double step, std::vector<std::string> filenames, double frameRate) {
             interruptible([&] {
                 writeGrowthAnimation(a, plants, {start, end, step}, filenames, {frameRate});
             });
         },
         py::arg("plantIDs"), py::arg("start"), py::arg("end"), py::arg("step"),
         py::arg("filenames"), py::arg("frame_rate") = 24.0,
         inPython(
             docs::writeGrowthAnimation,
             "Grows the plants from frame to frame (a frame every `step` days of growth from "
             "`start` to `end`) and writes the scene at each frame into every file (.glb, .gltf "
             "or .usda) as one animation that shows frame i alone at i / frame_rate seconds. "
             "The plants are left grown to the last frame."))
        .def(
            "setProgressCallback",
            [](PlantArchitecture& a, py::object fn) { setUserProgress(a, fn); },
            py::arg("callback"),
            inPython(docs::PlantArchitecture_setProgressCallback,
                     "callback(stage: str, fraction: float) is told how long calls progress (None: "
                     "none). Ctrl-C stops a long call between plants with KeyboardInterrupt."))
        .def("setPlantPhenologicalThresholds", &PlantArchitecture::setPlantPhenologicalThresholds,
             py::arg("plantID"), py::arg("thresholds"),
             docs::PlantArchitecture_setPlantPhenologicalThresholds)
        .def(
            "setPlantPhenologicalThresholds",
            [](PlantArchitecture& a, unsigned plant, float dormancyBreak, float initiation,
               float opening, float fruitSet, float maturity, float senescence, float lifespan,
               bool evergreen, py::object maxAge) {
                PhenologyParameters t = a.plant(plant).phenology;
                t.time_to_dormancy_break = dormancyBreak;
                t.time_to_flower_initiation = initiation;
                t.time_to_flower_opening = opening;
                t.time_to_fruit_set = fruitSet;
                t.time_to_fruit_maturity = maturity;
                t.time_to_senescence = senescence;
                t.max_leaf_lifespan = lifespan;
                t.evergreen = evergreen;
                if (!maxAge.is_none()) t.max_age = maxAge.cast<float>();
                a.setPlantPhenologicalThresholds(plant, t);
            },
            py::arg("plantID"), py::arg("time_to_dormancy_break"),
            py::arg("time_to_flower_initiation"), py::arg("time_to_flower_opening"),
            py::arg("time_to_fruit_set"), py::arg("time_to_fruit_maturity"),
            py::arg("time_to_senescence"), py::arg("max_leaf_lifespan") = 1e6f,
            py::arg("is_evergreen") = false, py::arg("max_age") = py::none(),
            inPython(docs::PlantArchitecture_setPlantPhenologicalThresholds,
                     "The specification's form, days (negative disables a stage)."))
        .def(
            "getPlantPhenologicalThresholds",
            [](const PlantArchitecture& a, unsigned plant) { return a.plant(plant).phenology; },
            py::arg("plantID"), "A copy of the plant's thresholds.")
        .def(
            "setPlantMaximumAge",
            [](PlantArchitecture& a, unsigned plant, float maxAge) {
                PhenologyParameters t = a.plant(plant).phenology;
                t.max_age = maxAge;
                a.setPlantPhenologicalThresholds(plant, t);
            },
            py::arg("plantID"), py::arg("max_age"), "The plant stops developing at max_age days.")
        .def("setDefaultPhenology", &PlantArchitecture::setDefaultPhenology, py::arg("thresholds"),
             docs::PlantArchitecture_setDefaultPhenology)
        .def("getDefaultPhenology", &PlantArchitecture::getDefaultPhenology,
             docs::PlantArchitecture_getDefaultPhenology)
        .def("getPhenologyStage", &PlantArchitecture::getPhenologyStage, py::arg("plantID"),
             docs::PlantArchitecture_getPhenologyStage)
        .def(
            "registerPhytomerCreationFunction",
            [](PlantArchitecture& a, const std::string& name, py::function fn) {
                a.registerPhytomerCreationFunction(name,
                                                   creationFunction(fn, callLockOf(a.context())));
            },
            py::arg("name"), py::arg("function"),
            inPython(
                docs::PlantArchitecture_registerPhytomerCreationFunction,
                "fn(ctx: PhytomerCreationContext) runs for every new phytomer of shoot types whose "
                "phytomer_creation_function names it (in species files too)."))
        .def(
            "registerPhytomerCallbackFunction",
            [](PlantArchitecture& a, const std::string& name, py::function fn) {
                a.registerPhytomerCallbackFunction(name,
                                                   callbackFunction(fn, callLockOf(a.context())));
            },
            py::arg("name"), py::arg("function"),
            "fn(ctx: PhytomerCallbackContext) runs for every phytomer at every whole day of "
            "plant age, for shoot types whose phytomer_callback_function names it.")
        .def(
            "registerLeafPrototype",
            [](PlantArchitecture& a, const std::string& name, py::function fn) {
                a.registerLeafPrototype(name, leafPrototypeFunction(fn, callLockOf(a.context())));
            },
            py::arg("name"), py::arg("function"),
            inPython(
                docs::PlantArchitecture_registerLeafPrototype,
                "fn(params: LeafPrototype, leafletIndex: int) returns the leaf in prototype units "
                "(length 1 along +x, base at the origin, +z up) as a Mesh or a list of (Mesh, "
                "Material); shoot types name it in leaf.prototype.prototype_function."))
        .def(
            "registerFloralPrototype",
            [](PlantArchitecture& a, const std::string& name, py::function fn) {
                a.registerFloralPrototype(name,
                                          floralPrototypeFunction(fn, callLockOf(a.context())));
            },
            py::arg("name"), py::arg("function"),
            "fn(request: FloralPrototypeRequest) returns a flower or fruit (length 1 along +x) "
            "as a Mesh or a list of (Mesh, Material); named in flower_prototype_function or "
            "fruit_prototype_function.")
        .def("hasLeafPrototype", &PlantArchitecture::hasLeafPrototype, py::arg("name"),
             docs::PlantArchitecture_hasLeafPrototype)
        .def("hasFloralPrototype", &PlantArchitecture::hasFloralPrototype, py::arg("name"),
             "Whether a flower or fruit prototype builder of that name is registered.");
}

void bindCollision(py::class_<PlantArchitecture>& c) {
    c.def(
         "enableSoftCollisionAvoidance",
         [](PlantArchitecture& a, float halfAngle, float lookAhead, unsigned rays, float inertia,
            bool internodes, bool petioles, bool peduncles, std::vector<ObjectID> objects,
            double interval) {
             SoftCollisionOptions o;
             o.cone = {halfAngle, lookAhead, rays, inertia};
             o.steerInternodes = internodes;
             o.steerPetioles = petioles;
             o.steerPeduncles = peduncles;
             o.objects = std::move(objects);
             o.updateInterval = interval;
             a.enableSoftCollisionAvoidance(o);
         },
         py::arg("cone_half_angle") = 80.0f, py::arg("look_ahead") = 0.1f, py::arg("rays") = 256u,
         py::arg("inertia") = 0.4f, py::arg("steer_internodes") = true,
         py::arg("steer_petioles") = false, py::arg("steer_peduncles") = false,
         py::arg("obstacle_objects") = std::vector<ObjectID>{}, py::arg("update_interval") = 1.0,
         inPython(
             docs::PlantArchitecture_enableSoftCollisionAvoidance,
             "Soft avoidance: new organs turn toward open space among plant organs and obstacles."))
        .def("disableSoftCollisionAvoidance", &PlantArchitecture::disableSoftCollisionAvoidance,
             docs::PlantArchitecture_disableSoftCollisionAvoidance)
        .def(
            "setCollisionRelevantOrgans",
            [](PlantArchitecture& a, bool internodes, bool leaves, bool petioles, bool flowers,
               bool fruit) {
                a.setCollisionRelevantOrgans(organs(internodes, leaves, petioles, flowers, fruit));
            },
            py::arg("include_internodes") = false, py::arg("include_leaves") = true,
            py::arg("include_petioles") = false, py::arg("include_flowers") = false,
            py::arg("include_fruit") = false, docs::PlantArchitecture_setCollisionRelevantOrgans)
        .def(
            "enableSolidObstacleAvoidance",
            [](PlantArchitecture& a, std::vector<ObjectID> obstacles, float distance,
               bool fruitAdjustment, bool clearance) {
                SolidObstacleOptions o;
                o.obstacles = std::move(obstacles);
                o.avoidanceDistance = distance;
                o.fruitAdjustment = fruitAdjustment;
                o.organClearance = clearance;
                a.enableSolidObstacleAvoidance(o);
            },
            py::arg("obstacle_objectIDs"), py::arg("avoidance_distance") = 0.2f,
            py::arg("enable_fruit_adjustment") = false, py::arg("organ_clearance") = true,
            docs::PlantArchitecture_enableSolidObstacleAvoidance)
        .def("disableSolidObstacleAvoidance", &PlantArchitecture::disableSolidObstacleAvoidance,
             docs::PlantArchitecture_disableSolidObstacleAvoidance)
        .def(
            "enableAttractionPoints",
            [](PlantArchitecture& a, py::object pts, float halfAngle, float lookAhead, float weight,
               std::vector<std::string> types, std::optional<unsigned> plant) {
                // The specification's weight (1: turn fully toward the point) is plantarch's
                // inertia read the other way round.
                if (!(weight >= 0.0f && weight <= 1.0f))
                    throw Error("attraction weight out of range",
                                {.parameter = "attraction_weight",
                                 .value = std::to_string(weight),
                                 .validRange = "0 (no attraction) to 1 (turn fully toward it)"});
                AttractionPoints ap{points(pts), halfAngle, lookAhead, 1.0f - weight,
                                    std::move(types)};
                if (plant)
                    a.enableAttractionPoints(*plant, ap);
                else
                    a.enableAttractionPoints(ap);
            },
            py::arg("attraction_points"), py::arg("view_half_angle_deg") = 80.0f,
            py::arg("look_ahead_distance") = 0.1f, py::arg("attraction_weight") = 0.6f,
            py::arg("shoot_types") = std::vector<std::string>{}, py::arg("plantID") = py::none(),
            inPython(docs::PlantArchitecture_enableAttractionPoints,
                     "Growing tips turn toward the nearest point in their cone (for every plant, "
                     "or one), "
                     "by attraction_weight: 0 not at all, 1 fully (AttractionPoints.inertia = 1 - "
                     "weight)."))
        .def(
            "updateAttractionPoints",
            [](PlantArchitecture& a, py::object pts, std::optional<unsigned> plant) {
                plant ? a.updateAttractionPoints(*plant, points(pts))
                      : a.updateAttractionPoints(points(pts));
            },
            py::arg("attraction_points"), py::arg("plantID") = py::none(),
            docs::PlantArchitecture_updateAttractionPoints)
        .def(
            "appendAttractionPoints",
            [](PlantArchitecture& a, py::object pts, std::optional<unsigned> plant) {
                plant ? a.appendAttractionPoints(*plant, points(pts))
                      : a.appendAttractionPoints(points(pts));
            },
            py::arg("attraction_points"), py::arg("plantID") = py::none(),
            docs::PlantArchitecture_appendAttractionPoints)
        .def(
            "disableAttractionPoints",
            [](PlantArchitecture& a, std::optional<unsigned> plant) {
                plant ? a.disableAttractionPoints(*plant) : a.disableAttractionPoints();
            },
            py::arg("plantID") = py::none(), docs::PlantArchitecture_disableAttractionPoints)
        .def("getAttractionPoints", &PlantArchitecture::getAttractionPoints, py::arg("plantID"),
             docs::PlantArchitecture_getAttractionPoints)
        .def(
            "getCollisionStats",
            [](const PlantArchitecture& a) { return statsDict(a.getCollisionStats()); },
            docs::PlantArchitecture_getCollisionStats)
        .def("resetCollisionStats", &PlantArchitecture::resetCollisionStats,
             docs::PlantArchitecture_resetCollisionStats);
}

void bindQueries(py::class_<PlantArchitecture>& c) {
    c.def("getAllPlantIDs", &PlantArchitecture::getAllPlantIDs,
          docs::PlantArchitecture_getAllPlantIDs)
        .def(
            "plant", [](const PlantArchitecture& a, unsigned plant) { return a.plant(plant); },
            py::arg("plantID"),
            inPython(
                docs::PlantArchitecture_plant,
                "A copy of the plant's whole state as it is now (read it; it stays valid whatever "
                "happens to the plant)."))
        .def("getPlantBasePosition", &PlantArchitecture::getPlantBasePosition, py::arg("plantID"),
             docs::PlantArchitecture_getPlantBasePosition)
        .def("getPlantAge", &PlantArchitecture::getPlantAge, py::arg("plantID"),
             docs::PlantArchitecture_getPlantAge)
        .def("getPlantHeight", &PlantArchitecture::getPlantHeight, py::arg("plantID"),
             docs::PlantArchitecture_getPlantHeight)
        .def("getPlantStemHeight", &PlantArchitecture::getPlantStemHeight, py::arg("plantID"),
             docs::PlantArchitecture_getPlantStemHeight)
        .def("getPlantLeafCount", &PlantArchitecture::getPlantLeafCount, py::arg("plantID"),
             docs::PlantArchitecture_getPlantLeafCount)
        .def("getPlantLeafArea", &PlantArchitecture::getPlantLeafArea, py::arg("plantID"),
             docs::PlantArchitecture_getPlantLeafArea)
        .def(
            "summarizePlant",
            [](const PlantArchitecture& a, unsigned plant) { return summarizePlant(a, plant); },
            py::arg("plantID"), docs::summarizePlant)
        .def("getPlantObjectIDs", &PlantArchitecture::getPlantObjectIDs, py::arg("plantID"),
             py::arg("organ"), docs::PlantArchitecture_getPlantObjectIDs)
        .def("getAllPlantObjectIDs", &PlantArchitecture::getAllPlantObjectIDs, py::arg("plantID"),
             docs::PlantArchitecture_getAllPlantObjectIDs)
        .def("getAllObjectIDs", &PlantArchitecture::getAllObjectIDs,
             docs::PlantArchitecture_getAllObjectIDs)
        .def("getShootCount", &PlantArchitecture::getShootCount, py::arg("plantID"),
             docs::PlantArchitecture_getShootCount)
        .def("getShootNodeCount", &PlantArchitecture::getShootNodeCount, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootNodeCount)
        .def("getShootParent", &PlantArchitecture::getShootParent, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootParent)
        .def("getShootRank", &PlantArchitecture::getShootRank, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootRank)
        .def("getShootChildren", &PlantArchitecture::getShootChildren, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootChildren)
        .def("getShootDescendants", &PlantArchitecture::getShootDescendants, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootDescendants)
        .def("getTerminalShoots", &PlantArchitecture::getTerminalShoots, py::arg("plantID"),
             docs::PlantArchitecture_getTerminalShoots)
        .def("getShootPathToRoot", &PlantArchitecture::getShootPathToRoot, py::arg("plantID"),
             py::arg("shootID"), docs::PlantArchitecture_getShootPathToRoot)
        .def("getNodePosition", &PlantArchitecture::getNodePosition, py::arg("plantID"),
             py::arg("shootID"), py::arg("node_index"), docs::PlantArchitecture_getNodePosition);
}

void bindFiles(py::class_<PlantArchitecture>& c) {
    c.def(
         "writePlantStructureXML",
         [](const PlantArchitecture& a, py::object plants, const std::string& file) {
             const std::vector<unsigned> ids = idList(plants, "plantID");
             py::gil_scoped_release release;
             a.writePlantStructureXML(ids, file);
         },
         py::arg("plantID"), py::arg("filename"),
         inPython(docs::PlantArchitecture_writePlantStructureXML,
                  "Writes one plant (an ID) or several (a list) as a plant structure XML file."))
        .def("getPlantStructureXML", &PlantArchitecture::getPlantStructureXML, py::arg("plantIDs"),
             docs::PlantArchitecture_getPlantStructureXML)
        .def(
            "writeHeliosPlantStructureXML",
            [](const PlantArchitecture& a, py::object plants, const std::string& file) {
                const std::vector<unsigned> ids = idList(plants, "plantID");
                py::gil_scoped_release release;
                writeHeliosPlantStructureXML(a, ids, file);
            },
            py::arg("plantID"), py::arg("filename"),
            inPython(
                docs::writeHeliosPlantStructureXML,
                "Writes one plant (an ID) or several (a list) as a <helios> plant structure file, "
                "the reference system's layout (docs/plant-xml.md)."))
        .def(
            "getHeliosPlantStructureXML",
            [](const PlantArchitecture& a, const std::vector<unsigned>& ids) {
                return getHeliosPlantStructureXML(a, ids);
            },
            py::arg("plantIDs"), docs::getHeliosPlantStructureXML)
        .def(
            "readPlantStructureXML",
            [](PlantArchitecture& a, const std::string& file, py::object warnings) {
                const PlantStructureReadOptions options = readOptions(warnings);
                py::gil_scoped_release release;
                return a.readPlantStructureXML(file, options);
            },
            py::arg("filename"), py::arg("warnings") = py::none(),
            inPython(docs::PlantArchitecture_readPlantStructureXML,
                     "Adds the plants of a file; returns their IDs. `warnings`: a list that "
                     "receives one "
                     "line per plant whose file left values out."))
        .def(
            "readPlantStructureXMLString",
            [](PlantArchitecture& a, const std::string& xml, py::object warnings) {
                return a.readPlantStructureXMLString(xml, readOptions(warnings));
            },
            py::arg("xml"), py::arg("warnings") = py::none(),
            docs::PlantArchitecture_readPlantStructureXMLString)
        .def(
            "getPlantString",
            [](const PlantArchitecture& a, unsigned plant, int digits) {
                return a.getPlantString(plant, {digits});
            },
            py::arg("plantID"), py::arg("significant_digits") = 4,
            docs::PlantArchitecture_getPlantString)
        .def(
            "generatePlantFromString",
            [](PlantArchitecture& a, const std::string& s) { return a.generatePlantFromString(s); },
            py::arg("plant_string"), docs::PlantArchitecture_generatePlantFromString);
}

}  // namespace

// Copies, moves, water sprouts, seasons by hand, ground clipping and organ geometry.
void bindPlantEdits(py::class_<PlantArchitecture>& c) {
    c.def("duplicatePlantInstance", &PlantArchitecture::duplicatePlantInstance, py::arg("plantID"),
          py::arg("base_position"), py::arg("base_rotation") = AxisRotation{}, py::arg("age"),
          docs::PlantArchitecture_duplicatePlantInstance, Release())
        .def("setPlantBasePosition", &PlantArchitecture::setPlantBasePosition, py::arg("plantID"),
             py::arg("base_position"), docs::PlantArchitecture_setPlantBasePosition, Release())
        .def("getPlantName", &PlantArchitecture::getPlantName, py::arg("plantID"),
             docs::PlantArchitecture_getPlantName)
        .def(
            "addEpicormicShoot",
            [](PlantArchitecture& a, unsigned plant, unsigned parent, float position,
               unsigned nodes, AxisRotation rot, float radius, float lengthMax, float lengthScale,
               float leafScale, float taper, const std::string& type) {
                return a.addEpicormicShoot(
                    plant, parent, position,
                    shootSpec(nodes, rot, radius, lengthMax, lengthScale, leafScale, taper, type));
            },
            py::arg("plantID"), py::arg("parent_shoot_ID"), py::arg("parent_position_fraction"),
            py::arg("current_node_number"), py::arg("base_rotation") = AxisRotation{},
            py::arg("internode_radius") = 0.001f, py::arg("internode_length_max") = 0.02f,
            py::arg("internode_length_scale_factor_fraction") = 1.0f,
            py::arg("leaf_scale_factor_fraction") = 1.0f, py::arg("radius_taper") = 0.0f,
            py::arg("shoot_type_label"),
            inPython(docs::PlantArchitecture_addEpicormicShoot,
                     "A water sprout from the wood of a shoot at a fraction (0, 1] of its length, "
                     "upright "
                     "(base_rotation.pitch from the vertical); returns its shoot ID."),
            Release())
        .def("enableEpicormicChildShoots", &PlantArchitecture::enableEpicormicChildShoots,
             py::arg("plantID"), py::arg("epicormic_shoot_type_label"),
             py::arg("epicormic_probability_perlength_perday"),
             inPython(
                 docs::PlantArchitecture_enableEpicormicChildShoots,
                 "Water sprouts as the plant grows: each day each shoot grows one with probability "
                 "rate x its length x the vertical part of its axis at a random point (0: off)."))
        .def("makePlantDormant", &PlantArchitecture::makePlantDormant, py::arg("plantID"),
             docs::PlantArchitecture_makePlantDormant, Release())
        .def("breakPlantDormancy", &PlantArchitecture::breakPlantDormancy, py::arg("plantID"),
             docs::PlantArchitecture_breakPlantDormancy, Release())
        .def("isPlantDormant", &PlantArchitecture::isPlantDormant, py::arg("plantID"),
             docs::PlantArchitecture_isPlantDormant)
        .def("enableGroundClipping", &PlantArchitecture::enableGroundClipping,
             py::arg("ground_height") = 0.0f, docs::PlantArchitecture_enableGroundClipping,
             Release())
        .def("disableGroundClipping", &PlantArchitecture::disableGroundClipping,
             "Turns ground clipping off.")
        .def("getGroundClipping", &PlantArchitecture::getGroundClipping,
             docs::PlantArchitecture_getGroundClipping)
        .def("setOrganGeometry", &PlantArchitecture::setOrganGeometry, py::arg("organ"),
             py::arg("build"), docs::PlantArchitecture_setOrganGeometry, Release())
        .def("getOrganGeometry", &PlantArchitecture::getOrganGeometry, py::arg("organ"),
             "Whether organs of that OrganKind get geometry.")
        .def("sumPlantLeafArea", &PlantArchitecture::sumPlantLeafArea, py::arg("plantIDs"),
             docs::PlantArchitecture_sumPlantLeafArea);
    // The per-organ object lists as the model specification names them: one call each.
    struct OrganList {
        const char* name;
        std::vector<OrganKind> kinds;
        const char* doc;
    };
    const OrganList lists[] = {
        {"getPlantInternodeObjectIDs", {OrganKind::Internode}, "Internode objects of a plant."},
        {"getPlantPetioleObjectIDs", {OrganKind::Petiole}, "Petiole objects of a plant."},
        {"getPlantLeafObjectIDs", {OrganKind::Leaf}, "Leaf objects of a plant."},
        {"getPlantPeduncleObjectIDs", {OrganKind::Peduncle}, "Peduncle objects of a plant."},
        {"getPlantFlowerObjectIDs",
         {OrganKind::FlowerClosed, OrganKind::FlowerOpen},
         "Flower objects of a plant, closed and open."},
        {"getPlantFruitObjectIDs", {OrganKind::Fruit}, "Fruit objects of a plant."},
    };
    for (const OrganList& list : lists)
        c.def(
            list.name,
            [kinds = list.kinds](const PlantArchitecture& a, unsigned plant) {
                std::vector<ObjectID> ids;
                for (OrganKind k : kinds) {
                    const std::vector<ObjectID> some = a.getPlantObjectIDs(plant, k);
                    ids.insert(ids.end(), some.begin(), some.end());
                }
                return ids;
            },
            py::arg("plantID"), list.doc);
}

void bindSummary(py::module_& m) {
    py::class_<PlantSummary>(
        m, "PlantSummary", "One plant's statistics at a glance (PlantArchitecture.summarizePlant)")
        .def_readonly("height", &PlantSummary::height, "top of the plant above its base (m)")
        .def_readonly("leafArea", &PlantSummary::leafArea, "one-sided leaf area (m^2)")
        .def_readonly("leaves", &PlantSummary::leaves, "leaf objects (each leaflet one)")
        .def_readonly("widthX", &PlantSummary::widthX, "width of the plant's box along x (m)")
        .def_readonly("widthY", &PlantSummary::widthY, "width of the plant's box along y (m)")
        .def_readonly("widthLong", &PlantSummary::widthLong,
                      "largest horizontal extent over every whole degree of direction (m)")
        .def_readonly("widthShort", &PlantSummary::widthShort,
                      "horizontal extent square to widthLong's direction (m)")
        .def_readonly("flowers", &PlantSummary::flowers, "flowers drawn")
        .def_readonly("fruit", &PlantSummary::fruit, "fruit drawn")
        .def_readonly("shootsByRank", &PlantSummary::shootsByRank, "shoots of rank 0, 1, ...")
        .def_readonly("phytomersByRank", &PlantSummary::phytomersByRank,
                      "phytomers of the shoots of rank 0, 1, ...")
        .def_readonly("mainNodes", &PlantSummary::mainNodes, "phytomers of the main shoot")
        .def_readonly("leafInclination", &PlantSummary::leafInclination,
                      "fraction of the leaf area inclined 0-10, 10-20, ... 80-90 degrees from "
                      "horizontal")
        .def_readonly("triangles", &PlantSummary::triangles, "triangles of every organ")
        .def("__repr__", [](const PlantSummary& s) {
            return "<PlantSummary height=" + std::to_string(s.height) +
                   " leaves=" + std::to_string(s.leaves) + ">";
        });
}

void bindArchitecture(py::module_& m) {
    bindSummary(m);
    py::class_<PlantArchitecture> c(
        m, "PlantArchitecture",
        "Builds plants from shoot types and keeps their geometry in a Context. Method names "
        "follow the model specification.");
    bindWithBlock(c, "the PlantArchitecture");
    c.def(py::init([](Context* context) {
              auto a = std::make_unique<PlantArchitecture>(context);
              setUserProgress(*a, py::none());  // watches for Ctrl-C
              return a;
          }),
          py::arg("context"), py::keep_alive<1, 2>(),
          "Plants are built into `context` (kept alive as long as this object).")
        .def("getContext", py::overload_cast<>(&PlantArchitecture::context),
             py::return_value_policy::reference_internal,
             "The Context the plants' geometry lives in.")
        .def("setSeed", &PlantArchitecture::setSeed, py::arg("seed"),
             docs::PlantArchitecture_setSeed)
        .def("context", py::overload_cast<>(&PlantArchitecture::context),
             py::return_value_policy::reference_internal, docs::PlantArchitecture_context)
        .def("seed", &PlantArchitecture::seed, "Seed of the scene (the same as getSeed).")
        .def("shootType", &PlantArchitecture::shootType, py::arg("shoot_type_label"),
             inPython(docs::PlantArchitecture_shootType,
                      "A copy of a defined shoot type's parameters (the same as getShootType)."))
        .def("getSeed", &PlantArchitecture::seed, "Seed of the scene.");
    bindLibrary(c);
    bindShootTypes(c);
    bindShootSpec(m);
    bindManual(c);
    bindGrowth(c);
    bindCollision(c);
    bindQueries(c);
    bindFiles(c);
    bindPlantEdits(c);
}

}  // namespace plantarch::python
