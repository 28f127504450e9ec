// libFuzzer target: the project builder's request handling (builder/server/), in this process
// without sockets (Server::handle: the security checks, the routes, the handlers, as the
// server runs them once cpp-httplib has read a request). One server, its output folder in a
// temporary folder, serves every input; its builds run on its worker thread as they would.
//
// An input is a request as text: the first line "METHOD TARGET" (TARGET: path and query),
// then header lines "Name: value" up to an empty line, then the body. A Host header naming
// the server is added when the input gives none (else most inputs would only reach the Host
// check). Pictures (render.png, thumbnail.png) are not asked for: one takes seconds under the
// sanitizers, and the server tests cover them.
//
// Every answer must be a status of 200 to 599; every /api/ answer JSON; every error one line
// of bounded length (1,000 bytes of text, each byte that is not UTF-8 sent as U+FFFD: at most
// 3,100 bytes), never an "internal error".

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "builder/server/server.h"
#include "plantarch/Error.h"

namespace fs = std::filesystem;
using plantarch::builder::Server;

namespace {

constexpr int kPort = 8080;  // never bound: only the Host check sees it

std::string& outputFolder() {
    static std::string folder = [] {
        std::string pattern =
            (fs::temp_directory_path() / "plantarch-fuzz-builder-XXXXXX").string();
        if (!mkdtemp(pattern.data())) std::abort();
        return pattern;
    }();
    return folder;
}

Server& server() {
    static Server* s = [] {
        plantarch::builder::ServerOptions o;
        o.port = kPort;
        o.output = outputFolder() + "/out";
        o.maxTriangles = 20000;  // small builds finish; larger ones are refused early
        o.maxQueuedBuilds = 2;
        o.keepFinishedBuilds = 2;
        o.maxBodyBytes = 1u << 20;
        return new Server(o);
    }();
    return *s;
}

// What the runs leave in the output folder (saved species and projects, exports) is removed
// now and then, so listing it stays quick.
void tidy(std::size_t run) {
    if (run % 500 != 0) return;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(outputFolder() + "/out", ec)) {
        if (entry.path().filename() == "species" || entry.path().filename() == "projects") {
            for (const auto& inner : fs::directory_iterator(entry.path(), ec))
                fs::remove_all(inner.path(), ec);
            continue;
        }
        fs::remove_all(entry.path(), ec);
    }
}

[[noreturn]] void fail(const std::string& why, const std::string& method, const std::string& target,
                       const Server::Reply& r) {
    std::fprintf(stderr, "fuzz_builder: %s: %s %s -> %d %s\n", why.c_str(), method.c_str(),
                 target.c_str(), r.status, r.body.substr(0, 2000).c_str());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static std::size_t runs = 0;
    tidy(++runs);
    const std::string input(reinterpret_cast<const char*>(data), size);
    std::size_t at = input.find('\n');
    const std::string first = input.substr(0, at);
    const std::size_t space = first.find(' ');
    if (space == std::string::npos) return 0;
    const std::string method = first.substr(0, space);
    const std::string target = first.substr(space + 1);
    if (target.find("render.png") != std::string::npos ||
        target.find("thumbnail.png") != std::string::npos)
        return 0;
    std::vector<std::pair<std::string, std::string>> headers;
    bool host = false;
    while (at != std::string::npos) {
        const std::size_t end = input.find('\n', at + 1);
        const std::string line =
            input.substr(at + 1, end == std::string::npos ? end : end - at - 1);
        at = end;
        if (line.empty()) break;
        const std::size_t colon = line.find(": ");
        if (colon == std::string::npos) continue;
        headers.emplace_back(line.substr(0, colon), line.substr(colon + 2));
        host = host || headers.back().first == "Host";
    }
    if (!host) headers.emplace_back("Host", "127.0.0.1:" + std::to_string(kPort));
    const std::string body = at == std::string::npos ? "" : input.substr(at + 1);

    Server::Reply r;
    try {
        r = server().handle(method, target, headers, body);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_builder: an exception left the server: %s\n", e.what());
        std::abort();
    }
    if (r.status < 200 || r.status > 599) fail("status", method, target, r);
    if (r.contentType != "application/json") return 0;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(r.body);
    } catch (const nlohmann::json::exception&) {
        fail("answer is not JSON", method, target, r);
    }
    if (r.status >= 400) {
        if (!j.is_object() || !j.contains("error") || !j["error"].is_string())
            fail("error without {\"error\": ...}", method, target, r);
        const std::string e = j["error"].get<std::string>();
        if (e.find('\n') != std::string::npos || e.size() > 3100 || e.starts_with("internal error"))
            fail("not a one-line error", method, target, r);
    }
    return 0;
}
