// The carbohydrate budget and nitrogen model (plantarch/Physiology.h): PlantArchitecture's
// physiology methods, growPhysiology, and the records as numpy arrays by column.

#include "plantarch/Physiology.h"

#include <map>
#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::python {

namespace {

// Records as one numpy array per column (physiologyColumns), in record order.
py::dict recordArrays(const std::vector<PhysiologyRecord>& records) {
    const std::vector<std::string> columns = physiologyColumns();
    std::vector<py::array_t<double>> arrays;
    for (std::size_t c = 0; c < columns.size(); ++c)
        arrays.emplace_back(py::ssize_t(records.size()));
    for (std::size_t r = 0; r < records.size(); ++r) {
        const std::vector<double> values = physiologyValues(records[r]);
        for (std::size_t c = 0; c < columns.size(); ++c)
            arrays[c].mutable_at(py::ssize_t(r)) = values[c];
    }
    py::dict out;
    for (std::size_t c = 0; c < columns.size(); ++c) out[columns[c].c_str()] = arrays[c];
    return out;
}

// The `location` of options and seasons as Python's (latitude, longitude) pair.
constexpr const char* kLocationDoc = "(latitude, longitude) in degrees, north and east positive";
template <class T>
py::tuple locationOf(const T& t) {
    return py::make_tuple(t.location.latitude, t.location.longitude);
}
template <class T>
void setLocation(T& t, std::pair<double, double> where) {
    t.location = {where.first, where.second};
}

}  // namespace

void bindPhysiology(py::module_& m) {
    py::class_<PhysiologyOptions>(
        m, "PhysiologyOptions", "How growPhysiology lights the scene and turns light into carbon.")
        .def(py::init<>())
        .def_property("location", &locationOf<PhysiologyOptions>, &setLocation<PhysiologyOptions>,
                      kLocationDoc)
        .def_readwrite("light", &PhysiologyOptions::light, "rays and optics (LightOptions)")
        .def_readwrite("lightEvery", &PhysiologyOptions::lightEvery,
                       "trace the sky every N hours of daylight (1 to 24)")
        .def_readwrite("co2", &PhysiologyOptions::co2, "umol/mol where the weather gives none");
    m.def("physiologyColumns", &physiologyColumns, docs::physiologyColumns);
    py::class_<Fertilisation>(
        m, "Fertilisation", "Nitrogen added to each plant's available pool once it reaches an age.")
        .def(py::init([](double age, double grams) {
                 return Fertilisation{age, grams};
             }),
             py::arg("age"), py::arg("grams"))
        .def_readwrite("age", &Fertilisation::age, "days, >= 0")
        .def_readwrite("grams", &Fertilisation::grams, "g N per plant, > 0")
        .def("__repr__", [](const Fertilisation& f) {
            return "Fertilisation(age=" + py::repr(py::float_(f.age)).cast<std::string>() +
                   ", grams=" + py::repr(py::float_(f.grams)).cast<std::string>() + ")";
        });
    py::class_<PhysiologySeason>(
        m, "PhysiologySeason",
        "A season for growPhysiologySeason: models, place, weather or clear days, fertilisation.")
        .def(py::init<>())
        .def_readwrite("carbon", &PhysiologySeason::carbon, "the carbohydrate budget")
        .def_readwrite("nitrogen", &PhysiologySeason::nitrogen, "the nitrogen model")
        .def_property("location", &locationOf<PhysiologySeason>, &setLocation<PhysiologySeason>,
                      kLocationDoc)
        .def_readwrite("weather", &PhysiologySeason::weather,
                       "WeatherHour list (consecutive dates); empty: clear days from start")
        .def_readwrite("start", &PhysiologySeason::start, "the first clear day (UTCTime)")
        .def_readwrite("clearness", &PhysiologySeason::clearness, "of the clear days, 0 to 1")
        .def_readwrite("fertilise", &PhysiologySeason::fertilise, "Fertilisation list")
        .def_readwrite("lightEvery", &PhysiologySeason::lightEvery,
                       "trace the sky every N hours of daylight (1 to 24)");
    m.def("checkPhysiologySeason", &checkPhysiologySeason, py::arg("season"),
          docs::checkPhysiologySeason);
    m.def(
        "growPhysiologySeason",
        [](PlantArchitecture& arch, const std::vector<unsigned>& plants,
           const PhysiologySeason& season, unsigned days) {
            std::vector<PhysiologyRecord> records;
            {
                py::gil_scoped_release release;
                records = growPhysiologySeason(arch, plants, season, days);
            }
            return recordArrays(records);
        },
        py::arg("architecture"), py::arg("plants"), py::arg("season"), py::arg("days"),
        inPython(docs::growPhysiologySeason,
                 "The records as a dict of numpy arrays, one per column (physiologyColumns())."));
    m.def(
        "growPhysiology",
        [](PlantArchitecture& arch, const std::vector<WeatherHour>& weather,
           const PhysiologyOptions& options) {
            std::vector<PhysiologyRecord> records;
            {
                py::gil_scoped_release release;
                records = growPhysiology(arch, weather, options);
            }
            return recordArrays(records);
        },
        py::arg("architecture"), py::arg("weather"), py::arg("options") = PhysiologyOptions{},
        inPython(docs::growPhysiology,
                 "The records as a dict of numpy arrays, one per column (physiologyColumns())."));
    m.def(
        "writePhysiologyCSV",
        [](const std::string& path, PlantArchitecture& arch, unsigned plantID) {
            writePhysiologyCSV(path, arch.getPhysiologyRecords(plantID));
        },
        py::arg("path"), py::arg("architecture"), py::arg("plant_id"),
        inPython(docs::writePhysiologyCSV, "Writes the records of one plant of `architecture`."));

    auto cls = py::reinterpret_borrow<py::class_<PlantArchitecture>>(m.attr("PlantArchitecture"));
    cls.def("enableCarbohydrateModel", &PlantArchitecture::enableCarbohydrateModel,
            py::arg("plant_id"), docs::PlantArchitecture_enableCarbohydrateModel)
        .def("enableNitrogenModel", &PlantArchitecture::enableNitrogenModel, py::arg("plant_id"),
             docs::PlantArchitecture_enableNitrogenModel)
        .def("hasCarbohydrateModel", &PlantArchitecture::hasCarbohydrateModel, py::arg("plant_id"),
             docs::PlantArchitecture_hasCarbohydrateModel)
        .def("hasNitrogenModel", &PlantArchitecture::hasNitrogenModel, py::arg("plant_id"),
             docs::PlantArchitecture_hasNitrogenModel)
        .def("addPlantNitrogen", &PlantArchitecture::addPlantNitrogen, py::arg("plant_id"),
             py::arg("grams"), docs::PlantArchitecture_addPlantNitrogen)
        .def("addLeafPhotosynthesis", &PlantArchitecture::addLeafPhotosynthesis,
             py::arg("net_rates"), py::arg("hours"),
             inPython(docs::PlantArchitecture_addLeafPhotosynthesis,
                      "`net_rates` is a dict {leaf object ID: umol m-2 s-1}."))
        .def("setAirTemperature", &PlantArchitecture::setAirTemperature, py::arg("celsius"),
             docs::PlantArchitecture_setAirTemperature)
        .def("addAbsorbedLight", &PlantArchitecture::addAbsorbedLight, py::arg("plant_id"),
             py::arg("mol_photons"), docs::PlantArchitecture_addAbsorbedLight)
        .def(
            "getPhysiologyRecords",
            [](const PlantArchitecture& a, unsigned plantID) {
                return recordArrays(a.getPhysiologyRecords(plantID));
            },
            py::arg("plant_id"),
            inPython(docs::PlantArchitecture_getPhysiologyRecords,
                     "As a dict of numpy arrays, one per column (physiologyColumns())."));
}

}  // namespace plantarch::python
