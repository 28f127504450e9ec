// Weather, the sun, the light model and leaf photosynthesis (plantarch/Light.h,
// plantarch/Photosynthesis.h); light results as numpy arrays.

#include "plantarch/Light.h"

#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"
#include "plantarch/Photosynthesis.h"

namespace plantarch::python {

namespace {

// A numpy array viewing one vector of a result kept alive by `owner`.
py::array_t<float> view(std::vector<float>& v, py::handle owner) {
    return py::array_t<float>({v.size()}, {sizeof(float)}, v.data(), owner);
}

py::dict resultArrays(LightResult&& r) {
    auto* owned = new LightResult(std::move(r));
    py::capsule owner(owned, [](void* p) { delete static_cast<LightResult*>(p); });
    py::dict out;
    out["absorbed"] = view(owned->absorbed, owner);
    out["sunlit"] = view(owned->sunlit, owner);
    out["incident"] = view(owned->incident, owner);
    out["absorbed_direct"] = view(owned->absorbedDirect, owner);
    return out;
}

LightResult resultFrom(const py::dict& d) {
    LightResult r;
    const auto column = [&](const char* name) {
        if (!d.contains(name))
            throw Error("a light result needs its arrays",
                        {.parameter = "result",
                         .value = "no " + std::string(name),
                         .validRange = "the dict LightModel.compute returns"});
        return d[name].cast<std::vector<float>>();
    };
    r.absorbed = column("absorbed");
    r.sunlit = column("sunlit");
    r.incident = column("incident");
    r.absorbedDirect = column("absorbed_direct");
    return r;
}

// A UTCTime, or its text (read strictly: a bad one is a plantarch.Error, not a TypeError).
UTCTime timeOf(py::handle value) {
    if (py::isinstance<py::str>(value)) return parseUTCTime(value.cast<std::string>());
    return value.cast<UTCTime>();
}

}  // namespace

void bindLight(py::module_& m) {
    py::class_<UTCTime>(m, "UTCTime", "A moment in Coordinated Universal Time.")
        .def(py::init([](const std::string& text) { return parseUTCTime(text); }), py::arg("text"),
             inPython(docs::parseUTCTime, "Made from its text."))
        .def_readwrite("year", &UTCTime::year, "1900 to 2100")
        .def_readwrite("month", &UTCTime::month, "1 to 12")
        .def_readwrite("day", &UTCTime::day, "1 to the month's length")
        .def_readwrite("hour", &UTCTime::hour, "0 to 24, fractional")
        .def("__str__", [](const UTCTime& t) { return formatUTCTime(t); })
        .def("__repr__", [](const UTCTime& t) { return "UTCTime('" + formatUTCTime(t) + "')"; });
    py::class_<SunPosition>(m, "SunPosition", "Where the sun stands (degrees).")
        .def(py::init<>(), "The sun at the zenith.")
        .def_readwrite("elevation", &SunPosition::elevation, "above the horizon, degrees")
        .def_readwrite("azimuth", &SunPosition::azimuth, "clockwise from north, degrees")
        .def("direction", &SunPosition::direction, docs::SunPosition_direction);
    m.def(
        "sunPosition",
        [](double latitude, double longitude, py::handle when) {
            return sunPosition({latitude, longitude}, timeOf(when));
        },
        py::arg("latitude"), py::arg("longitude"), py::arg("time"),
        inPython(docs::sunPosition, "`time` is a UTCTime or its text, \"2026-06-21T20:00Z\"."));
    m.def("erbsDiffuseFraction", &erbsDiffuseFraction, py::arg("clearness_index"),
          docs::erbsDiffuseFraction);
    py::class_<WeatherHour>(m, "WeatherHour", "One interval of weather.")
        .def(py::init<>())
        .def_readwrite("time", &WeatherHour::time, "the middle of the interval, UTC")
        .def_readwrite("par", &WeatherHour::par, "PAR on a horizontal surface, µmol m-2 s-1")
        .def_readwrite("diffuseFraction", &WeatherHour::diffuseFraction,
                       "diffuse share of par; negative: Erbs model")
        .def_readwrite("airTemperature", &WeatherHour::airTemperature, "°C")
        .def_readwrite("relativeHumidity", &WeatherHour::relativeHumidity,
                       "%, negative when not given")
        .def_readwrite("vpd", &WeatherHour::vpd, "kPa, negative when not given")
        .def_readwrite("co2", &WeatherHour::co2, "ppm, negative when not given")
        .def_readwrite("wind", &WeatherHour::wind, "m s-1, negative when not given");
    m.def("readWeatherFile", &readWeatherFile, py::arg("path"), docs::readWeatherFile);
    m.def(
        "clearSkyDay",
        [](double latitude, double longitude, py::handle day, double clearness, double tMin,
           double tMax) {
            const UTCTime date = timeOf(day);
            return clearSkyDay({latitude, longitude}, date.year, date.month, date.day, clearness,
                               tMin, tMax);
        },
        py::arg("latitude"), py::arg("longitude"), py::arg("date"), py::arg("clearness") = 0.75,
        py::arg("t_min") = 15.0, py::arg("t_max") = 28.0,
        inPython(docs::clearSkyDay, "`date` is a UTCTime or its text, \"2026-06-21\"."));
    py::class_<SkyLight>(m, "SkyLight", "The light of one weather interval, split.")
        .def(py::init<>())
        .def_readwrite("sun", &SkyLight::sun, "the sun's position")
        .def_readwrite("directNormal", &SkyLight::directNormal, "PAR on a surface facing the sun")
        .def_readwrite("diffuseHorizontal", &SkyLight::diffuseHorizontal,
                       "sky PAR on a horizontal surface");
    m.def(
        "skyLight",
        [](double latitude, double longitude, const WeatherHour& hour) {
            return skyLight({latitude, longitude}, hour);
        },
        py::arg("latitude"), py::arg("longitude"), py::arg("hour"), docs::skyLight);
    py::class_<SurfaceOptics>(m, "SurfaceOptics", "Shares of PAR reflected and transmitted.")
        .def(py::init<float, float>(), py::arg("reflectance") = 0.0f,
             py::arg("transmittance") = 0.0f)
        .def_readwrite("reflectance", &SurfaceOptics::reflectance, "share reflected, 0 to 1")
        .def_readwrite("transmittance", &SurfaceOptics::transmittance, "share transmitted, 0 to 1");
    py::class_<LightOptions>(m, "LightOptions", "Rays and optics of the light model.")
        .def(py::init<>())
        .def_readwrite("directRays", &LightOptions::directRays, "rays per triangle toward the sun")
        .def_readwrite("diffuseRays", &LightOptions::diffuseRays, "rays per triangle to the sky")
        .def_readwrite("scatterRays", &LightOptions::scatterRays,
                       "rays per triangle for scattered light")
        .def_readwrite("scatteringOrders", &LightOptions::scatteringOrders, "0 or 1")
        .def_readwrite("leaf", &LightOptions::leaf, "leaves' optics")
        .def_readwrite("stem", &LightOptions::stem, "internodes, petioles, peduncles")
        .def_readwrite("flowerAndFruit", &LightOptions::flowerAndFruit, "flowers and fruit")
        .def_readwrite("ground", &LightOptions::ground, "objects with organ ground")
        .def_readwrite("other", &LightOptions::other, "obstacles, trellises, the rest")
        .def_readwrite("seed", &LightOptions::seed, "the rays' jitter")
        .def_readwrite("samplesPerObject", &LightOptions::samplesPerObject,
                       "cast each object's rays from N of its triangles (0: every triangle)");
    py::class_<LightModel>(m, "LightModel", "The visible triangles of a Context, for light.")
        .def(py::init([](const Context& c, const LightOptions& o) {
                 py::gil_scoped_release release;
                 return std::make_unique<LightModel>(c, o);
             }),
             py::arg("context"), py::arg("options") = LightOptions{}, docs::LightModel_LightModel)
        .def(
            "compute",
            [](const LightModel& model, const SkyLight& sky) {
                LightResult r;
                {
                    py::gil_scoped_release release;
                    r = model.compute(sky);
                }
                return resultArrays(std::move(r));
            },
            py::arg("sky"),
            inPython(docs::LightModel_compute,
                     "As numpy arrays, one value per triangle: absorbed, sunlit, incident and "
                     "absorbed_direct."))
        .def("primitives", &LightModel::primitives, docs::LightModel_primitives)
        .def("objects", &LightModel::objects, docs::LightModel_objects)
        .def("areas", &LightModel::areas, docs::LightModel_areas)
        .def("triangleCount", &LightModel::triangleCount, docs::LightModel_triangleCount)
        .def("sampleCount", &LightModel::sampleCount, docs::LightModel_sampleCount)
        .def("raysCast", &LightModel::raysCast, docs::LightModel_raysCast);
    m.def(
        "writeLightData",
        [](Context& c, const LightModel& model, const py::dict& result) {
            writeLightData(c, model, resultFrom(result));
        },
        py::arg("context"), py::arg("model"), py::arg("result"), docs::writeLightData);

    py::class_<FarquharParameters>(m, "FarquharParameters",
                                   "The C3 photosynthesis model's parameters (defaults: a crop "
                                   "leaf).")
        .def(py::init<>())
        .def_readwrite("vcmax25", &FarquharParameters::vcmax25, "µmol m-2 s-1 at 25 °C")
        .def_readwrite("jmax25", &FarquharParameters::jmax25, "µmol m-2 s-1 at 25 °C")
        .def_readwrite("rd25", &FarquharParameters::rd25, "day respiration at 25 °C")
        .def_readwrite("quantumYield", &FarquharParameters::quantumYield,
                       "electrons per absorbed photon")
        .def_readwrite("curvature", &FarquharParameters::curvature, "theta of the light response")
        .def_readwrite("ciOverCa", &FarquharParameters::ciOverCa, "intercellular over ambient CO2")
        .def_readwrite("oxygen", &FarquharParameters::oxygen, "mmol mol-1");
    py::class_<LightResponseParameters>(m, "LightResponseParameters",
                                        "A non-rectangular light-response hyperbola.")
        .def(py::init<>())
        .def_readwrite("alpha", &LightResponseParameters::alpha, "initial slope")
        .def_readwrite("pmax", &LightResponseParameters::pmax, "light-saturated gross rate")
        .def_readwrite("curvature", &LightResponseParameters::curvature, "theta, 0 to 1")
        .def_readwrite("respiration", &LightResponseParameters::respiration, "µmol m-2 s-1");
    py::class_<LeafPhotosynthesis>(m, "LeafPhotosynthesis", "One leaf's rates, µmol m-2 s-1.")
        .def_readonly("gross", &LeafPhotosynthesis::gross, "carboxylation, µmol m-2 s-1")
        .def_readonly("net", &LeafPhotosynthesis::net, "gross - respiration")
        .def_readonly("respiration", &LeafPhotosynthesis::respiration, "day respiration")
        .def_readonly("lightLimited", &LeafPhotosynthesis::lightLimited,
                      "electron transport sets the rate");
    m.def("farquhar", &farquhar, py::arg("parameters"), py::arg("absorbed_par"),
          py::arg("leaf_temperature"), py::arg("co2") = 420.0, docs::farquhar);
    m.def("farquharSunlitShaded", &farquharSunlitShaded, py::arg("parameters"), py::arg("absorbed"),
          py::arg("absorbed_direct"), py::arg("sunlit_fraction"), py::arg("leaf_temperature"),
          py::arg("co2") = 420.0, docs::farquharSunlitShaded);
    m.def("lightResponse", &lightResponse, py::arg("parameters"), py::arg("absorbed_par"),
          docs::lightResponse);
}

}  // namespace plantarch::python
