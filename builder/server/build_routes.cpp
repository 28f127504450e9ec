// Build endpoints: queue a build (or grow an earlier one on), its state, cancel, its scene as
// GLB and a rendered picture.

#include <cstdio>
#include <fstream>
#include <sstream>

#include "builder/server/export_files.h"
#include "builder/server/export_options.h"
#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/Render.h"

namespace plantarch::builder {

namespace {

json stateJSON(const Build& b) {
    json j = {{"id", b.id},
              {"state", buildStateName(b.state)},
              {"stage", b.stage},
              {"progress", b.progress},
              {"error", b.error.empty() ? json(nullptr) : json(b.error)},
              {"from", b.from.empty() ? json(nullptr) : json(b.from)},
              {"taken_by", b.takenBy.empty() ? json(nullptr) : json(b.takenBy)},
              {"stats", nullptr},
              {"blocks", json::array()},
              {"ages", b.ages}};
    if (b.state == BuildState::Done) {
        const ProjectStats& s = b.stats;
        j["stats"] = {{"plants", s.plants},      {"triangles", s.triangles},
                      {"objects", s.objects},    {"height", s.height},
                      {"leaf_area", s.leafArea}, {"leaf_count", s.leafCount}};
    }
    for (std::size_t i = 0; i < b.project.blocks.size(); ++i) {
        json plants = json::array();
        if (b.scene && i < b.scene->built.blockPlants.size())
            plants = b.scene->built.blockPlants[i];
        j["blocks"].push_back({{"name", b.project.blocks[i].name}, {"plants", plants}});
    }
    return j;
}

int dimension(const httplib::Request& req, const char* name, int fallback) {
    if (!req.has_param(name)) return fallback;
    const std::string text = req.get_param_value(name);
    int v = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%d%c", &v, &extra) != 1 || v < 16 || v > 4096)
        throw HttpError{400, std::string(name) + " = " + text.substr(0, 40) +
                                 ": not a picture size (valid: 16 to 4096 pixels)"};
    return v;
}

std::shared_ptr<Scene> sceneOf(BuildQueue& builds, const std::string& id) {
    auto found = builds.scene(id);
    if (const auto* r = std::get_if<Refusal>(&found)) throw HttpError{r->status, r->message};
    return std::get<std::shared_ptr<Scene>>(found);
}

}  // namespace

void Server::Impl::buildRoutes() {
    on("POST", "/api/builds", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const json body = bodyJSON(req);
            if (!body.contains("project"))
                throw HttpError{400, "project: missing (valid: a project {...})"};
            for (const auto& [key, value] : body.items())
                if (key != "project" && key != "from")
                    throw HttpError{400, clip(key) + ": unknown field (valid: project, from)"};
            Project project = requestProject(body["project"]);
            checkProject(project);
            auto queued = builds.submit(std::move(project), stringField(body, "from").value_or(""));
            if (const auto* r = std::get_if<Refusal>(&queued))
                throw HttpError{r->status, r->message};
            sendJSON(res, {{"id", std::get<std::string>(queued)}}, 202);
        });
    });
    on("GET", "/api/builds/([^/]+)", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const auto b = builds.status(req.matches[1].str());
            if (!b) throw HttpError{404, "no build " + req.matches[1].str()};
            sendJSON(res, stateJSON(*b));
        });
    });
    on("DELETE", "/api/builds/([^/]+)",
       [this](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               const auto cancelled = builds.cancel(req.matches[1].str());
               if (!cancelled) throw HttpError{404, "no build " + req.matches[1].str()};
               sendJSON(res, {{"state", *cancelled ? "cancelled" : "deleted"}});
           });
       });
    on("GET", "/api/builds/([^/]+)/scene.glb",
       [this](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               // The view's materials (flat or textured), as an export's; nothing else.
               for (const auto& [param, value] : req.params)
                   if (param != "materials" && param != "texture_size")
                       throw HttpError{400, clip(param) +
                                                ": unknown parameter of scene.glb (valid: "
                                                "materials, texture_size)"};
               PlantFileOptions variant;
               variant.appearance = exportVariant(req, "glb").appearance;
               const MaterialOptions& look = variant.appearance;
               const std::string key = look.style == MaterialStyle::Flat
                                           ? ""
                                           : std::string(materialStyleName(look.style)) + ":" +
                                                 std::to_string(look.textureSize);
               auto bytes = builds.glb(req.matches[1].str(), key, [&](Scene& s) {
                   return sceneFileBytes(*this, s, "glb", variant);
               });
               if (const auto* r = std::get_if<Refusal>(&bytes))
                   throw HttpError{r->status, r->message};
               res.set_header("Cache-Control", "no-store");
               res.set_content(std::get<std::string>(bytes), "model/gltf-binary");
           });
       });
    on("GET", "/api/builds/([^/]+)/render.png",
       [this](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               RenderOptions o;
               o.width = dimension(req, "w", 800);
               o.height = dimension(req, "h", 600);
               const std::shared_ptr<Scene> s = sceneOf(builds, req.matches[1].str());
               std::string png;
               {
                   std::shared_lock<std::shared_mutex> read(s->lock);
                   png = encodePNG(render(s->context, o));
               }
               res.set_header("Cache-Control", "no-store");
               res.set_content(png, "image/png");
           });
       });
}

}  // namespace plantarch::builder
