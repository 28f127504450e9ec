// The output formats of the plantarch command, declared once, and CommandOutputs: the files
// of one command checked before any work and put in place together at its end.

#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"

namespace plantarch::cli {

namespace {

// Every file format a command writes, by extension (lower case). Help texts, the checks
// before work and the error messages listing valid extensions are all made from this table.
constexpr OutputFormat kOutputFormats[] = {
    {".obj", "Wavefront OBJ mesh with its .mtl materials", kSceneOutput},
    {".ply", "PLY mesh, or a point cloud with --points", kSceneOutput | kScanOutput},
    {".glb", "binary glTF", kSceneOutput | kAnimationOutput},
    {".gltf", "glTF", kSceneOutput | kAnimationOutput},
    {".usda", "USD text", kSceneOutput | kAnimationOutput},
    {".png", "picture", kSceneOutput | kPictureOutput | kDepthOutput},
    {".npz", "NumPy point cloud (with --points)", kSceneOutput | kScanOutput},
    {".npy", "NumPy array of depths in metres", kDepthOutput},
    {".xml", "plant structure file", kPlantOutput},
    {".helios.xml", "plant structure file in the Helios layout", kPlantOutput},
    {".txt", "plant strings, one line per plant", kPlantOutput},
    {".csv", "quantitative structure model (cylinders)", kPlantOutput},
};

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

}  // namespace

std::span<const OutputFormat> outputFormats() {
    return kOutputFormats;
}

std::string lowerExtension(const std::string& path) {
    return lower(std::filesystem::path(path).extension().string());
}

const OutputFormat* outputFormat(const std::string& path, unsigned uses) {
    const std::string name = lower(std::filesystem::path(path).filename().string());
    const OutputFormat* best = nullptr;
    for (const OutputFormat& f : kOutputFormats)
        if ((f.uses & uses) && name.size() > f.extension.size() && name.ends_with(f.extension) &&
            (!best || f.extension.size() > best->extension.size()))
            best = &f;
    return best;
}

std::string outputExtensions(unsigned uses) {
    std::string list;
    for (const OutputFormat& f : kOutputFormats)
        if (f.uses & uses) list += (list.empty() ? "" : ", ") + std::string(f.extension);
    return list;
}

void requireOutputFormat(const std::string& path, unsigned uses, const std::string& what) {
    if (outputFormat(path, uses)) return;
    const std::string ext = lowerExtension(path);
    if (ext.empty())
        throw Error(what + ": the name has no extension",
                    {.file = path, .validRange = outputExtensions(uses)});
    throw Error(what, {.file = path, .value = ext, .validRange = outputExtensions(uses)});
}

// ---- CommandOutputs ------------------------------------------------------------------------

CommandOutputs::CommandOutputs(const std::vector<std::string>& paths, bool endsProcess)
    : endsProcess_(endsProcess) {
    try {
        for (const std::string& path : paths) add(path);
    } catch (...) {
        removeMadeFolders();  // the destructor does not run for a constructor that throws
        throw;
    }
    set_.emplace();
}

CommandOutputs::~CommandOutputs() {
    set_.reset();  // uncommitted files are discarded
    if (!committed_) removeMadeFolders();
}

void CommandOutputs::removeMadeFolders() {
    // Deepest first; a folder with anything in it stays.
    for (auto it = madeFolders_.rbegin(); it != madeFolders_.rend(); ++it) it->remove();
    madeFolders_.clear();
}

void CommandOutputs::makeFolders(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) return;
    std::vector<fs::path> missing;  // innermost first
    std::error_code ec;
    for (fs::path p = folder; !p.empty() && !fs::exists(fs::symlink_status(p, ec));
         p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (!fs::create_directory(*it, ec) && ec)
            throw Error("cannot create folder " + it->string() + ": " + ec.message(),
                        {.file = path});
        madeFolders_.emplace_back(it->string());
    }
}

namespace {

// The same file as far as the names tell (a/../b.obj and b.obj), without touching the disk
// for files that do not exist yet.
std::filesystem::path sameFileKey(const std::string& path) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    if (ec) return std::filesystem::path(path).lexically_normal();
    const std::filesystem::path full = std::filesystem::weakly_canonical(absolute, ec);
    return ec ? absolute.lexically_normal() : full;
}

}  // namespace

void CommandOutputs::add(const std::string& path) {
    const std::filesystem::path key = sameFileKey(path);
    for (const std::filesystem::path& seen : paths_)
        if (seen == key)
            throw Error("cannot write: the same file is named twice as an output", {.file = path});
    makeFolders(path);
    checkOutputPath(path);
    // An OBJ brings its material library along.
    if (lowerExtension(path) == ".obj") {
        std::error_code ec;
        const std::string mtl = std::filesystem::path(path).replace_extension(".mtl").string();
        if (std::filesystem::is_directory(mtl, ec))
            throw Error("cannot write its materials: " + mtl + " is a directory", {.file = path});
    }
    paths_.push_back(key);
}

void CommandOutputs::requireNotAnInput(const std::string& input, const std::string& option) {
    const std::filesystem::path key = sameFileKey(input);
    for (const std::filesystem::path& seen : paths_)
        if (seen == key)
            throw Error("cannot write over an input of the same command",
                        {.file = input, .parameter = option});
}

void CommandOutputs::commit() {
    if (endsProcess_) {
        if (const std::string failure = standardOutputFailure(); !failure.empty())
            throw Error(failure);
        // The command has succeeded from here: an interrupt now would leave its files in
        // place and report failure, so SIGINT and SIGTERM wait (until the exit discards them).
        sigset_t held;
        sigemptyset(&held);
        sigaddset(&held, SIGINT);
        sigaddset(&held, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &held, nullptr);
    }
    if (set_) set_->commit();
    committed_ = true;
    for (FolderMadeForOutputs& f : madeFolders_) f.keep();
}

}  // namespace plantarch::cli
