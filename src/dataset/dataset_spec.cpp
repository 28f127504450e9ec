// Reading dataset spec files (JSON): every field checked, each error one line naming the
// file, the field as a JSON pointer without its leading slash, the value and the valid range.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/input_file.h"
#include "core/value_text.h"
#include "dataset/dataset_internal.h"
#include "plantarch/Error.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/SpeciesIO.h"
#include "project/json_document.h"
#include "project/json_fields.h"

namespace plantarch {

namespace {

using json = nlohmann::json;
using Reader = project::JSONFields;

constexpr std::size_t kMaxChoices = 10000;
constexpr std::size_t kMaxSpecies = 1000;
constexpr std::size_t kMaxPathPoints = 100000;

std::string at(const std::string& field, const std::string& key) {
    return Reader::join(field, key);
}

// A Draw from a number, [lo, hi], {"uniform": [lo, hi]}, {"normal": [mean, sd]} or
// {"choice": [...], "weights": [...]}, every value within `r`.
Draw readDraw(const Reader& rd, const json& j, const std::string& field, const Range& r) {
    Draw d;
    d.whole = r.whole;
    d.lo = r.lo;
    d.hi = r.hi;
    const std::string forms =
        "a number, [lo, hi], {\"uniform\": [lo, hi]}, {\"normal\": [mean, "
        "sd]} or {\"choice\": [...], \"weights\": [...]}";
    auto value = [&](const json& v, const std::string& f) {
        return double(rd.number(v, f, r.lo, r.hi, r.text, r.loOpen, r.whole, r.hiOpen));
    };
    auto bounds = [&](const json& v, const std::string& f) {
        if (!v.is_array() || v.size() != 2) rd.fail(f, "expected [lo, hi]", &v, r.text);
        d.kind = Draw::Kind::Uniform;
        d.a = value(v[0], at(f, "0"));
        d.b = value(v[1], at(f, "1"));
        if (d.b < d.a) rd.fail(f, "lo is above hi", &v, "lo <= hi, each " + r.text);
    };
    if (j.is_number()) {
        d.a = d.b = value(j, field);
        return d;
    }
    if (j.is_array()) {
        bounds(j, field);
        return d;
    }
    if (!j.is_object() || j.size() == 0) rd.fail(field, "expected a value to draw", &j, forms);
    if (j.contains("uniform")) {
        rd.object(j, field, {"uniform"});
        bounds(j["uniform"], at(field, "uniform"));
    } else if (j.contains("normal")) {
        rd.object(j, field, {"normal"});
        const std::string f = at(field, "normal");
        const json& v = j["normal"];
        if (!v.is_array() || v.size() != 2) rd.fail(f, "expected [mean, sd]", &v);
        d.kind = Draw::Kind::Normal;
        d.a = value(v[0], at(f, "0"));
        d.b = rd.number(v[1], at(f, "1"), 0, 1e30, "a standard deviation >= 0");
        if (r.whole)
            rd.fail(f, "a normal cannot draw whole numbers", nullptr, "[lo, hi] or choice");
    } else if (j.contains("choice")) {
        rd.object(j, field, {"choice", "weights"});
        const std::string f = at(field, "choice");
        const json& v = j["choice"];
        if (!v.is_array() || v.empty() || v.size() > kMaxChoices)
            rd.fail(f, "expected a list of 1 to 10000 values", &v);
        d.kind = Draw::Kind::Choice;
        for (std::size_t i = 0; i < v.size(); ++i)
            d.values.push_back(value(v[i], at(f, std::to_string(i))));
        if (j.contains("weights")) {
            const std::string fw = at(field, "weights");
            const json& w = j["weights"];
            if (!w.is_array() || w.size() != v.size())
                rd.fail(fw, "expected one weight per choice", &w,
                        std::to_string(v.size()) + " numbers >= 0");
            double sum = 0.0;
            for (std::size_t i = 0; i < w.size(); ++i) {
                d.weights.push_back(rd.number(w[i], at(fw, std::to_string(i)), 0, 1e30, ">= 0"));
                sum += d.weights.back();
            }
            if (!(sum > 0.0)) rd.fail(fw, "the weights sum to 0", nullptr, "a sum above 0");
        }
    } else {
        rd.object(j, field, {"uniform", "normal", "choice"});
    }
    return d;
}

Range wholeRange(double lo, double hi) {
    return {lo, hi,
            "whole numbers " + std::to_string(std::int64_t(lo)) + " to " +
                std::to_string(std::int64_t(hi)),
            false, true};
}

double readWeight(const Reader& rd, const json& j, const std::string& field) {
    if (!j.contains("weight")) return 1.0;
    return rd.number(j["weight"], at(field, "weight"), 0, 1e6, "> 0 to 1000000", true);
}

std::map<std::string, Draw> readDrawMap(const Reader& rd, const json& j, const std::string& field) {
    if (!j.is_object()) rd.fail(field, "expected an object {\"name\": value, ...}", &j);
    std::map<std::string, Draw> out;
    for (const auto& [key, value] : j.items()) {
        const std::string f = at(field, key);
        if (key.empty()) rd.fail(f, "empty name", nullptr, "a parameter name");
        out[key] = readDraw(rd, value, f, anyNumber());
    }
    return out;
}

DatasetSpecies readSpecies(const Reader& rd, const json& j, const std::string& field) {
    rd.object(j, field, {"species", "weight", "age", "build_parameters", "species_parameters"});
    DatasetSpecies s;
    if (!j.contains("species")) rd.fail(at(field, "species"), "missing", nullptr, "a species");
    s.species = rd.name(j["species"], at(field, "species"), "a library name or species file");
    s.weight = readWeight(rd, j, field);
    if (j.contains("age")) s.age = readDraw(rd, j["age"], at(field, "age"), ageRange());
    if (j.contains("build_parameters"))
        s.buildParameters = readDrawMap(rd, j["build_parameters"], at(field, "build_parameters"));
    if (j.contains("species_parameters"))
        s.speciesParameters =
            readDrawMap(rd, j["species_parameters"], at(field, "species_parameters"));
    return s;
}

std::vector<DatasetSpecies> readSpeciesList(const Reader& rd, const json& j,
                                            const std::string& field) {
    if (!j.is_array() || j.empty() || j.size() > kMaxSpecies)
        rd.fail(field, "expected a list of 1 to 1000 species {\"species\": ...}", &j);
    std::vector<DatasetSpecies> out;
    for (std::size_t i = 0; i < j.size(); ++i)
        out.push_back(readSpecies(rd, j[i], at(field, std::to_string(i))));
    return out;
}

const std::vector<std::pair<std::string, DatasetLayout::Kind>>& layoutKinds() {
    static const std::vector<std::pair<std::string, DatasetLayout::Kind>> kinds = {
        {"single", DatasetLayout::Kind::Single},
        {"rows", DatasetLayout::Kind::Rows},
        {"grid", DatasetLayout::Kind::Grid},
        {"scatter", DatasetLayout::Kind::Scatter}};
    return kinds;
}

DatasetLayout readLayout(const Reader& rd, const json& j, const std::string& field) {
    if (!j.is_object()) rd.fail(field, "expected an object {\"layout\": ...}", &j);
    std::vector<std::string> names;
    for (const auto& k : layoutKinds()) names.push_back(k.first);
    if (!j.contains("layout")) rd.fail(at(field, "layout"), "missing", nullptr, text::oneOf(names));
    const std::string name = rd.string(j["layout"], at(field, "layout"));
    DatasetLayout l;
    const auto kind = std::find_if(layoutKinds().begin(), layoutKinds().end(),
                                   [&](const auto& k) { return k.first == name; });
    if (kind == layoutKinds().end())
        rd.fail(at(field, "layout"), "unknown layout", &j["layout"], text::oneOf(names));
    l.kind = kind->second;
    const Range plantCount = wholeRange(1, 1000);  // rows x plants per row: at most 10^6
    const Range spacing = spacingRange();
    switch (l.kind) {
        case DatasetLayout::Kind::Single:
            rd.object(j, field, {"layout", "weight"});
            break;
        case DatasetLayout::Kind::Rows:
            rd.object(
                j, field,
                {"layout", "weight", "rows", "plants_per_row", "row_spacing", "plant_spacing"});
            if (j.contains("rows")) l.rows = readDraw(rd, j["rows"], at(field, "rows"), plantCount);
            if (j.contains("plants_per_row"))
                l.plantsPerRow =
                    readDraw(rd, j["plants_per_row"], at(field, "plants_per_row"), plantCount);
            if (j.contains("row_spacing"))
                l.rowSpacing = readDraw(rd, j["row_spacing"], at(field, "row_spacing"), spacing);
            if (j.contains("plant_spacing"))
                l.plantSpacing =
                    readDraw(rd, j["plant_spacing"], at(field, "plant_spacing"), spacing);
            break;
        case DatasetLayout::Kind::Grid:
            rd.object(j, field, {"layout", "weight", "count", "spacing"});
            if (j.contains("count"))
                l.count = readDraw(rd, j["count"], at(field, "count"), wholeRange(1, 100));
            if (j.contains("spacing"))
                l.spacing = readDraw(rd, j["spacing"], at(field, "spacing"), spacing);
            break;
        case DatasetLayout::Kind::Scatter:
            rd.object(j, field, {"layout", "weight", "plants", "area"});
            if (j.contains("plants"))
                l.plants = readDraw(rd, j["plants"], at(field, "plants"), wholeRange(1, 10000));
            if (j.contains("area"))
                l.area =
                    readDraw(rd, j["area"], at(field, "area"), {0, 1000, "> 0 to 1000 m", true});
            break;
    }
    l.weight = readWeight(rd, j, field);
    return l;
}

void readScene(const Reader& rd, const json& j, DatasetSpec& s) {
    rd.object(j, "scene",
              {"species", "layouts", "weeds", "germination", "mesh_detail", "soft_collision",
               "leaf_color", "max_triangles"});
    if (!j.contains("species"))
        rd.fail("scene/species", "missing", nullptr, "a list of species {\"species\": ...}");
    s.species = readSpeciesList(rd, j["species"], "scene/species");
    if (j.contains("layouts")) {
        const json& l = j["layouts"];
        if (!l.is_array() || l.empty() || l.size() > 1000)
            rd.fail("scene/layouts", "expected a list of 1 to 1000 layouts", &l);
        for (std::size_t i = 0; i < l.size(); ++i)
            s.layouts.push_back(readLayout(rd, l[i], "scene/layouts/" + std::to_string(i)));
    } else {
        s.layouts.push_back(DatasetLayout{});
    }
    if (j.contains("weeds")) {
        const json& w = j["weeds"];
        rd.object(w, "scene/weeds", {"probability", "species", "plants", "margin"});
        if (w.contains("probability"))
            s.weeds.probability =
                rd.number(w["probability"], "scene/weeds/probability", 0, 1, "0 to 1");
        if (!w.contains("species"))
            rd.fail("scene/weeds/species", "missing", nullptr, "a list of species");
        s.weeds.species = readSpeciesList(rd, w["species"], "scene/weeds/species");
        if (w.contains("plants"))
            s.weeds.plants = readDraw(rd, w["plants"], "scene/weeds/plants", wholeRange(1, 10000));
        if (w.contains("margin"))
            s.weeds.margin =
                readDraw(rd, w["margin"], "scene/weeds/margin", {0, 100, "0 to 100 m"});
    }
    if (j.contains("germination"))
        s.germination = readDraw(rd, j["germination"], "scene/germination", germinationRange());
    if (j.contains("mesh_detail"))
        s.meshDetail = readDraw(rd, j["mesh_detail"], "scene/mesh_detail", meshDetailRange());
    if (j.contains("soft_collision"))
        s.softCollision = rd.flag(j["soft_collision"], "scene/soft_collision");
    if (j.contains("leaf_color")) {
        const json& c = j["leaf_color"];
        rd.object(c, "scene/leaf_color", {"hue", "saturation", "value"});
        if (c.contains("hue"))
            s.leafColor.hue =
                readDraw(rd, c["hue"], "scene/leaf_color/hue", {-180, 180, "-180 to 180 degrees"});
        if (c.contains("saturation"))
            s.leafColor.saturation =
                readDraw(rd, c["saturation"], "scene/leaf_color/saturation", {0, 4, "0 to 4"});
        if (c.contains("value"))
            s.leafColor.value =
                readDraw(rd, c["value"], "scene/leaf_color/value", {0, 4, "0 to 4"});
    }
    if (j.contains("max_triangles"))
        s.maxTriangles = std::size_t(rd.number(j["max_triangles"], "scene/max_triangles", 1, 1e9,
                                               "whole numbers 1 to 1000000000", false, true));
}

const std::vector<std::pair<std::string, DatasetCamera::Kind>>& cameraKinds() {
    static const std::vector<std::pair<std::string, DatasetCamera::Kind>> kinds = {
        {"orbit", DatasetCamera::Kind::Orbit},
        {"nadir", DatasetCamera::Kind::Nadir},
        {"row", DatasetCamera::Kind::Row},
        {"random", DatasetCamera::Kind::Random},
        {"trajectory", DatasetCamera::Kind::Trajectory}};
    return kinds;
}

std::array<double, 3> readTriple(const Reader& rd, const json& j, const std::string& field,
                                 const Range& r) {
    const auto v = rd.numbers(j, field, 3, {r, r, r}, "[x, y, z]");
    return {v[0], v[1], v[2]};
}

void readCamera(const Reader& rd, const json& j, DatasetSpec& s) {
    DatasetCamera& c = s.camera;
    const std::string f = "camera";
    if (!j.is_object()) rd.fail(f, "expected an object {\"kind\": ...}", &j);
    std::vector<std::string> names;
    for (const auto& k : cameraKinds()) names.push_back(k.first);
    if (j.contains("kind")) {
        const std::string name = rd.string(j["kind"], "camera/kind");
        const auto kind = std::find_if(cameraKinds().begin(), cameraKinds().end(),
                                       [&](const auto& k) { return k.first == name; });
        if (kind == cameraKinds().end())
            rd.fail("camera/kind", "unknown camera kind", &j["kind"], text::oneOf(names));
        c.kind = kind->second;
    }
    std::vector<std::string> fields = {"kind", "width", "height", "samples_per_pixel", "fov"};
    switch (c.kind) {
        case DatasetCamera::Kind::Orbit:
            fields.insert(fields.end(), {"azimuth", "elevation", "margin"});
            break;
        case DatasetCamera::Kind::Nadir:
            fields.insert(fields.end(), {"azimuth", "margin"});
            break;
        case DatasetCamera::Kind::Row:
            fields.insert(fields.end(), {"height_above", "pitch"});
            break;
        case DatasetCamera::Kind::Random:
            fields.insert(fields.end(), {"eye_min", "eye_max"});
            break;
        case DatasetCamera::Kind::Trajectory:
            fields.insert(fields.end(), {"path", "target"});
            break;
    }
    rd.object(j, f, fields, {}, "");
    const Range pixels{1, 8192, "whole numbers 1 to 8192", false, true};
    if (j.contains("width")) c.width = int(rd.number(j["width"], "camera/width", pixels));
    if (j.contains("height")) c.height = int(rd.number(j["height"], "camera/height", pixels));
    if (j.contains("samples_per_pixel"))
        c.samplesPerPixel = int(rd.number(j["samples_per_pixel"], "camera/samples_per_pixel",
                                          {1, 256, "whole numbers 1 to 256", false, true}));
    {
        // What one sample's picture casts: camera rays, each with a sun and a sky ray.
        const std::uint64_t rays =
            std::uint64_t(c.width) * std::uint64_t(c.height) * std::uint64_t(c.samplesPerPixel) * 3;
        if (rays > kMaxRenderRays)
            rd.fail(
                j.contains("samples_per_pixel") ? "camera/samples_per_pixel" : "camera/width",
                "a picture of " + std::to_string(rays) + " rays is too large", nullptr,
                "width x height x samples_per_pixel x 3 at most " + std::to_string(kMaxRenderRays));
    }
    if (j.contains("fov"))
        c.fov = readDraw(rd, j["fov"], "camera/fov", {1, 150, "1 to 150 degrees"});
    if (j.contains("azimuth"))
        c.azimuth =
            readDraw(rd, j["azimuth"], "camera/azimuth", {-360, 360, "-360 to 360 degrees"});
    if (j.contains("elevation"))
        c.elevation =
            readDraw(rd, j["elevation"], "camera/elevation", {-89, 89, "-89 to 89 degrees"});
    if (j.contains("margin"))
        c.margin = readDraw(rd, j["margin"], "camera/margin", {0, 0.9, "0 to 0.9"});
    if (j.contains("height_above"))
        c.heightAbove = readDraw(rd, j["height_above"], "camera/height_above",
                                 {0, 1000, "> 0 to 1000 m", true});
    if (j.contains("pitch"))
        c.pitch = readDraw(rd, j["pitch"], "camera/pitch", {-89, 89, "-89 to 89 degrees"});
    for (int k = 0; k < 2; ++k) {
        const char* name = k == 0 ? "eye_min" : "eye_max";
        if (!j.contains(name)) continue;
        const json& v = j[name];
        const std::string fe = at(f, name);
        if (!v.is_array() || v.size() != 3) rd.fail(fe, "expected [x, y, z] (each drawn)", &v);
        auto& out = k == 0 ? c.eyeMin : c.eyeMax;
        for (std::size_t i = 0; i < 3; ++i)
            out[i] =
                readDraw(rd, v[i], at(fe, std::to_string(i)), {-1000, 1000, "-1000 to 1000 m"});
    }
    if (c.kind == DatasetCamera::Kind::Trajectory) {
        if (!j.contains("path"))
            rd.fail("camera/path", "missing", nullptr, "a list of eye points [[x, y, z], ...]");
        const json& p = j["path"];
        if (!p.is_array() || p.empty() || p.size() > kMaxPathPoints)
            rd.fail("camera/path", "expected a list of 1 to 100000 points [[x, y, z], ...]", &p);
        for (std::size_t i = 0; i < p.size(); ++i)
            c.path.push_back(readTriple(rd, p[i], "camera/path/" + std::to_string(i),
                                        {-1e4, 1e4, "-10000 to 10000 m"}));
        if (j.contains("target"))
            c.target =
                readTriple(rd, j["target"], "camera/target", {-1e4, 1e4, "-10000 to 10000 m"});
        for (std::size_t i = 0; i < c.path.size(); ++i)
            if (c.path[i] == c.target)
                rd.fail("camera/path/" + std::to_string(i), "an eye point is the target", nullptr,
                        "points apart from camera/target");
    }
}

void readLighting(const Reader& rd, const json& j, DatasetSpec& s) {
    DatasetLighting& l = s.lighting;
    rd.object(j, "lighting",
              {"location", "day_of_year", "hour", "sun_intensity", "sun_softness", "sky_intensity",
               "haze", "exposure"});
    if (j.contains("location")) {
        const auto v = rd.numbers(j["location"], "lighting/location", 2, locationRanges(),
                                  "[latitude, longitude]");
        l.latitude = v[0];
        l.longitude = v[1];
    }
    if (j.contains("day_of_year"))
        l.dayOfYear = readDraw(rd, j["day_of_year"], "lighting/day_of_year", wholeRange(1, 365));
    if (j.contains("hour"))
        l.hour = readDraw(rd, j["hour"], "lighting/hour", {0, 24, "0 to 24 (solar time)"});
    if (j.contains("sun_intensity"))
        l.sunIntensity =
            readDraw(rd, j["sun_intensity"], "lighting/sun_intensity", {0, 100, "0 to 100"});
    if (j.contains("sun_softness"))
        l.sunSoftness =
            readDraw(rd, j["sun_softness"], "lighting/sun_softness", {0, 45, "0 to 45 degrees"});
    if (j.contains("sky_intensity"))
        l.skyIntensity =
            readDraw(rd, j["sky_intensity"], "lighting/sky_intensity", {0, 100, "0 to 100"});
    if (j.contains("haze")) l.haze = readDraw(rd, j["haze"], "lighting/haze", {0, 1, "0 to 1"});
    if (j.contains("exposure"))
        l.exposure = readDraw(rd, j["exposure"], "lighting/exposure", {0, 100, "> 0 to 100", true});
}

void readGround(const Reader& rd, const json& j, DatasetSpec& s) {
    rd.object(j, "ground", {"colors", "variation", "patch_size"});
    if (j.contains("colors")) {
        const json& c = j["colors"];
        if (!c.is_array() || c.size() != 2)
            rd.fail("ground/colors", "expected two sRGB colours [[r, g, b], [r, g, b]]", &c);
        const Range unit{0, 1, "0 to 1"};
        s.ground.colorA = readTriple(rd, c[0], "ground/colors/0", unit);
        s.ground.colorB = readTriple(rd, c[1], "ground/colors/1", unit);
    }
    if (j.contains("variation"))
        s.ground.variation = readDraw(rd, j["variation"], "ground/variation", {0, 1, "0 to 1"});
    if (j.contains("patch_size"))
        s.ground.patchSize =
            readDraw(rd, j["patch_size"], "ground/patch_size", {0.001, 1000, "0.001 to 1000 m"});
}

void readOutputs(const Reader& rd, const json& j, DatasetSpec& s) {
    std::vector<std::string> names;
    for (DatasetOutput o : datasetOutputs()) names.push_back(datasetOutputName(o));
    if (!j.is_array() || j.empty())
        rd.fail("outputs", "expected a list of outputs", &j, text::oneOf(names));
    s.outputs.clear();
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string f = "outputs/" + std::to_string(i);
        const std::string name = rd.string(j[i], f);
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
            const std::string near = text::closestMatch(name, names);
            rd.fail(f, "unknown output" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                    &j[i], text::oneOf(names));
        }
        const DatasetOutput o = datasetOutputs()[std::size_t(it - names.begin())];
        if (std::find(s.outputs.begin(), s.outputs.end(), o) != s.outputs.end())
            rd.fail(f, "output named twice", &j[i]);
        s.outputs.push_back(o);
    }
}

void readSplits(const Reader& rd, const json& j, DatasetSpec& s) {
    if (!j.is_object() || j.empty() || j.size() > 100)
        rd.fail("splits", "expected {\"train\": fraction, ...} with 1 to 100 splits", &j);
    s.splits.clear();
    double sum = 0.0;
    for (const auto& [name, value] : j.items()) {
        const std::string f = "splits/" + name;
        if (name.empty() || name.size() > 64 || !std::all_of(name.begin(), name.end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
            }))
            rd.fail(f, "a split name must be 1 to 64 letters, digits, '_' or '-'", nullptr,
                    "names such as train, val, test");
        s.splits.emplace_back(name, rd.number(value, f, 0, 1, "0 to 1"));
        sum += s.splits.back().second;
    }
    if (std::abs(sum - 1.0) > 1e-6)
        rd.fail("splits", "the fractions sum to " + std::to_string(sum), nullptr, "a sum of 1");
}

DatasetSpec readSpec(const Reader& rd, const json& j, const std::string& folder) {
    rd.object(j, "",
              {"plantarch_dataset", "name", "seed", "samples", "scene", "camera", "lighting",
               "ground", "outputs", "coco", "points", "scan", "splits"});
    if (!j.contains("plantarch_dataset"))
        rd.fail("plantarch_dataset", "missing: not a dataset spec", nullptr,
                std::to_string(kDatasetVersion));
    rd.number(j["plantarch_dataset"], "plantarch_dataset", kDatasetVersion, kDatasetVersion,
              std::to_string(kDatasetVersion), false, true);
    DatasetSpec s;
    s.folder = folder;
    s.file = rd.file();
    s.outputs.clear();
    for (DatasetOutput o : datasetOutputs())
        if (o != DatasetOutput::Scan) s.outputs.push_back(o);
    if (j.contains("name")) s.name = rd.name(j["name"], "name", "a name");
    if (j.contains("seed")) s.seed = rd.seed(j["seed"], "seed");
    if (j.contains("samples"))
        s.samples = std::size_t(rd.number(j["samples"], "samples", 1, double(kMaxDatasetSamples),
                                          "whole numbers 1 to 10000000", false, true));
    if (!j.contains("scene")) rd.fail("scene", "missing", nullptr, "an object {\"species\": ...}");
    readScene(rd, j["scene"], s);
    if (j.contains("camera")) readCamera(rd, j["camera"], s);
    if (j.contains("lighting")) readLighting(rd, j["lighting"], s);
    if (j.contains("ground")) readGround(rd, j["ground"], s);
    if (j.contains("outputs")) readOutputs(rd, j["outputs"], s);
    if (j.contains("coco")) {
        rd.object(j["coco"], "coco", {"min_area"});
        if (j["coco"].contains("min_area"))
            s.cocoMinArea =
                rd.number(j["coco"]["min_area"], "coco/min_area", 0, 1e8, "0 to 100000000 pixels");
    }
    if (j.contains("points")) {
        rd.object(j["points"], "points", {"count"});
        if (j["points"].contains("count"))
            s.points = std::size_t(rd.number(j["points"]["count"], "points/count", 1, 1e8,
                                             "whole numbers 1 to 100000000", false, true));
    }
    if (j.contains("scan")) {
        rd.object(j["scan"], "scan", {"resolution"});
        if (j["scan"].contains("resolution"))
            s.scanResolution = rd.number(j["scan"]["resolution"], "scan/resolution",
                                         {0.01, 10, "0.01 to 10 degrees"});
    }
    if (j.contains("splits")) readSplits(rd, j["splits"], s);
    return s;
}

}  // namespace

DatasetSpec readDatasetSpecString(const std::string& text, const std::string& nameForErrors,
                                  const std::string& folder) {
    const std::string file = nameForErrors.empty() ? "dataset spec" : nameForErrors;
    const json j = project::parseJSONDocument(text, file, project::kMaxJSONDepth, nullptr);
    return readSpec(Reader(file), j, folder);
}

void checkDatasetSpec(const DatasetSpec& spec) {
    // Each species as a one-plant block with its drawn fields at a value they can take.
    auto sample = [](const Draw& d) { return d.kind == Draw::Kind::Choice ? d.values[0] : d.a; };
    auto check = [&](const DatasetSpecies& s, const std::string& field) {
        Project p;
        p.folder = spec.folder;
        p.file = spec.file;
        ProjectBlock b;
        b.layout = ProjectBlock::Layout::Single;
        b.species = s.species;
        for (const auto& [name, d] : s.buildParameters) b.parameters[name] = float(sample(d));
        for (const auto& [path, d] : s.speciesParameters)
            b.speciesParameters[path] = text::formatFloat(float(sample(d)));
        p.blocks.push_back(b);
        try {
            checkProject(p);
        } catch (const Error& e) {
            // "blocks/0/parameters/x" of the made project is "FIELD/build_parameters/x".
            std::string at = e.parameter();
            const std::string prefix = "blocks/0/";
            if (at.rfind(prefix, 0) == 0) at = at.substr(prefix.size());
            if (at.rfind("parameters/", 0) == 0) at = "build_parameters/" + at.substr(11);
            throw Error(e.message(), {.file = spec.file,
                                      .parameter = field + "/" + at,
                                      .value = e.value(),
                                      .validRange = e.validRange()});
        }
    };
    for (std::size_t i = 0; i < spec.species.size(); ++i)
        check(spec.species[i], "scene/species/" + std::to_string(i));
    for (std::size_t i = 0; i < spec.weeds.species.size(); ++i)
        check(spec.weeds.species[i], "scene/weeds/species/" + std::to_string(i));
}

DatasetSpec readDatasetSpecFile(const std::string& path) {
    const std::string text = io::readWholeFile(path, io::kDatasetSpecFile);
    const std::string folder = std::filesystem::path(path).parent_path().string();
    return readDatasetSpecString(text, path, folder.empty() ? "." : folder);
}

}  // namespace plantarch
