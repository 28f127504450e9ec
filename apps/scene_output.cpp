// Writing a scene in the format its file extension names; shared by every subcommand that
// produces geometry.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/Render.h"

namespace plantarch::cli {

std::string sceneFileExtensions() {
    return ".obj, .ply, .png";
}

void writeSceneFile(const Context& ctx, const std::string& path, const GlobalOptions& g) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") {
        writeOBJ(ctx, path);
    } else if (ext == ".ply") {
        writePLY(ctx, path);
    } else if (ext == ".png") {
        RenderOptions o;
        o.progress = terminalProgress();
        o.seed = g.seed;
        writePNG(render(ctx, o), path);
    } else {
        throw Error(
            "unknown output format",
            {.file = path, .value = ext.empty() ? path : ext, .validRange = sceneFileExtensions()});
    }
    info(g, "wrote " + path);
}

}  // namespace plantarch::cli
