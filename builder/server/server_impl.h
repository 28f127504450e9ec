#pragma once
// The server's state and the helpers its route files share (private to builder/server/).

#include <httplib.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <variant>
#include <vector>

#include "builder/server/builds.h"
#include "builder/server/server.h"
#include "plantarch/Species.h"

namespace plantarch::builder {

using json = nlohmann::json;
namespace fs = std::filesystem;

/// A request refused: the HTTP status and the one-line error sent as {"error": ...}.
struct HttpError {
    int status;
    std::string message;
};

/// JSON nested deeper than this in a request body is refused (400): a project needs 5 levels.
inline constexpr std::size_t kMaxRequestDepth = 64;

using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

/// The dataset endpoints' previews and runs (dataset_routes.cpp).
struct DatasetState;

/// A route: requests of `method` whose whole path matches `pattern` go to `handler`.
struct Route {
    std::string method;
    std::regex pattern;
    Handler handler;
};

struct Server::Impl {
    ServerOptions options;
    fs::path output;  ///< absolute, canonical
    /// The folders whose files the builder reads, embeds and serves: the output folder and the
    /// species library's (canonical).
    std::vector<fs::path> readable;
    int port = 0;  ///< bound (or options.port before bind())
    httplib::Server http;
    std::vector<Route> table;  ///< in the order declared: the first that matches is taken
    BuildQueue builds;
    /// Held by everything that writes files: plantarch's writers put files in place through
    /// one process-wide OutputSet while one is open, so writes never overlap.
    std::mutex files;
    std::mutex cache;                               ///< guards the caches below
    std::map<std::string, std::string> thumbnails;  ///< PNG bytes by species name
    std::optional<json> librarySpecies;             ///< GET /api/species entries of the library
    /// Declared last: destroyed first, it cancels a dataset run and waits for its thread.
    std::shared_ptr<DatasetState> datasets;

    explicit Impl(ServerOptions o);
    /// Declares a route (dispatch() takes them in the order declared).
    void on(const char* method, const char* pattern, Handler handler);
    /// Handles one request as the server does: the security checks (refused()), then the first
    /// route of its method (HEAD as GET) whose pattern matches its whole path; 404 when none
    /// does. cpp-httplib hands every request to this; tests and the fuzzer call it
    /// without sockets.
    void dispatch(const httplib::Request& req, httplib::Response& res) const;
    void routes();
    void speciesRoutes();
    void buildRoutes();
    void exportRoutes();
    void projectRoutes();
    void datasetRoutes();
    void assetRoutes();

    /// The request allowed (Host and, for state-changing methods, Origin), or an HttpError.
    std::optional<HttpError> refused(const httplib::Request& req) const;

    // ---- shared by the routes ---------------------------------------------------------
    /// A user species file's path (OUTPUT/species/NAME.xml) when one of that name exists.
    std::optional<fs::path> userSpecies(const std::string& name) const;
    /// A project from the JSON of a request: checked, user species names resolved, every path
    /// under OUTPUT (else 403). Throws HttpError.
    Project requestProject(const json& j) const;

    // ---- files a species or scene names (confine.cpp) ------------------------------------
    /// Every file `species` names (leaf OBJ models and textures, stem textures, flower and fruit
    /// OBJ models) is a regular file under `readable` however the reader resolves it (from
    /// `speciesFile`'s folder or from the working folder): else an HttpError naming the
    /// parameter (as a species edit names it: "shoot_types.LABEL.phytomer....") and the
    /// folders (403 outside them, 400 not a regular file or missing).
    void confineSpecies(const SpeciesModel& species, const fs::path& speciesFile) const;
    /// Every texture of the scene's materials is a regular file under `readable` (else a
    /// plantarch::Error naming the texture): nothing else is embedded in an export.
    void confineScene(const Context& scene) const;
    /// "OUTPUT or LIBRARY", for messages.
    std::string readableText() const;
};

/// Runs `handler`, turning HttpError, plantarch::Error and anything else into a JSON error.
void guarded(httplib::Response& res, const std::function<void()>& handler);
/// Sends `body` as JSON with `status`.
void sendJSON(httplib::Response& res, const json& body, int status = 200);
/// The request body as JSON (400 when it is not JSON, not an object, nested deeper than
/// kMaxRequestDepth or holds a number beyond a double's range; request_json.cpp).
json bodyJSON(const httplib::Request& req);
/// At most `max` bytes of `text` (for quoting a request's text in a message), "..." when cut,
/// its line breaks written as \n and other control characters as '?'.
std::string clip(const std::string& text, std::size_t max = 80);
/// `message` cut to 1000 bytes, its line breaks written as \n and other control characters
/// as '?': one line.
std::string oneLine(const std::string& message);
/// A JSON value of a request as a message quotes it: compact, at most about 60 bytes.
std::string shownJSON(const json& value);
/// A field of a JSON object, with its type checked (400 naming it when wrong); nullopt when
/// absent or null.
std::optional<std::string> stringField(const json& j, const char* name);
/// A name of a species, project or file: letters, digits, '_' and '-', 1 to 64 (else 400).
void requireName(const std::string& name, const char* field);
/// The folder OUTPUT/`sub` for a relative `sub` without "..", not reaching out of OUTPUT
/// through a symbolic link (else 403).
fs::path outputSubfolder(const fs::path& output, const std::string& sub);
/// Whether `path` (absolute or relative to the working folder) lies under `folder` once
/// symbolic links of its existing part are resolved.
bool isUnder(const fs::path& path, const fs::path& folder);

}  // namespace plantarch::builder
