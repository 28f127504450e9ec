#pragma once
// AtomicFile: writes a file so that it appears whole or not at all.
//
// Bytes go into `<path>.tmp-<pid>-<counter>` in the target's directory (so the final rename
// stays on one filesystem) through a large in-memory buffer. commit() flushes, closes and
// renames the temporary over the target. If the AtomicFile is destroyed without commit()
// (an exception on the way), the temporary is removed and the target is untouched.
//
// Durability: no fsync. An interrupted process or a failed write never leaves a partial
// target; surviving a power cut right after commit() is left to the filesystem.
//
// Failures throw plantarch::Error whose file is the target path, for example
//   out/scene.obj: cannot open for writing: No such file or directory

#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

namespace plantarch::io {

class AtomicFile {
public:
    static constexpr std::size_t kDefaultBufferBytes = std::size_t(4) << 20;
    /// The longest reserve() a caller may ask for.
    static constexpr std::size_t kMaxReserve = 4096;

    /// Creates the temporary file; throws Error when it cannot be created.
    explicit AtomicFile(std::string path, std::size_t bufferBytes = kDefaultBufferBytes);
    ~AtomicFile();
    AtomicFile(AtomicFile&& other) noexcept;
    AtomicFile& operator=(AtomicFile&&) = delete;
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, std::size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }

    /// Room for at least `size` (<= kMaxReserve) bytes, to be filled by the caller and
    /// handed back with advance(end). Formatting straight into the buffer avoids a copy.
    char* reserve(std::size_t size) {
        if (capacity_ - used_ < size) makeRoom(size);
        return buffer_.get() + used_;
    }
    /// Marks the bytes up to `end` (inside the last reserve()) as written.
    void advance(const char* end) { used_ = static_cast<std::size_t>(end - buffer_.get()); }

    /// Flushes and closes the temporary file, releasing the buffer; the file is not yet in
    /// place. Lets a caller finish several files before committing them all.
    void finish();
    /// finish() if needed, then renames the temporary over the target.
    void commit();

    const std::string& path() const { return path_; }
    const std::string& temporaryPath() const { return temp_; }
    /// Bytes written so far (flushed or buffered).
    std::size_t size() const { return flushed_ + used_; }

private:
    void makeRoom(std::size_t size);
    void flushBuffer();
    void writeAll(const char* data, std::size_t size);
    [[noreturn]] void fail(const std::string& what, int err) const;

    std::string path_;
    std::string temp_;
    int fd_ = -1;
    std::unique_ptr<char[]> buffer_;
    std::size_t capacity_ = 0;
    std::size_t used_ = 0;
    std::size_t flushed_ = 0;
    bool committed_ = false;
};

}  // namespace plantarch::io
