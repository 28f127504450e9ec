#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>

#include "plantarch/Error.h"

namespace plantarch::io {

namespace {

std::atomic<unsigned long> temporaryCounter{0};

std::string temporaryName(const std::string& path) {
    return path + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
           std::to_string(temporaryCounter.fetch_add(1, std::memory_order_relaxed));
}

}  // namespace

AtomicFile::AtomicFile(std::string path, std::size_t bufferBytes)
    : path_(std::move(path)),
      temp_(temporaryName(path_)),
      capacity_(std::max(bufferBytes, 2 * kMaxReserve)) {
    if (path_.empty()) throw Error("cannot open for writing: empty file name");
    buffer_ = std::make_unique_for_overwrite<char[]>(capacity_);  // before the file exists
    // A name left behind by a killed process whose PID has been reused: take the next one.
    for (int attempt = 0;; ++attempt) {
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0) break;
        const int err = errno;
        if (err == EINTR) continue;
        if (err != EEXIST || attempt >= 100) fail("cannot open for writing", err);
        temp_ = temporaryName(path_);
    }
}

AtomicFile::AtomicFile(AtomicFile&& o) noexcept
    : path_(std::move(o.path_)),
      temp_(std::move(o.temp_)),
      fd_(std::exchange(o.fd_, -1)),
      buffer_(std::move(o.buffer_)),
      capacity_(std::exchange(o.capacity_, 0)),
      used_(std::exchange(o.used_, 0)),
      flushed_(std::exchange(o.flushed_, 0)),
      committed_(std::exchange(o.committed_, true)) {}  // the moved-from one owns nothing

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
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
    if (fd_ < 0) return;
    flushBuffer();
    buffer_.reset();
    const int fd = std::exchange(fd_, -1);
    if (::close(fd) != 0) fail("cannot write", errno);
}

void AtomicFile::commit() {
    if (committed_) return;
    finish();
    if (::rename(temp_.c_str(), path_.c_str()) != 0) fail("cannot replace file", errno);
    committed_ = true;
}

}  // namespace plantarch::io
