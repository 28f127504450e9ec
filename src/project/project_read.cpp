// Reading project files (JSON): every field checked, each error one line naming the file, the
// field as a JSON pointer without its leading slash, the value and the valid range.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/input_file.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Project.h"
#include "project/json_document.h"
#include "project/json_fields.h"
#include "project/json_scan.h"
#include "project/project_fields.h"

namespace plantarch {

namespace {

using json = nlohmann::json;

using Reader = project::JSONFields;

// Text -> JSON (json_document.h): each number beyond a double's range is read as 1e308 (of
// its sign), out of every field's range, and listed in `overflows` for readProjectString to
// name in the error.
json parseJSON(const std::string& text, const std::string& file,
               std::vector<project::JSONScan::Overflow>& overflows) {
    return project::parseJSONDocument(text, file, project::kMaxJSONDepth, &overflows);
}

void readGround(const Reader& r, const json& j, Project& p) {
    if (j.is_null()) return;
    r.object(j, "ground", {"size", "center"});
    ProjectGround g;
    if (j.contains("size")) g.size = r.pair(j["size"], "ground/size", groundSizeRange());
    if (j.contains("center")) g.center = r.pair(j["center"], "ground/center", anyNumber());
    p.ground = g;
}

void readSoft(const Reader& r, const json& j, Project& p) {
    r.object(j, "soft_collision", {"enabled", "cone"});
    if (j.contains("enabled")) p.softCollision = r.flag(j["enabled"], "soft_collision/enabled");
    if (j.contains("cone")) {
        const auto v = r.numbers(j["cone"], "soft_collision/cone", 4, softConeRanges(),
                                 "[half-angle, look-ahead, rays, inertia]");
        p.softCone = PerceptionCone{v[0], v[1], unsigned(v[2]), v[3]};
    }
}

void readObstacles(const Reader& r, const json& j, Project& p) {
    r.object(j, "obstacles", {"files", "avoid_distance", "fruit_adjustment"});
    if (j.contains("files")) {
        const json& files = j["files"];
        if (!files.is_array())
            r.fail("obstacles/files", "expected a list [\"file.obj\", ...]", &files);
        for (std::size_t i = 0; i < files.size(); ++i) {
            const std::string field = "obstacles/files/" + std::to_string(i);
            p.obstacleFiles.push_back(r.name(files[i], field, "an OBJ file"));
        }
    }
    if (j.contains("avoid_distance"))
        p.avoidDistance =
            r.number(j["avoid_distance"], "obstacles/avoid_distance", distanceRange());
    if (j.contains("fruit_adjustment"))
        p.fruitAdjustment = r.flag(j["fruit_adjustment"], "obstacles/fruit_adjustment");
}

void readAttraction(const Reader& r, const json& j, Project& p) {
    r.object(j, "attraction", {"enabled", "points", "file", "cone"});
    if (j.contains("enabled")) p.attraction = r.flag(j["enabled"], "attraction/enabled");
    if (j.contains("points")) {
        const json& points = j["points"];
        if (!points.is_array())
            r.fail("attraction/points", "expected a list of points [[x, y, z], ...]", &points);
        if (points.size() > kMaxAttractionPoints)
            r.fail("attraction/points", "too many points", nullptr,
                   "at most " + std::to_string(kMaxAttractionPoints));
        for (std::size_t i = 0; i < points.size(); ++i)
            p.attractionPoints.push_back(
                r.point(points[i], "attraction/points/" + std::to_string(i)));
    }
    if (j.contains("file") && !j["file"].is_null()) {
        p.attractionFile = r.name(j["file"], "attraction/file", "a CSV file, or null");
    }
    if (j.contains("cone")) {
        const auto v = r.numbers(j["cone"], "attraction/cone", 3, attractionConeRanges(),
                                 "[half-angle, look-ahead, inertia]");
        p.attractionCone.halfAngle = v[0];
        p.attractionCone.lookAhead = v[1];
        p.attractionCone.inertia = v[2];
    }
}

void readPhysiology(const Reader& r, const json& j, Project& p) {
    if (j.is_null()) return;
    r.object(j, "physiology", physiologyFields());
    ProjectPhysiology ph;
    PhysiologySeason& s = ph.season;
    if (j.contains("carbon")) s.carbon = r.flag(j["carbon"], "physiology/carbon");
    if (j.contains("nitrogen")) s.nitrogen = r.flag(j["nitrogen"], "physiology/nitrogen");
    if (!s.carbon && !s.nitrogen)
        r.fail("physiology", "neither carbon nor nitrogen is on", nullptr,
               "\"carbon\": true and/or \"nitrogen\": true (or no physiology section)");
    if (!j.contains("location"))
        r.fail("physiology/location", "missing", nullptr, "[latitude, longitude] in degrees");
    const json& where = j["location"];
    if (!where.is_array() || where.size() != 2)
        r.fail("physiology/location", "expected 2 numbers [latitude, longitude]", &where);
    const auto ranges = locationRanges();
    s.location.latitude =
        r.number(where[0], "physiology/location/0", ranges[0].lo, ranges[0].hi, ranges[0].text);
    s.location.longitude =
        r.number(where[1], "physiology/location/1", ranges[1].lo, ranges[1].hi, ranges[1].text);
    const bool start = j.contains("start") && !j["start"].is_null();
    const bool weather = j.contains("weather") && !j["weather"].is_null();
    if (start == weather)
        r.fail("physiology/start", start ? "both a start date and a weather file" : "missing",
               nullptr, "a start date \"YYYY-MM-DD\" (clear days) or a weather file, not both");
    if (start) {
        const std::string date = r.string(j["start"], "physiology/start");
        try {
            s.start = parseUTCTime(date);
        } catch (const Error& e) {
            r.fail("physiology/start", e.message(), &j["start"], "a date YYYY-MM-DD");
        }
        if (s.start.year < 1900 || s.start.year > 2100)
            r.fail("physiology/start", "out of range", &j["start"], "the years 1900 to 2100");
    }
    if (weather) ph.weatherFile = r.name(j["weather"], "physiology/weather", "a CSV file");
    if (j.contains("clearness"))
        s.clearness = r.number(j["clearness"], "physiology/clearness", 0.0, 1.0, "0 to 1");
    if (j.contains("light_every"))
        s.lightEvery = unsigned(r.number(j["light_every"], "physiology/light_every", 1, 24,
                                         "whole hours 1 to 24", false, true));
    if (j.contains("days"))
        ph.days = unsigned(r.number(j["days"], "physiology/days", physiologyDaysRange()));
    if (j.contains("fertilise")) {
        const json& events = j["fertilise"];
        if (!events.is_array())
            r.fail("physiology/fertilise", "expected a list [[age, grams], ...]", &events);
        if (!events.empty() && !s.nitrogen)
            r.fail("physiology/fertilise", "fertilisation adds nitrogen", nullptr,
                   "with \"nitrogen\": true");
        if (events.size() > 10000)
            r.fail("physiology/fertilise", "too many events", nullptr, "at most 10000");
        for (std::size_t i = 0; i < events.size(); ++i) {
            const std::string at = "physiology/fertilise/" + std::to_string(i);
            const auto v = r.numbers(events[i], at, 2, fertiliseRanges(), "[age, grams]");
            s.fertilise.push_back({double(v[0]), double(v[1])});
        }
    }
    p.physiology = ph;
}

ProjectBlock readBlock(const Reader& r, const json& j, const std::string& at, std::size_t index) {
    if (!j.is_object()) r.fail(at, "expected a block {...}", &j);
    ProjectBlock b;
    b.name = "block " + std::to_string(index + 1);
    const std::string layoutField = at + "/layout";
    if (j.contains("layout")) {
        const std::string layout = r.string(j["layout"], layoutField);
        const auto found = layoutFromName(layout);
        if (!found) {
            const std::string near = text::closestMatch(layout, layoutNames());
            r.fail(layoutField,
                   "unknown layout" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                   &j["layout"], "grid, scatter, single, skeleton");
        }
        b.layout = *found;
    }
    const std::string kind = layoutName(b.layout);
    r.object(j, at, blockFields(b.layout), blockFieldsElsewhere(b.layout),
             "does not apply to a " + kind + " block");
    auto field = [&](const char* key) { return at + "/" + key; };
    if (j.contains("name")) {
        b.name = r.string(j["name"], field("name"));
        if (b.name.empty()) r.fail(field("name"), "empty block name", &j["name"], "any text");
    }
    if (!j.contains("species"))
        r.fail(field("species"), "missing", nullptr, "a species name or file");
    b.species = r.name(j["species"], field("species"), "a species name or file");
    if (j.contains("origin")) b.origin = r.point(j["origin"], field("origin"));
    if (b.layout == ProjectBlock::Layout::Grid) {
        if (j.contains("count")) {
            const auto v = r.numbers(j["count"], field("count"), 2,
                                     {gridCountRange(), gridCountRange()}, "[x, y]");
            b.count = glm::ivec2(int(v[0]), int(v[1]));
            if (double(b.count.x) * double(b.count.y) > kMaxBlockPlants)
                r.fail(field("count"), "too many plants", &j["count"],
                       "at most 1000000 plants in a block");
        }
        if (j.contains("spacing"))
            b.spacing = r.pair(j["spacing"], field("spacing"), spacingRange());
    }
    if (b.layout == ProjectBlock::Layout::Scatter) {
        if (j.contains("count"))
            b.plants = unsigned(r.number(j["count"], field("count"), scatterCountRange()));
        if (j.contains("area")) b.area = r.pair(j["area"], field("area"), areaRange());
    }
    if (b.layout == ProjectBlock::Layout::Skeleton) {
        if (!j.contains("skeleton"))
            r.fail(field("skeleton"), "missing", nullptr,
                   "{\"file\": \"plant.csv\", \"unit\": 1, \"spacing\": 0}");
        const json& s = j["skeleton"];
        const std::string sat = field("skeleton");
        r.object(s, sat, skeletonFields());
        if (!s.contains("file"))
            r.fail(sat + "/file", "missing", nullptr, "a skeleton file (.csv, .json or .mtg)");
        b.skeleton = r.name(s["file"], sat + "/file", "a skeleton file (.csv, .json or .mtg)");
        if (s.contains("unit"))
            b.skeletonUnit = r.number(s["unit"], sat + "/unit", skeletonUnitRange());
        if (s.contains("spacing"))
            b.skeletonSpacing = r.number(s["spacing"], sat + "/spacing", skeletonSpacingRange());
    }
    if (j.contains("bend")) b.bend = r.flag(j["bend"], field("bend"));
    if (j.contains("elastic_modulus") && !j["elastic_modulus"].is_null())
        b.elasticModulus =
            r.number(j["elastic_modulus"], field("elastic_modulus"), elasticModulusRange());
    if (j.contains("germination"))
        b.germination = r.number(j["germination"], field("germination"), germinationRange());
    if (j.contains("age")) b.age = r.number(j["age"], field("age"), ageRange());
    if (j.contains("seed")) b.seed = r.seed(j["seed"], field("seed"));
    if (j.contains("trellis")) b.trellis = r.flag(j["trellis"], field("trellis"));
    if (j.contains("parameters")) {
        const json& params = j["parameters"];
        if (!params.is_object())
            r.fail(field("parameters"), "expected an object {\"name\": value, ...}", &params);
        for (const auto& [name, value] : params.items())
            b.parameters[name] = r.number(value, field("parameters") + "/" + name, anyNumber());
    }
    if (j.contains("species_parameters")) {
        const json& params = j["species_parameters"];
        if (!params.is_object())
            r.fail(field("species_parameters"), "expected an object {\"field.path\": value, ...}",
                   &params);
        for (const auto& [name, value] : params.items()) {
            const std::string f = field("species_parameters") + "/" + name;
            if (name.empty()) r.fail(f, "empty field path", nullptr, "a species field path");
            if (value.is_number())
                b.speciesParameters[name] = text::formatFloat(r.number(value, f, anyNumber()));
            else
                b.speciesParameters[name] =
                    r.name(value, f, "a number or a value as a species file writes it");
        }
    }
    return b;
}

// The project of parsed JSON `j`.
Project readProject(const Reader& r, const json& j, const std::string& nameForErrors,
                    const std::string& folder) {
    const std::string& file = r.file();
    r.object(j, "", projectFields());
    if (!j.contains("plantarch_project"))
        throw Error("not a plantarch project: no \"plantarch_project\": 1",
                    {.file = file, .parameter = "plantarch_project", .validRange = "1"});
    const json& version = j["plantarch_project"];
    if (!version.is_number_integer() || version.get<std::int64_t>() != kProjectVersion)
        r.fail("plantarch_project", "unsupported project version", &version,
               std::to_string(kProjectVersion));
    Project p;
    p.file = nameForErrors;
    p.folder = folder.empty() ? "." : folder;
    if (j.contains("name")) p.name = r.string(j["name"], "name");
    if (j.contains("seed")) p.seed = r.seed(j["seed"], "seed");
    if (j.contains("mesh_detail"))
        p.meshDetail = r.number(j["mesh_detail"], "mesh_detail", meshDetailRange());
    if (j.contains("ground")) readGround(r, j["ground"], p);
    if (j.contains("soft_collision")) readSoft(r, j["soft_collision"], p);
    if (j.contains("obstacles")) readObstacles(r, j["obstacles"], p);
    if (j.contains("attraction")) readAttraction(r, j["attraction"], p);
    if (j.contains("physiology")) readPhysiology(r, j["physiology"], p);
    if (j.contains("blocks")) {
        const json& blocks = j["blocks"];
        if (!blocks.is_array()) r.fail("blocks", "expected a list of blocks [{...}, ...]", &blocks);
        if (blocks.size() > kMaxBlocks)
            r.fail("blocks", "too many blocks", nullptr, "at most " + std::to_string(kMaxBlocks));
        std::map<std::string, std::size_t> names;
        for (std::size_t i = 0; i < blocks.size(); ++i) {
            const std::string at = "blocks/" + std::to_string(i);
            p.blocks.push_back(readBlock(r, blocks[i], at, i));
            const auto [it, fresh] = names.emplace(p.blocks.back().name, i);
            if (!fresh) {
                // The name as written, or the default ("block 2") of a block without one.
                const json name = p.blocks.back().name;
                r.fail(at + "/name",
                       "another block has this name (blocks/" + std::to_string(it->second) + ")",
                       &name, "a name of its own");
            }
        }
    }
    return p;
}

}  // namespace

Project readProjectString(const std::string& text, const std::string& nameForErrors,
                          const std::string& folder) {
    const std::string file = nameForErrors.empty() ? "project" : nameForErrors;
    const Reader r(file);
    std::vector<project::JSONScan::Overflow> overflows;
    const json j = parseJSON(text, file, overflows);
    try {
        return readProject(r, j, nameForErrors, folder);
    } catch (const Error& e) {
        // A number beyond a double's range was read as 1e308: the error about it shows the
        // number as written, on its line.
        for (const auto& o : overflows)
            if (e.parameter() == o.field)
                throw Error(e.message(), {.file = file,
                                          .line = o.line,
                                          .parameter = e.parameter(),
                                          .value = o.token,
                                          .validRange = e.validRange()});
        throw;
    }
}

Project readProjectFile(const std::string& path) {
    // Regular files only, at most the project file limit (16 MiB), read without blocking.
    const std::string text = io::readWholeFile(path, io::kProjectFile);
    std::string folder = std::filesystem::path(path).parent_path().string();
    return readProjectString(text, path, folder.empty() ? "." : folder);
}

}  // namespace plantarch
