// Species endpoints: the library and the user's saved species, each species' parameters as
// the parameter table declares them, thumbnails, and editing (check, save).

#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::builder {

namespace {

json summary(const SpeciesModel& m, bool user) {
    return {{"name", m.name},
            {"common_name", m.commonName},
            {"latin_name", m.latinName},
            {"plant_type", m.plantType},
            {"description", m.description},
            {"trellis", m.trellis.has_value()},
            {"recommended_age",
             {{"min", m.recommendedAgeMin},
              {"max", m.recommendedAgeMax},
              {"default", m.recommendedAge}}},
            {"user", user}};
}

// The library's one JSON form of the fields (parameterInfoJson).
json parameters(const std::vector<ParameterInfo>& fields) {
    return json::parse(parameterInfoJson(fields));
}

json details(const SpeciesModel& m, bool user) {
    json j = summary(m, user);
    json build = json::array();
    for (const BuildParameter& p : m.buildParameters)
        build.push_back({{"name", p.name},
                         {"value", p.value},
                         {"min", p.min},
                         {"max", p.max},
                         {"range", rangeText({.min = p.min, .max = p.max, .single = true})},
                         {"unit", p.unit},
                         {"doc", p.doc}});
    j["build_parameters"] = build;
    j["phenology"] = parameters(parameterInfo(m.phenology));
    json types = json::object();
    for (const auto& [label, type] : m.shootTypes) types[label] = parameters(parameterInfo(type));
    j["shoot_types"] = types;
    return j;
}

// The species edit of a check or save request: its base species with the changes applied.
struct Edit {
    SpeciesModel model;
    std::string name;
};

}  // namespace

void Server::Impl::speciesRoutes() {
    // A species by name: the library's, else the user's (OUTPUT/species/NAME.xml).
    auto load = [this](const std::string& name, bool& user) {
        requireName(name, "species");
        const std::vector<std::string> library = listSpecies();
        user = std::find(library.begin(), library.end(), name) == library.end();
        if (!user) return loadSpecies(name);
        const auto path = userSpecies(name);
        if (!path) throw HttpError{404, "species = " + name + ": no such species"};
        return readSpeciesFile(path->string());
    };
    auto edit = [this, load](const json& body, bool forSave) {
        Edit e;
        const std::string base = stringField(body, "base").value_or("");
        if (base.empty()) throw HttpError{400, "base: missing (valid: a species name)"};
        bool user = false;
        const SpeciesModel model = load(base, user);
        e.name = stringField(body, "name").value_or("");
        if (forSave || !e.name.empty()) {
            requireName(e.name, "name");
            const std::vector<std::string> library = listSpecies();
            if (std::find(library.begin(), library.end(), e.name) != library.end())
                throw HttpError{400, "name = " + e.name +
                                         ": a library species has this name (valid: a name of "
                                         "its own)"};
        }
        std::map<std::string, std::string> changes;
        if (body.contains("changes")) {
            const json& c = body["changes"];
            if (!c.is_object())
                throw HttpError{400, "changes: expected an object {\"key\": \"value\", ...}"};
            for (const auto& [key, value] : c.items()) {
                if (value.is_string())
                    changes[key] = value.get<std::string>();
                else if (value.is_number() || value.is_boolean())
                    changes[key] = value.dump();
                else
                    throw HttpError{400, clip(key) + " = " + shownJSON(value) +
                                             ": expected the value as text, e.g. "
                                             "\"uniform(10, 30)\""};
            }
        }
        (void)user;
        e.model = editSpecies(model, changes, e.name);
        // The files it names: where the species is saved (or would be) is where they are
        // looked for.
        confineSpecies(e.model, output / "species" / ((e.name.empty() ? base : e.name) + ".xml"));
        return e;
    };

    on("GET", "/api/species", [this](const httplib::Request&, httplib::Response& res) {
        guarded(res, [&] {
            json list;
            {
                std::lock_guard<std::mutex> lock(cache);
                if (!librarySpecies) {
                    json all = json::array();
                    for (const std::string& name : listSpecies())
                        all.push_back(summary(loadSpecies(name), false));
                    librarySpecies = all;
                }
                list = *librarySpecies;
            }
            std::vector<std::string> names;
            std::error_code ec;
            for (const auto& entry : fs::directory_iterator(output / "species", ec))
                if (entry.path().extension() == ".xml")
                    names.push_back(entry.path().stem().string());
            std::sort(names.begin(), names.end());
            for (const std::string& name : names) {
                if (!userSpecies(name)) continue;
                try {
                    SpeciesModel m = readSpeciesFile(userSpecies(name)->string());
                    m.name = name;
                    list.push_back(summary(m, true));
                } catch (const Error&) {
                    // A broken file in the folder is left out of the list, not an error of it.
                }
            }
            sendJSON(res, list);
        });
    });
    on("GET", "/api/species/([^/]+)", [load](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            bool user = false;
            SpeciesModel m = load(req.matches[1].str(), user);
            if (user) m.name = req.matches[1].str();
            sendJSON(res, details(m, user));
        });
    });
    on("GET", "/api/species/([^/]+)/thumbnail.png",
       [this, load](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               const std::string name = req.matches[1].str();
               bool user = false;
               const SpeciesModel m = load(name, user);
               confineSpecies(m, m.sourceFile);
               std::string png;
               {
                   std::lock_guard<std::mutex> lock(cache);
                   if (const auto it = thumbnails.find(name); it != thumbnails.end())
                       png = it->second;
               }
               if (png.empty()) {
                   Context ctx;
                   PlantArchitecture arch(&ctx);
                   arch.setTriangleLimit(options.maxTriangles);
                   arch.setSeed(1);
                   arch.loadPlantModelFromLibrary(user ? userSpecies(name)->string() : name);
                   arch.buildPlantInstanceFromLibrary(vec3(0.0f), m.recommendedAge);
                   confineScene(ctx);
                   RenderOptions o;
                   o.width = 256;
                   o.height = 256;
                   png = encodePNG(render(ctx, o));
                   std::lock_guard<std::mutex> lock(cache);
                   thumbnails[name] = png;
               }
               res.set_header("Cache-Control", "no-cache");
               res.set_content(png, "image/png");
           });
       });
    on("POST", "/api/species/check", [edit](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            edit(bodyJSON(req), false);
            sendJSON(res, {{"ok", true}});
        });
    });
    on("POST", "/api/species/save",
       [this, edit](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               const Edit e = edit(bodyJSON(req), true);
               const fs::path path = output / "species" / (e.name + ".xml");
               if (!isUnder(path, output))
                   throw HttpError{403, "species/" + e.name +
                                            ".xml: a symbolic link leads out of the output folder"};
               {
                   std::lock_guard<std::mutex> lock(files);
                   writeSpeciesFile(e.model, path.string());
               }
               {
                   std::lock_guard<std::mutex> lock(cache);
                   thumbnails.erase(e.name);
               }
               sendJSON(res, {{"path", "species/" + e.name + ".xml"}, {"name", e.name}});
           });
       });
}

}  // namespace plantarch::builder
