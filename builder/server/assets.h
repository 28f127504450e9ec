// The files of the builder's web front end (builder/web), embedded in the plantarch binary at
// build time: CMake bundles builder/web with esbuild and generates the source implementing
// assets() (builder/web/embed.mjs). Nothing is read from disk or the network at run time.
#pragma once
#include <span>
#include <string_view>

namespace plantarch::builder {

struct Asset {
    std::string_view path;         // "/index.html", "/app.js", ...
    std::string_view contentType;  // "text/html; charset=utf-8", ...
    std::string_view bytes;
};

// Every file of the bundle, sorted by path; "/" is served as "/index.html".
std::span<const Asset> assets();

}  // namespace plantarch::builder
