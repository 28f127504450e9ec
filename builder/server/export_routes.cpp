// Export and project endpoints: a build's scene written under the output folder or sent as a
// download (a zip for several files); projects saved, listed and loaded.

#include <algorithm>

#include "builder/server/export_files.h"
#include "builder/server/export_options.h"
#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/Project.h"

namespace plantarch::builder {

namespace {

// The scene an export of build `id` writes (BuildQueue::exportScene).
std::shared_ptr<Scene> sceneFor(BuildQueue& builds, const std::string& id) {
    auto found = builds.exportScene(id);
    if (const auto* r = std::get_if<Refusal>(&found)) throw HttpError{r->status, r->message};
    return std::get<std::shared_ptr<Scene>>(found);
}

// A file name (without extension) for exports: letters, digits, '_', '-' and '.', not
// starting with '.', 1 to 100.
void requireFileName(const std::string& name) {
    const bool ok =
        !name.empty() && name.size() <= 100 && name[0] != '.' &&
        std::all_of(name.begin(), name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
        });
    if (!ok)
        throw HttpError{name.find('/') != std::string::npos ? 403 : 400,
                        "name = \"" + name.substr(0, 80) +
                            "\": not a file name (valid: letters, digits, _, - and ., 1 to 100, "
                            "no folder)"};
}

bool boolParam(const std::string& text, const char* name) {
    if (text == "true" || text == "1") return true;
    if (text == "false" || text == "0" || text.empty()) return false;
    throw HttpError{400, std::string(name) + " = " + text.substr(0, 40) +
                             ": not true or false (valid: true, false)"};
}

// The project's species given back by name where they are the user's saved species.
Project withSpeciesNames(Project p, const Server::Impl& s) {
    for (ProjectBlock& b : p.blocks) {
        const std::string prefix = "../species/";
        if (b.species.starts_with(prefix) && b.species.ends_with(".xml")) {
            const std::string name =
                b.species.substr(prefix.size(), b.species.size() - prefix.size() - 4);
            if (s.userSpecies(name)) b.species = name;
        }
    }
    return p;
}

}  // namespace

void Server::Impl::exportRoutes() {
    on("POST", "/api/export", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const json body = bodyJSON(req);
            const std::vector<std::string>& variants = exportVariantFields();
            for (const auto& [key, value] : body.items())
                if (key != "build" && key != "format" && key != "per_plant" && key != "folder" &&
                    key != "name" &&
                    std::find(variants.begin(), variants.end(), key) == variants.end())
                    throw HttpError{400, clip(key) +
                                             ": unknown field (valid: build, format, "
                                             "per_plant, folder, name, materials, texture_size, "
                                             "atlas, nodes, instancing, lod, meshopt, skin)"};
            const std::string id = stringField(body, "build").value_or("");
            const std::string format = stringField(body, "format").value_or("glb");
            const std::string name = stringField(body, "name").value_or("scene");
            const std::string sub = stringField(body, "folder").value_or("");
            bool perPlant = false;
            if (body.contains("per_plant")) {
                if (!body["per_plant"].is_boolean())
                    throw HttpError{400, "per_plant = " + shownJSON(body["per_plant"]) +
                                             ": expected true or false"};
                perPlant = body["per_plant"].get<bool>();
            }
            exportExtension(format);
            const PlantFileOptions variant = exportVariant(body, format);
            requireFileName(name);
            const fs::path folder = outputSubfolder(output, sub);
            const std::shared_ptr<Scene> scene = sceneFor(builds, id);
            std::vector<fs::path> files;
            {
                std::shared_lock<std::shared_mutex> read(scene->lock);
                files = writeSceneFiles(*this, *scene, folder, name, format, perPlant, variant);
            }
            json list = json::array();
            for (const fs::path& f : files)
                list.push_back(f.lexically_relative(output).generic_string());
            sendJSON(res, {{"files", list}});
        });
    });
    on("GET", "/api/export/download", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const std::string id = req.get_param_value("build");
            const std::string format =
                req.has_param("format") ? req.get_param_value("format") : "glb";
            const std::string name = req.has_param("name") ? req.get_param_value("name") : "scene";
            const bool perPlant = boolParam(req.get_param_value("per_plant"), "per_plant");
            const std::string ext = exportExtension(format);
            const PlantFileOptions variant = exportVariant(req, format);
            requireFileName(name);
            const std::shared_ptr<Scene> scene = sceneFor(builds, id);
            const TemporaryFolder temp;
            std::vector<fs::path> files;
            {
                std::shared_lock<std::shared_mutex> read(scene->lock);
                files =
                    writeSceneFiles(*this, *scene, temp.path(), name, format, perPlant, variant);
            }
            res.set_header("Cache-Control", "no-store");
            if (files.size() == 1) {
                std::ifstream in(files.front(), std::ios::binary);
                std::ostringstream ss;
                ss << in.rdbuf();
                res.set_header("Content-Disposition",
                               "attachment; filename=\"" + name + ext + "\"");
                res.set_content(ss.str(),
                                format == "glb" ? "model/gltf-binary" : "application/octet-stream");
                return;
            }
            res.set_header("Content-Disposition", "attachment; filename=\"" + name + ".zip\"");
            res.set_content(zipArchive(files, temp.path()), "application/zip");
        });
    });
}

void Server::Impl::projectRoutes() {
    on("POST", "/api/projects/save", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const json body = bodyJSON(req);
            const std::string name = stringField(body, "name").value_or("");
            requireName(name, "name");
            if (!body.contains("project"))
                throw HttpError{400, "project: missing (valid: a project {...})"};
            const Project project = requestProject(body["project"]);
            const fs::path path = output / "projects" / (name + ".json");
            if (!isUnder(path, output))
                throw HttpError{403, "projects/" + name +
                                         ".json: a symbolic link leads out of the output folder"};
            {
                std::lock_guard<std::mutex> lock(files);
                writeProjectFile(project, path.string());
            }
            sendJSON(res, {{"path", "projects/" + name + ".json"}});
        });
    });
    on("GET", "/api/projects", [this](const httplib::Request&, httplib::Response& res) {
        guarded(res, [&] {
            std::vector<std::string> names;
            std::error_code ec;
            for (const auto& entry : fs::directory_iterator(output / "projects", ec))
                if (entry.path().extension() == ".json")
                    names.push_back(entry.path().stem().string());
            std::sort(names.begin(), names.end());
            sendJSON(res, names);
        });
    });
    on("GET", "/api/projects/([^/]+)", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const std::string name = req.matches[1].str();
            requireName(name, "project");
            const fs::path path = output / "projects" / (name + ".json");
            std::error_code ec;
            if (!fs::is_regular_file(path, ec) || !isUnder(path, output))
                throw HttpError{404, "project = " + name + ": no such project"};
            const Project p = withSpeciesNames(readProjectFile(path.string()), *this);
            sendJSON(res, json::parse(writeProjectString(p)));
        });
    });
}

}  // namespace plantarch::builder
