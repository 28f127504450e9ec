#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <utility>

#include "core/temporary_files.h"
#include "plantarch/Error.h"

namespace plantarch::io {

namespace {

std::atomic<unsigned long> temporaryCounter{0};
/// Unnamed temporaries finished but not yet placed, each holding a descriptor open.
std::atomic<long> heldDescriptors{0};

std::string temporaryName(const std::string& path) {
    return path + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
           std::to_string(temporaryCounter.fetch_add(1, std::memory_order_relaxed));
}

std::string folderOf(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

// Unnamed temporaries need O_TMPFILE and /proc/self/fd to link them by; the environment
// variable PLANTARCH_NAMED_TEMPORARIES=1 turns them off (tests of the named fallback).
bool unnamedWanted() {
    static const bool procFds = ::access("/proc/self/fd", X_OK) == 0;
    const char* off = std::getenv("PLANTARCH_NAMED_TEMPORARIES");
    return procFds && !(off && *off && std::string_view(off) != "0");
}

// Finished unnamed files a process keeps open before naming further ones: a quarter of the
// descriptor limit, at most 256, so that writing thousands of files never runs out.
long maxHeldDescriptors() {
    static const long limit = [] {
        rlimit r{};
        if (::getrlimit(RLIMIT_NOFILE, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return 256L;
        return std::clamp(long(r.rlim_cur / 4), 0L, 256L);
    }();
    return limit;
}

}  // namespace

AtomicFile::AtomicFile(std::string path, std::size_t bufferBytes)
    : path_(std::move(path)), capacity_(std::max(bufferBytes, 2 * kMaxReserve)) {
    if (path_.empty()) throw Error("cannot open for writing: empty file name");
    struct stat st {};
    if (::stat(path_.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw Error("cannot write: is a directory, not a file", {.file = path_});
    refuseSpecialFile(path_, "cannot write");
    buffer_ = std::make_unique_for_overwrite<char[]>(capacity_);  // before the file exists
    if (unnamedWanted()) {
        do {
            fd_ = ::open(folderOf(path_).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
        } while (fd_ < 0 && errno == EINTR);
        if (fd_ >= 0) return;
        // Filesystems without unnamed files say so with one of these; anything else (no
        // such folder, no permission) is the answer for a named file too.
        if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL)
            fail("cannot open for writing", errno);
    }
    openNamed();
}

void AtomicFile::openNamed() {
    // A name left behind by a killed process whose PID has been reused: take the next one.
    for (int attempt = 0;; ++attempt) {
        temp_ = temporaryName(path_);
        slot_ = registerTemporary(temp_.c_str());  // before the file exists: no unregistered moment
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0) return;
        const int err = errno;
        unregisterTemporary(std::exchange(slot_, -1));
        temp_.clear();
        if (err == EINTR) continue;
        if (err != EEXIST || attempt >= 100) fail("cannot open for writing", err);
    }
}

AtomicFile::AtomicFile(AtomicFile&& o) noexcept
    : path_(std::move(o.path_)),
      temp_(std::move(o.temp_)),
      fd_(std::exchange(o.fd_, -1)),
      slot_(std::exchange(o.slot_, -1)),
      held_(std::exchange(o.held_, false)),
      finished_(o.finished_),
      buffer_(std::move(o.buffer_)),
      capacity_(std::exchange(o.capacity_, 0)),
      used_(std::exchange(o.used_, 0)),
      flushed_(std::exchange(o.flushed_, 0)),
      committed_(std::exchange(o.committed_, true)) {  // the moved-from one owns nothing
    o.temp_.clear();
}

AtomicFile::~AtomicFile() {
    closeDescriptor();  // an unnamed temporary vanishes here
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
    unregisterTemporary(slot_);
}

void AtomicFile::closeDescriptor() {
    if (held_) heldDescriptors.fetch_sub(1);
    held_ = false;
    if (fd_ >= 0) ::close(std::exchange(fd_, -1));
}

void AtomicFile::fail(const std::string& what, int err) const {
    throw Error(what + ": " + std::generic_category().message(err), {.file = path_});
}

void AtomicFile::writeAll(const char* data, std::size_t size) {
    while (size > 0) {
        const ::ssize_t n = ::write(fd_, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", errno);
        }
        if (n == 0) fail("cannot write", EIO);
        data += n;
        size -= static_cast<std::size_t>(n);
        flushed_ += static_cast<std::size_t>(n);
    }
}

void AtomicFile::flushBuffer() {
    const std::size_t n = used_;
    used_ = 0;  // even if writing throws, never write these bytes twice
    writeAll(buffer_.get(), n);
}

void AtomicFile::makeRoom(std::size_t) {
    flushBuffer();
}

void AtomicFile::write(const void* data, std::size_t size) {
    const char* bytes = static_cast<const char*>(data);
    if (size <= capacity_ - used_) {
        std::memcpy(buffer_.get() + used_, bytes, size);
        used_ += size;
        return;
    }
    flushBuffer();
    if (size >= capacity_ / 2) {  // large block: skip the copy
        writeAll(bytes, size);
    } else {
        std::memcpy(buffer_.get(), bytes, size);
        used_ = size;
    }
}

void AtomicFile::finish() {
    if (finished_) return;
    flushBuffer();
    buffer_.reset();
    finished_ = true;
    if (temp_.empty()) {  // unnamed: the open descriptor is the file
        held_ = true;
        if (heldDescriptors.fetch_add(1) >= maxHeldDescriptors()) nameTemporary();
        return;
    }
    if (::close(std::exchange(fd_, -1)) != 0) fail("cannot write", errno);
}

void AtomicFile::nameTemporary() {
    if (!temp_.empty()) return;
    const std::string self = "/proc/self/fd/" + std::to_string(fd_);
    for (int attempt = 0;; ++attempt) {
        temp_ = temporaryName(path_);
        slot_ = registerTemporary(temp_.c_str());
        if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temp_.c_str(), AT_SYMLINK_FOLLOW) == 0)
            break;
        const int err = errno;
        unregisterTemporary(std::exchange(slot_, -1));
        temp_.clear();
        if (err != EEXIST || attempt >= 100) fail("cannot write", err);
    }
    closeDescriptor();  // the name now keeps the file
}

void AtomicFile::place() {
    nameTemporary();
    if (::rename(temp_.c_str(), path_.c_str()) != 0) fail("cannot replace file", errno);
    committed_ = true;
    temp_.clear();
    unregisterTemporary(std::exchange(slot_, -1));
}

void AtomicFile::commit() {
    if (committed_) return;
    finish();
    if (holdInOpenOutputSet(*this)) return;
    // Named and renamed back to back: between the two calls the file has a temporary name,
    // which SIGINT and SIGTERM remove but SIGKILL would leave; the window is two system calls.
    place();
}

void writeWholeFile(const std::string& path, std::string_view bytes) {
    AtomicFile file(path, std::min<std::size_t>(bytes.size() + 1, AtomicFile::kDefaultBufferBytes));
    file.write(bytes);
    file.commit();
}

void refuseSpecialFile(const std::string& path, const char* what) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return;
    const char* kind = S_ISFIFO(st.st_mode)                         ? "a FIFO"
                       : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                       : S_ISSOCK(st.st_mode)                       ? "a socket"
                                                                    : nullptr;
    if (!kind) return;
    throw Error(std::string(what) + ": is " + kind +
                    ", not a file (plantarch writes whole files and puts them in place)",
                {.file = path});
}

}  // namespace plantarch::io
