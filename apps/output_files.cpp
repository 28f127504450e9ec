// CommandOutputs: the files of one command checked before any work and put in place together
// at its end.

#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"

namespace plantarch::cli {

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
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (folder.empty()) return;
    std::vector<FolderMadeForOutputs> made;
    try {
        made = makeFoldersForOutputs(folder.string());
    } catch (const Error& e) {
        throw Error(e.message(), {.file = path});  // named by the output it is for
    }
    for (FolderMadeForOutputs& f : made) madeFolders_.push_back(std::move(f));
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
