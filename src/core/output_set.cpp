// OutputSet, checkOutputPath and the other pieces of OutputFiles.h.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <system_error>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/temporary_files.h"
#include "plantarch/Error.h"
#include "plantarch/OutputFiles.h"

namespace plantarch {

struct OutputSet::Held {
    std::vector<io::AtomicFile> files;
};

namespace {

std::mutex openSetMutex;
std::vector<io::AtomicFile>* openSet = nullptr;  // the open set's files, under openSetMutex

std::string message(int err) {
    return std::generic_category().message(err);
}

bool isDirectory(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// Whether a new file can be made in `folder`: an unnamed one, gone when closed, or where the
// filesystem has none, a named one removed at once. Returns 0 or the errno of the failure.
int tryCreateIn(const std::string& folder) {
    int fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
    if (fd >= 0) {
        ::close(fd);
        return 0;
    }
    if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) return errno;
    const std::string probe =
        folder + "/.plantarch-probe-" + std::to_string(static_cast<long>(::getpid()));
    fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) return errno == EEXIST ? 0 : errno;
    ::close(fd);
    ::unlink(probe.c_str());
    return 0;
}

}  // namespace

void checkOutputPath(const std::string& path) {
    if (path.empty()) throw Error("cannot write: empty file name");
    if (path.back() == '/' || isDirectory(path))
        throw Error("cannot write: is a directory, not a file", {.file = path});
    io::refuseSpecialFile(path, "cannot write");
    const std::size_t slash = path.find_last_of('/');
    const std::string folder =
        slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
    struct stat st {};
    if (::stat(folder.c_str(), &st) != 0)
        throw Error("cannot write: no folder " + folder + ": " + message(errno), {.file = path});
    if (!S_ISDIR(st.st_mode))
        throw Error("cannot write: " + folder + " is not a folder", {.file = path});
    if (const int err = tryCreateIn(folder))
        throw Error("cannot write in folder " + folder + ": " +
                        (err == ENOENT ? std::string("it does not take new files") : message(err)),
                    {.file = path});
}

OutputSet::OutputSet() : held_(std::make_unique<Held>()) {
    const std::lock_guard lock(openSetMutex);
    if (openSet) throw Error("an output set is already open: commit or discard it first");
    openSet = &held_->files;
}

OutputSet::~OutputSet() {
    const std::lock_guard lock(openSetMutex);
    if (openSet == &held_->files) openSet = nullptr;
    // held_'s files are destroyed uncommitted: their temporaries go, the targets stay as they were
}

std::size_t OutputSet::size() const {
    const std::lock_guard lock(openSetMutex);
    return held_->files.size();
}

void OutputSet::commit() {
    std::vector<io::AtomicFile> files;
    {
        const std::lock_guard lock(openSetMutex);
        if (openSet == &held_->files) openSet = nullptr;
        files.swap(held_->files);
    }
    // Named first (registered for removal on SIGINT/SIGTERM) and every target checked, so a
    // failure so far leaves every target as it was; then renamed one after the other.
    for (io::AtomicFile& f : files) {
        if (isDirectory(f.path()))
            throw Error("cannot replace file: is a directory, not a file", {.file = f.path()});
        io::refuseSpecialFile(f.path(), "cannot replace file");
        f.nameTemporary();
    }
    for (io::AtomicFile& f : files) f.place();
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
    io::writeWholeFile(path, bytes);
}

void removeTemporaryFilesOnSignal() {
    io::installTemporaryFileCleanup();
}

FolderMadeForOutputs::FolderMadeForOutputs(std::string path)
    : path_(std::move(path)), slot_(io::registerTemporaryFolder(path_.c_str())) {}

FolderMadeForOutputs::~FolderMadeForOutputs() {
    keep();
}

FolderMadeForOutputs::FolderMadeForOutputs(FolderMadeForOutputs&& other) noexcept
    : path_(std::move(other.path_)),
      slot_(std::exchange(other.slot_, -1)),
      active_(std::exchange(other.active_, false)) {}

void FolderMadeForOutputs::remove() {
    if (!active_) return;
    ::rmdir(path_.c_str());  // a folder with anything in it stays
    keep();
}

void FolderMadeForOutputs::keep() {
    io::unregisterTemporaryFolder(slot_);
    slot_ = -1;
    active_ = false;
}

namespace io {

bool holdInOpenOutputSet(AtomicFile& file) {
    const std::lock_guard lock(openSetMutex);
    if (!openSet) return false;
    openSet->push_back(std::move(file));
    return true;
}

}  // namespace io

std::vector<FolderMadeForOutputs> makeFoldersForOutputs(const std::string& folder) {
    namespace fs = std::filesystem;
    std::vector<fs::path> missing;  // innermost first
    std::error_code ec;
    for (fs::path p = folder; !p.empty() && !fs::exists(fs::symlink_status(p, ec));
         p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    std::vector<FolderMadeForOutputs> made;
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (!fs::create_directory(*it, ec) && ec) {
            for (auto m = made.rbegin(); m != made.rend(); ++m) m->remove();
            throw Error("cannot create folder " + it->string() + ": " + ec.message(),
                        {.file = it->string()});
        }
        made.emplace_back(it->string());
    }
    return made;
}

}  // namespace plantarch
