// The project builder's HTTP server: security checks on every request, the embedded web
// front end, the JSON helpers the route files share, and the server's life (bind, serve,
// stop).

#include "builder/server/server.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <set>

#include "builder/server/assets.h"
#include "builder/server/export_files.h"
#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Project.h"
#include "plantarch/SpeciesIO.h"
#include "plantarch/Version.h"

namespace plantarch::builder {

// ---- helpers ------------------------------------------------------------------------------

void sendJSON(httplib::Response& res, const json& body, int status) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    // Invalid UTF-8 in a request's text quoted by a message is replaced, not thrown about.
    res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

std::string oneLine(const std::string& message) {
    return clip(message, 1000);
}

void guarded(httplib::Response& res, const std::function<void()>& handler) {
    try {
        handler();
    } catch (const HttpError& e) {
        sendJSON(res, {{"error", oneLine(e.message)}}, e.status);
    } catch (const TriangleBudgetError& e) {
        sendJSON(res, {{"error", oneLine(e.what()) + " (--max-triangles)"}}, 400);
    } catch (const Error& e) {
        sendJSON(res, {{"error", oneLine(e.what())}}, 400);
    } catch (const std::bad_alloc&) {
        sendJSON(res, {{"error", "out of memory"}}, 500);
    } catch (const std::exception& e) {
        sendJSON(res, {{"error", "internal error: " + oneLine(e.what())}}, 500);
    }
}

std::optional<std::string> stringField(const json& j, const char* name) {
    if (!j.contains(name) || j[name].is_null()) return std::nullopt;
    if (!j[name].is_string())
        throw HttpError{
            400, std::string(name) + " = " + shownJSON(j[name]) + ": expected a text in quotes"};
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
        throw HttpError{403, "folder = \"" + clip(sub) +
                                 "\": not inside the output folder (valid: a "
                                 "relative folder such as \"trial/day30\")"};
    for (const fs::path& part : p)
        if (part == "..")
            throw HttpError{403, "folder = \"" + clip(sub) +
                                     "\": '..' leads out of the output folder "
                                     "(valid: a folder inside it)"};
    const fs::path folder = sub.empty() ? output : output / p;
    if (!isUnder(folder, output))
        throw HttpError{403, "folder = \"" + clip(sub) +
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

// The species library's folder, canonical, if there is one.
std::vector<fs::path> libraryFolder() {
    try {
        std::error_code ec;
        const fs::path library = fs::canonical(speciesLibraryDirectory(), ec);
        if (!ec) return {library};
    } catch (const Error&) {
        // No library: the builder reads only its output folder.
    }
    return {};
}

}  // namespace

Server::Impl::Impl(ServerOptions o)
    : options(std::move(o)),
      output(makeOutput(options.output)),
      port(options.port),
      builds(BuildQueue::Options{.maxTriangles = options.maxTriangles,
                                 .maxQueued = options.maxQueuedBuilds,
                                 .keepFinished = options.keepFinishedBuilds,
                                 .checkScene = [this](const Context& c) { confineScene(c); }}) {
    readable = {output};
    for (const fs::path& library : libraryFolder()) readable.push_back(library);
    routes();
}

void Server::Impl::on(const char* method, const char* pattern, Handler handler) {
    table.push_back({method, std::regex(pattern), std::move(handler)});
}

void Server::Impl::dispatch(const httplib::Request& req, httplib::Response& res) const {
    if (const auto e = refused(req)) return sendJSON(res, {{"error", e->message}}, e->status);
    const std::string method = req.method == "HEAD" ? "GET" : req.method;
    // The route's captures go in the request as cpp-httplib's own routing puts them; the
    // request is cpp-httplib's (or handle()'s) own object, not a constant.
    auto& matches = const_cast<httplib::Request&>(req).matches;
    for (const Route& r : table)
        if (r.method == method && std::regex_match(req.path, matches, r.pattern))
            return r.handler(req, res);
    sendJSON(res, {{"error", "no such endpoint: " + clip(req.method, 16) + " " + clip(req.path)}},
             404);
}

std::optional<HttpError> Server::Impl::refused(const httplib::Request& req) const {
    std::string portText = ":";  // appended: GCC 12 warns of a false overlap in ":" + ...
    portText += std::to_string(port);
    std::vector<std::string> hosts = {"127.0.0.1" + portText, "localhost" + portText};
    if (options.host != "127.0.0.1" && options.host != "localhost")
        hosts.push_back(options.host + portText);
    const std::string host = req.get_header_value("Host");
    if (std::find(hosts.begin(), hosts.end(), host) == hosts.end())
        return HttpError{403, "Host = \"" + clip(host) + "\": not this server (valid: 127.0.0.1" +
                                  portText + " or localhost" + portText + ")"};
    const bool changes = req.method != "GET" && req.method != "HEAD";
    if (changes && req.has_header("Origin")) {
        const std::string origin = req.get_header_value("Origin");
        if (std::none_of(hosts.begin(), hosts.end(),
                         [&](const std::string& h) { return origin == "http://" + h; }))
            return HttpError{403, "Origin = \"" + clip(origin) +
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
    std::vector<std::string> written;  // each block's species as the request names it
    for (const ProjectBlock& b : p.blocks) written.push_back(b.species);
    for (std::size_t i = 0; i < p.blocks.size(); ++i) {
        ProjectBlock& b = p.blocks[i];
        const bool path = b.species.find('/') != std::string::npos || b.species.ends_with(".xml");
        if (!path && std::find(library.begin(), library.end(), b.species) == library.end() &&
            userSpecies(b.species))
            b.species = "../species/" + b.species + ".xml";
        if (path && !isUnder(projectPath(p, b.species), output))
            throw HttpError{403, "project: blocks/" + std::to_string(i) + "/species = \"" +
                                     clip(b.species) +
                                     "\": outside the output folder (valid: a file "
                                     "under " +
                                     output.string() + ")"};
    }
    for (std::size_t i = 0; i < p.obstacleFiles.size(); ++i)
        if (!isUnder(projectPath(p, p.obstacleFiles[i]), output))
            throw HttpError{403, "project: obstacles/files/" + std::to_string(i) + " = \"" +
                                     clip(p.obstacleFiles[i]) + "\": outside the output folder"};
    for (std::size_t i = 0; i < p.blocks.size(); ++i)
        if (p.blocks[i].layout == ProjectBlock::Layout::Skeleton &&
            !isUnder(projectPath(p, p.blocks[i].skeleton), output))
            throw HttpError{403, "project: blocks/" + std::to_string(i) + "/skeleton/file = \"" +
                                     clip(p.blocks[i].skeleton) +
                                     "\": outside the output folder (valid: a file under " +
                                     output.string() + ")"};
    if (!p.attractionFile.empty() && !isUnder(projectPath(p, p.attractionFile), output))
        throw HttpError{403, "project: attraction/file = \"" + clip(p.attractionFile) +
                                 "\": outside the output folder"};
    // The files each block's species names (textures, OBJ models). A species that does not
    // load is left to the build, which refuses it.
    std::set<std::string> checked;
    for (std::size_t i = 0; i < p.blocks.size(); ++i) {
        const std::string species = projectSpecies(p, p.blocks[i]);
        if (!checked.insert(species).second) continue;
        const std::string& named = written[i];
        std::error_code ec;
        if ((named.find('/') != std::string::npos || named.ends_with(".xml")) &&
            !fs::is_regular_file(species, ec))
            continue;  // a species file missing, a pipe...: checkProject says which
        SpeciesModel model;
        try {
            model = loadSpecies(species);
        } catch (const Error&) {
            continue;
        }
        try {
            confineSpecies(model, model.sourceFile);
        } catch (const HttpError& e) {
            throw HttpError{e.status, "project: blocks/" + std::to_string(i) + "/species = \"" +
                                          clip(written[i]) + "\": " + e.message};
        }
    }
    return p;
}

void Server::Impl::assetRoutes() {
    on("GET", ".*", [](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            if (req.path.starts_with("/api/") || req.path == "/api")
                throw HttpError{404, "no such endpoint: GET " + clip(req.path)};
            const std::string path = req.path == "/" ? "/index.html" : req.path;
            for (const Asset& a : assets())
                if (a.path == path) {
                    // Asked for again each time, so a new plantarch never shows an old page.
                    res.set_header("Cache-Control", "no-cache");
                    res.set_header("X-Content-Type-Options", "nosniff");
                    res.set_content(std::string(a.bytes), std::string(a.contentType));
                    return;
                }
            throw HttpError{404, "no such file: " + clip(req.path)};
        });
    });
}

namespace {

// GET /api/defaults: what the page would otherwise restate, from the C++ declarations. A
// project file's defaults as the library writes a default Project; a ground's and each
// layout's block's, from projects that have one; a physiology season's; the organ label
// colours; the export formats.
json pageDefaults() {
    const json project = json::parse(writeProjectString(Project{}));
    Project grounded;
    grounded.ground = ProjectGround{};
    Project seasoned;
    seasoned.physiology = ProjectPhysiology{};
    Project blocks;
    for (ProjectBlock::Layout layout :
         {ProjectBlock::Layout::Grid, ProjectBlock::Layout::Scatter, ProjectBlock::Layout::Single,
          ProjectBlock::Layout::Skeleton})
        blocks.blocks.emplace_back().layout = layout;
    const json written = json::parse(writeProjectString(blocks));
    json byLayout = json::object();
    for (json b : written["blocks"]) {
        b.erase("name");  // a file's block has no default species; its name is numbered
        b.erase("species");
        byLayout[b["layout"].get<std::string>()] = b;
    }
    json colors = json::object();
    for (std::string_view organ : kOrganLabels) {
        const auto rgb = organLabelColor(organ);
        colors[std::string(organ)] = {rgb[0], rgb[1], rgb[2]};
    }
    json formats = json::array();
    for (const OutputFormat& f : outputFormats())
        if (f.uses & kBuilderExport)
            formats.push_back({{"format", std::string(f.extension.substr(1))},
                               {"description", std::string(f.description)}});
    return {{"project", project},
            {"ground", json::parse(writeProjectString(grounded))["ground"]},
            {"blocks", byLayout},
            {"physiology", json::parse(writeProjectString(seasoned))["physiology"]},
            {"organ_colors", colors},
            {"export_formats", formats}};
}

}  // namespace

void Server::Impl::routes() {
    http.set_payload_max_length(options.maxBodyBytes);
    http.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return;
        std::string message = "HTTP " + std::to_string(res.status);
        if (res.status == 413)
            message = "request body too large (valid: at most " +
                      std::to_string(options.maxBodyBytes) + " bytes)";
        else if (res.status == 404)
            message = "no such endpoint: " + clip(req.method, 16) + " " + clip(req.path);
        else if (res.status == 405)
            message = "method not allowed: " + clip(req.method, 16) + " " + clip(req.path);
        sendJSON(res, {{"error", message}}, res.status);
    });
    http.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
            sendJSON(res, {{"error", "internal error"}}, 500);
        });
    on("GET", "/api/config", [this](const httplib::Request&, httplib::Response& res) {
        sendJSON(res, {{"version", PLANTARCH_VERSION_STRING},
                       {"output", output.string()},
                       {"max_triangles", options.maxTriangles},
                       {"max_queued_builds", options.maxQueuedBuilds},
                       {"max_body_bytes", options.maxBodyBytes},
                       {"max_json_depth", kMaxRequestDepth},
                       {"formats", exportFormats()}});
    });
    on("GET", "/api/defaults", [](const httplib::Request&, httplib::Response& res) {
        static const json defaults = pageDefaults();
        sendJSON(res, defaults);
    });
    speciesRoutes();
    buildRoutes();
    exportRoutes();
    projectRoutes();
    datasetRoutes();
    assetRoutes();
    // cpp-httplib hands every request to dispatch(), which routes it (and answers 404).
    const auto all = [this](const httplib::Request& req, httplib::Response& res) {
        dispatch(req, res);
    };
    http.Get(".*", all);
    http.Post(".*", all);
    http.Put(".*", all);
    http.Patch(".*", all);
    http.Delete(".*", all);
    http.Options(".*", all);
}

Server::Server(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

Server::~Server() {
    stop();
}

namespace {

// Why binding `host`:`port` fails, found by trying it with a socket of our own (cpp-httplib
// says only that it failed).
std::string bindFailure(const std::string& host, int port) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE;
    addrinfo* found = nullptr;
    if (const int e = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found))
        return std::string("not an address of this machine (") + gai_strerror(e) + ")";
    int error = 0;
    const int sock = socket(found->ai_family, found->ai_socktype, found->ai_protocol);
    if (sock < 0) {
        error = errno;
    } else {
        const int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
        if (::bind(sock, found->ai_addr, found->ai_addrlen) != 0 || listen(sock, 1) != 0)
            error = errno;
        close(sock);
    }
    freeaddrinfo(found);
    if (error == EADDRINUSE) return "the port is in use (another program listens on it)";
    if (error == EADDRNOTAVAIL) return "not an address of this machine";
    if (error == EACCES) return "a port below 1024 needs privileges";
    return error ? std::strerror(error) : "in use, or not an address of this machine";
}

}  // namespace

int Server::bind() {
    Impl& s = *impl_;
    // cpp-httplib's default sets SO_REUSEPORT, with which a second server binds the same port
    // and the kernel shares the connections between the two: SO_REUSEADDR only (a restart
    // still binds while old connections linger), so a port in use is refused.
    s.http.set_socket_options([](int sock) {
        const int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    const int port =
        s.options.port == 0
            ? s.http.bind_to_any_port(s.options.host)
            : (s.http.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1);
    if (port <= 0) {
        const std::string why = bindFailure(s.options.host, s.options.port);
        const bool address = why.starts_with("not an address");
        throw Error("cannot listen on " + s.options.host + ":" + std::to_string(s.options.port) +
                        ": " + why,
                    {.parameter = address ? "--host" : "--port",
                     .value = address ? s.options.host : std::to_string(s.options.port),
                     .validRange = address ? "an address of this machine (127.0.0.1)"
                                           : "a free port, or 0 for any free port"});
    }
    s.port = port;
    return port;
}

Server::Reply Server::handle(const std::string& method, const std::string& target,
                             const std::vector<std::pair<std::string, std::string>>& headers,
                             const std::string& body) {
    httplib::Request req;
    httplib::Response res;
    req.method = method;
    req.target = target;
    const auto query = target.find('?');
    req.path = httplib::detail::decode_url(target.substr(0, query), false);
    if (query != std::string::npos)
        httplib::detail::parse_query_text(target.substr(query + 1), req.params);
    for (const auto& [name, value] : headers) req.headers.emplace(name, value);
    req.body = body;
    if (body.size() > impl_->options.maxBodyBytes)  // as cpp-httplib refuses it
        sendJSON(res,
                 {{"error", "request body too large (valid: at most " +
                                std::to_string(impl_->options.maxBodyBytes) + " bytes)"}},
                 413);
    else
        impl_->dispatch(req, res);
    // A handler that only sets content leaves the status to cpp-httplib, which makes it 200.
    return {res.status == -1 ? 200 : res.status, res.get_header_value("Content-Type"), res.body};
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
