#pragma once
// The project builder's HTTP server (`plantarch builder`): the web front end embedded in the
// binary (builder/server/assets.h) and the JSON API of builder/API.md, on cpp-httplib.

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace plantarch::builder {

struct ServerOptions {
    std::string host = "127.0.0.1";  ///< address to listen on
    int port = 8080;                 ///< 0: any free port (bind() says which)
    /// The only folder the server writes under (exports, species, projects); made if missing.
    std::string output = "builder-output";
    std::size_t maxTriangles = 0;         ///< per build, 0 for no limit
    std::size_t maxBodyBytes = 4u << 20;  ///< larger request bodies: 413
    std::size_t maxQueuedBuilds = 4;      ///< more waiting builds: 429
    std::size_t keepFinishedBuilds = 8;   ///< older finished builds are forgotten
};

class Server {
public:
    /// Makes the output folder (and its species/ and projects/). Throws plantarch::Error
    /// naming the folder when it cannot.
    explicit Server(ServerOptions options);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    /// Binds to the host and port; returns the port. Throws plantarch::Error when it cannot.
    int bind();
    /// Serves requests until stop() (blocking). bind() first.
    void serve();
    /// Stops serve() (from another thread or a signal-safe context's thread), cancels builds.
    void stop();
    /// The output folder, absolute.
    std::string outputFolder() const;

    /// An answer of handle().
    struct Reply {
        int status = 0;
        std::string contentType;
        std::string body;
    };
    /// Handles one request in this process, without sockets (tests, fuzzing), as the server
    /// handles it once cpp-httplib has read it: `target` is the path and query as sent
    /// ("/api/builds/b1?x=1"), the Host header is checked against the bound port (or
    /// ServerOptions::port before bind()), a body over maxBodyBytes is refused (413).
    Reply handle(const std::string& method, const std::string& target,
                 const std::vector<std::pair<std::string, std::string>>& headers,
                 const std::string& body = "");

    struct Impl;  ///< the server's state, for its route files (server_impl.h)

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace plantarch::builder
