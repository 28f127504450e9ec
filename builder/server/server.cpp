// The project builder's HTTP server: security checks on every request, the embedded web
// front end, the JSON helpers the route files share, and the server's life (bind, serve,
// stop).

#include "builder/server/server.h"

#include <algorithm>
#include <cctype>

#include "builder/server/assets.h"
#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"
#include "plantarch/Version.h"

namespace plantarch::builder {

// ---- helpers ------------------------------------------------------------------------------

void sendJSON(httplib::Response& res, const json& body, int status) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(body.dump(), "application/json");
}

void guarded(httplib::Response& res, const std::function<void()>& handler) {
    try {
        handler();
    } catch (const HttpError& e) {
        sendJSON(res, {{"error", e.message}}, e.status);
    } catch (const TriangleBudgetError& e) {
        sendJSON(res, {{"error", std::string(e.what()) + " (--max-triangles)"}}, 400);
    } catch (const Error& e) {
        sendJSON(res, {{"error", e.what()}}, 400);
    } catch (const std::bad_alloc&) {
        sendJSON(res, {{"error", "out of memory"}}, 500);
    } catch (const std::exception& e) {
        sendJSON(res, {{"error", std::string("internal error: ") + e.what()}}, 500);
    }
}

json bodyJSON(const httplib::Request& req) {
    try {
        json j = json::parse(req.body);
        if (!j.is_object()) throw HttpError{400, "the request body is not a JSON object {...}"};
        return j;
    } catch (const json::parse_error& e) {
        std::string why = e.what();
        if (const auto colon = why.find(": "); colon != std::string::npos)
            why = why.substr(colon + 2);
        throw HttpError{400, "the request body is not JSON: " + why};
    }
}

std::optional<std::string> stringField(const json& j, const char* name) {
    if (!j.contains(name) || j[name].is_null()) return std::nullopt;
    if (!j[name].is_string())
        throw HttpError{400,
                        std::string(name) + " = " + j[name].dump() + ": expected a text in quotes"};
    return j[name].get<std::string>();
}

void requireName(const std::string& name, const char* field) {
    const bool ok =
        !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
        });
    if (!ok)
        throw HttpError{400, std::string(field) + " = \"" + name.substr(0, 80) +
                                 "\": not a name (valid: letters, digits, _ and -, 1 to 64)"};
}

bool isUnder(const fs::path& path, const fs::path& folder) {
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(path), ec);
    if (ec) return false;
    const fs::path base = fs::weakly_canonical(folder, ec);
    if (ec) return false;
    auto r = resolved.begin();
    for (auto b = base.begin(); b != base.end(); ++b, ++r)
        if (r == resolved.end() || *r != *b) return false;
    return true;
}

fs::path outputSubfolder(const fs::path& output, const std::string& sub) {
    const fs::path p(sub);
    if (sub.find('\0') != std::string::npos || p.is_absolute() || p.has_root_name())
        throw HttpError{403, "folder = \"" + sub +
                                 "\": not inside the output folder (valid: a "
                                 "relative folder such as \"trial/day30\")"};
    for (const fs::path& part : p)
        if (part == "..")
            throw HttpError{403, "folder = \"" + sub +
                                     "\": '..' leads out of the output folder "
                                     "(valid: a folder inside it)"};
    const fs::path folder = sub.empty() ? output : output / p;
    if (!isUnder(folder, output))
        throw HttpError{403, "folder = \"" + sub +
                                 "\": a symbolic link leads out of the output "
                                 "folder (valid: a folder inside it)"};
    return folder;
}

// ---- the server ---------------------------------------------------------------------------

namespace {

fs::path makeOutput(const std::string& folder) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error("cannot make the output folder: " + ec.message(), {.file = folder});
    for (const char* sub : {"species", "projects"}) {
        fs::create_directories(fs::path(folder) / sub, ec);
        if (ec)
            throw Error("cannot make a folder in the output folder: " + ec.message(),
                        {.file = (fs::path(folder) / sub).string()});
    }
    return fs::canonical(folder);
}

}  // namespace

Server::Impl::Impl(ServerOptions o)
    : options(std::move(o)),
      output(makeOutput(options.output)),
      builds(BuildQueue::Options{.maxTriangles = options.maxTriangles,
                                 .maxQueued = options.maxQueuedBuilds,
                                 .keepFinished = options.keepFinishedBuilds}) {}

std::optional<HttpError> Server::Impl::refused(const httplib::Request& req) const {
    std::string portText = ":";  // appended: GCC 12 warns of a false overlap in ":" + ...
    portText += std::to_string(port);
    std::vector<std::string> hosts = {"127.0.0.1" + portText, "localhost" + portText};
    if (options.host != "127.0.0.1" && options.host != "localhost")
        hosts.push_back(options.host + portText);
    const std::string host = req.get_header_value("Host");
    if (std::find(hosts.begin(), hosts.end(), host) == hosts.end())
        return HttpError{403, "Host = \"" + host.substr(0, 80) +
                                  "\": not this server (valid: 127.0.0.1" + portText +
                                  " or localhost" + portText + ")"};
    const bool changes = req.method != "GET" && req.method != "HEAD";
    if (changes && req.has_header("Origin")) {
        const std::string origin = req.get_header_value("Origin");
        if (std::none_of(hosts.begin(), hosts.end(),
                         [&](const std::string& h) { return origin == "http://" + h; }))
            return HttpError{403, "Origin = \"" + origin.substr(0, 80) +
                                      "\": requests that change anything come from the "
                                      "builder's own page (valid: http://127.0.0.1" +
                                      portText + ")"};
    }
    if (changes && req.get_header_value("Sec-Fetch-Site") == "cross-site")
        return HttpError{403, "a cross-site request (valid: from the builder's own page)"};
    return std::nullopt;
}

std::optional<fs::path> Server::Impl::userSpecies(const std::string& name) const {
    if (name.empty() || name.size() > 64 || name.find_first_of("/\\.") != std::string::npos)
        return std::nullopt;
    const fs::path p = output / "species" / (name + ".xml");
    std::error_code ec;
    if (fs::is_regular_file(p, ec) && isUnder(p, output)) return p;
    return std::nullopt;
}

Project Server::Impl::requestProject(const json& j) const {
    const fs::path folder = output / "projects";
    Project p = readProjectString(j.dump(), "project", folder.string());
    const std::vector<std::string> library = listSpecies();
    for (std::size_t i = 0; i < p.blocks.size(); ++i) {
        ProjectBlock& b = p.blocks[i];
        const bool path = b.species.find('/') != std::string::npos || b.species.ends_with(".xml");
        if (!path && std::find(library.begin(), library.end(), b.species) == library.end() &&
            userSpecies(b.species))
            b.species = "../species/" + b.species + ".xml";
        if (path && !isUnder(projectPath(p, b.species), output))
            throw HttpError{403, "project: blocks/" + std::to_string(i) + "/species = \"" +
                                     b.species +
                                     "\": outside the output folder (valid: a file "
                                     "under " +
                                     output.string() + ")"};
    }
    for (std::size_t i = 0; i < p.obstacleFiles.size(); ++i)
        if (!isUnder(projectPath(p, p.obstacleFiles[i]), output))
            throw HttpError{403, "project: obstacles/files/" + std::to_string(i) + " = \"" +
                                     p.obstacleFiles[i] + "\": outside the output folder"};
    if (!p.attractionFile.empty() && !isUnder(projectPath(p, p.attractionFile), output))
        throw HttpError{403, "project: attraction/file = \"" + p.attractionFile +
                                 "\": outside the output folder"};
    return p;
}

void Server::Impl::assetRoutes() {
    http.Get(".*", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            if (req.path.starts_with("/api/") || req.path == "/api")
                throw HttpError{404, "no such endpoint: GET " + req.path};
            const std::string path = req.path == "/" ? "/index.html" : req.path;
            for (const Asset& a : assets())
                if (a.path == path) {
                    // Asked for again each time, so a new plantarch never shows an old page.
                    res.set_header("Cache-Control", "no-cache");
                    res.set_header("X-Content-Type-Options", "nosniff");
                    res.set_content(std::string(a.bytes), std::string(a.contentType));
                    return;
                }
            throw HttpError{404, "no such file: " + req.path};
        });
    });
}

void Server::Impl::routes() {
    http.set_payload_max_length(options.maxBodyBytes);
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        if (const auto e = refused(req)) {
            sendJSON(res, {{"error", e->message}}, e->status);
            return httplib::Server::HandlerResponse::Handled;
        }
        return httplib::Server::HandlerResponse::Unhandled;
    });
    http.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return;
        std::string message = "HTTP " + std::to_string(res.status);
        if (res.status == 413)
            message = "request body too large (valid: at most " +
                      std::to_string(options.maxBodyBytes) + " bytes)";
        else if (res.status == 404)
            message = "no such endpoint: " + req.method + " " + req.path;
        else if (res.status == 405)
            message = "method not allowed: " + req.method + " " + req.path;
        sendJSON(res, {{"error", message}}, res.status);
    });
    http.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
            sendJSON(res, {{"error", "internal error"}}, 500);
        });
    http.Get("/api/config", [this](const httplib::Request&, httplib::Response& res) {
        sendJSON(res, {{"version", PLANTARCH_VERSION_STRING},
                       {"output", output.string()},
                       {"max_triangles", options.maxTriangles},
                       {"max_queued_builds", options.maxQueuedBuilds},
                       {"max_body_bytes", options.maxBodyBytes},
                       {"formats", {"obj", "ply", "glb", "gltf", "usda", "xml"}}});
    });
    speciesRoutes();
    buildRoutes();
    exportRoutes();
    projectRoutes();
    // Unknown API endpoints of other methods.
    for (const char* method : {"POST", "DELETE", "PUT"}) {
        auto notFound = [method](const httplib::Request& req, httplib::Response& res) {
            sendJSON(res, {{"error", std::string("no such endpoint: ") + method + " " + req.path}},
                     404);
        };
        if (std::string(method) == "POST") http.Post(".*", notFound);
        if (std::string(method) == "DELETE") http.Delete(".*", notFound);
        if (std::string(method) == "PUT") http.Put(".*", notFound);
    }
    assetRoutes();
}

Server::Server(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

Server::~Server() {
    stop();
}

int Server::bind() {
    Impl& s = *impl_;
    const int port =
        s.options.port == 0
            ? s.http.bind_to_any_port(s.options.host)
            : (s.http.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1);
    if (port <= 0)
        throw Error("cannot listen on " + s.options.host + ":" + std::to_string(s.options.port) +
                        " (in use, or not an address of this machine)",
                    {.parameter = "--port", .validRange = "a free port, or another --host"});
    s.port = port;
    s.routes();
    return port;
}

void Server::serve() {
    impl_->http.listen_after_bind();
}

void Server::stop() {
    if (impl_->http.is_running()) impl_->http.stop();
}

std::string Server::outputFolder() const {
    return impl_->output.string();
}

}  // namespace plantarch::builder
