#pragma once
// Writing a build's scene to files with the command line's own writers (so an export equals
// what `plantarch project run` writes), in the output folder or in a temporary folder for a
// download, and zipping several files.

#include <filesystem>
#include <string>
#include <vector>

#include "builder/server/server_impl.h"
#include "plantarch/PlantFiles.h"

namespace plantarch::builder {

/// The export formats the builder offers ("obj", "ply" ...), from plantarch's table of output
/// formats (those marked kBuilderExport), in its order.
std::vector<std::string> exportFormats();
/// The file extension of an export format ("glb" -> ".glb"); 400 for an unknown format.
std::string exportExtension(const std::string& format);

/// Writes the scene into `folder`/`name`<ext> (with `perPlant`, one file per plant and the
/// index `name`_index.json, as `--separate` does) with `options` (the export's variant,
/// export_options.h), all or none. Returns the files written, texture images included.
/// Holds the server's file lock while it writes.
std::vector<std::filesystem::path> writeSceneFiles(Server::Impl& server, const Scene& scene,
                                                   const std::filesystem::path& folder,
                                                   const std::string& name,
                                                   const std::string& format, bool perPlant,
                                                   const PlantFileOptions& options = {});

/// The scene as one file of `format`, its bytes (written in a temporary folder, removed).
std::string sceneFileBytes(Server::Impl& server, const Scene& scene, const std::string& format,
                           const PlantFileOptions& options = {});

/// A zip archive of `files`, each stored under its path relative to `base`.
std::string zipArchive(const std::vector<std::filesystem::path>& files,
                       const std::filesystem::path& base);

/// A folder of its own under the system's temporary folder, removed with everything in it
/// when this goes.
class TemporaryFolder {
public:
    TemporaryFolder();
    ~TemporaryFolder();
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace plantarch::builder
