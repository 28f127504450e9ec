#pragma once
// The server's state and the helpers its route files share (private to builder/server/).

#include <httplib.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>

#include "builder/server/builds.h"
#include "builder/server/server.h"

namespace plantarch::builder {

using json = nlohmann::json;
namespace fs = std::filesystem;

/// A request refused: the HTTP status and the one-line error sent as {"error": ...}.
struct HttpError {
    int status;
    std::string message;
};

struct Server::Impl {
    ServerOptions options;
    fs::path output;  ///< absolute, canonical
    int port = 0;
    httplib::Server http;
    BuildQueue builds;
    /// Held by everything that writes files: plantarch's writers put files in place through
    /// one process-wide OutputSet while one is open, so writes never overlap.
    std::mutex files;
    std::mutex cache;                               ///< guards the caches below
    std::map<std::string, std::string> thumbnails;  ///< PNG bytes by species name
    std::optional<json> librarySpecies;             ///< GET /api/species entries of the library

    explicit Impl(ServerOptions o);
    void routes();
    void speciesRoutes();
    void buildRoutes();
    void exportRoutes();
    void projectRoutes();
    void assetRoutes();

    /// The request allowed (Host and, for state-changing methods, Origin), or an HttpError.
    std::optional<HttpError> refused(const httplib::Request& req) const;

    // ---- shared by the routes ---------------------------------------------------------
    /// A user species file's path (OUTPUT/species/NAME.xml) when one of that name exists.
    std::optional<fs::path> userSpecies(const std::string& name) const;
    /// A project from the JSON of a request: checked, user species names resolved, every path
    /// under OUTPUT (else 403). Throws HttpError.
    Project requestProject(const json& j) const;
};

/// Runs `handler`, turning HttpError, plantarch::Error and anything else into a JSON error.
void guarded(httplib::Response& res, const std::function<void()>& handler);
/// Sends `body` as JSON with `status`.
void sendJSON(httplib::Response& res, const json& body, int status = 200);
/// The request body as JSON (400 when it is not).
json bodyJSON(const httplib::Request& req);
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
