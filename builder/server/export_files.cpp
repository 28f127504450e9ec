// A build's scene written as the command line writes it (plantarch/PlantFiles.h, checked
// paths, all files or none), and zip archives of several files (libzip).

#include "builder/server/export_files.h"

#include <stdlib.h>
#include <sys/stat.h>
#include <zip.h>

#include <fstream>
#include <map>
#include <sstream>

#include "plantarch/Error.h"
#include "plantarch/OutputFiles.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/PlantFiles.h"

namespace plantarch::builder {

namespace {

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read back a file just written", {.file = path.string()});
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The texture images in `folder` an OBJ or USD file named `name`... may have beside it
// (`<stem>_<texture>_<map>.png`), with their inode numbers: those a write adds or replaces
// (writers rename a new file into place) are the ones it wrote.
std::map<fs::path, ino_t> textureImages(const fs::path& folder, const std::string& name) {
    std::map<fs::path, ino_t> found;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string file = entry.path().filename().string();
        struct stat st {};
        if (file.starts_with(name + "_") && entry.path().extension() == ".png" &&
            ::lstat(entry.path().c_str(), &st) == 0 && S_ISREG(st.st_mode))
            found[entry.path()] = st.st_ino;
    }
    return found;
}

}  // namespace

TemporaryFolder::TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "plantarch-builder-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw Error("cannot make a temporary folder", {.file = pattern});
    path_ = pattern;
}

TemporaryFolder::~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

std::vector<std::string> exportFormats() {
    std::vector<std::string> names;
    for (const OutputFormat& f : outputFormats())
        if (f.uses & kBuilderExport) names.emplace_back(f.extension.substr(1));
    return names;
}

std::string exportExtension(const std::string& format) {
    std::string valid;
    for (const std::string& f : exportFormats()) {
        if (format == f) return "." + format;
        valid += (valid.empty() ? "" : ", ") + f;
    }
    throw HttpError{400, "format = \"" + format.substr(0, 40) +
                             "\": unknown export format (valid: " + valid + ")"};
}

std::vector<fs::path> writeSceneFiles(Server::Impl& server, const Scene& scene,
                                      const fs::path& folder, const std::string& name,
                                      const std::string& format, bool perPlant,
                                      const PlantFileOptions& options) {
    const std::string ext = exportExtension(format);
    const std::string path = (folder / (name + ext)).string();
    const bool images =
        options.appearance.style == MaterialStyle::Textured && (ext == ".obj" || ext == ".usda");
    const PlantArchitecture& arch = *scene.arch;
    const std::vector<unsigned> plants = scene.built.plants();
    std::vector<fs::path> files;
    auto withMaterials = [&](const std::string& file) {
        files.push_back(file);
        if (ext == ".obj") files.push_back(fs::path(file).replace_extension(".mtl"));
    };
    std::lock_guard<std::mutex> lock(server.files);
    std::vector<FolderMadeForOutputs> made = makeFoldersForOutputs(folder.string());
    const std::map<fs::path, ino_t> before =
        images ? textureImages(folder, name) : std::map<fs::path, ino_t>{};
    try {
        checkOutputPath(perPlant ? separatePlantIndexName(path) : path);
        OutputSet outputs;
        if (perPlant) {
            writeSeparatePlantFiles(arch, plants, {path}, false, options);
            for (unsigned id : plants) withMaterials(separatePlantFileName(path, id));
            files.push_back(separatePlantIndexName(path));
        } else {
            writePlantFile(arch, plants, path, options);
            withMaterials(path);
        }
        outputs.commit();
        if (images)
            for (const auto& [file, inode] : textureImages(folder, name))
                if (!before.count(file) || before.at(file) != inode) files.push_back(file);
    } catch (...) {
        for (auto m = made.rbegin(); m != made.rend(); ++m) m->remove();
        throw;
    }
    for (FolderMadeForOutputs& m : made) m.keep();
    return files;
}

std::string sceneFileBytes(Server::Impl& server, const Scene& scene, const std::string& format,
                           const PlantFileOptions& options) {
    const TemporaryFolder temp;
    const std::vector<fs::path> files =
        writeSceneFiles(server, scene, temp.path(), "scene", format, false, options);
    return readBytes(files.front());
}

std::string zipArchive(const std::vector<fs::path>& files, const fs::path& base) {
    const TemporaryFolder temp;
    const std::string archive = (temp.path() / "files.zip").string();
    int error = 0;
    zip_t* zip = zip_open(archive.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!zip) throw Error("cannot make a zip archive (libzip error " + std::to_string(error) + ")");
    for (const fs::path& f : files) {
        const std::string name = f.lexically_relative(base).generic_string();
        zip_source_t* source = zip_source_file(zip, f.c_str(), 0, -1);
        if (!source || zip_file_add(zip, name.c_str(), source, ZIP_FL_ENC_UTF_8) < 0) {
            if (source) zip_source_free(source);
            const std::string why = zip_strerror(zip);
            zip_discard(zip);
            throw Error("cannot add a file to the zip archive: " + why, {.file = f.string()});
        }
    }
    if (zip_close(zip) != 0) {
        const std::string why = zip_strerror(zip);
        zip_discard(zip);
        throw Error("cannot write the zip archive: " + why);
    }
    return readBytes(archive);
}

}  // namespace plantarch::builder
