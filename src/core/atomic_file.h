#pragma once
// AtomicFile: writes a file so that it appears whole or not at all.
//
// Bytes go through a large in-memory buffer into a temporary file in the target's folder (so
// the final rename stays on one filesystem). On Linux the temporary has no name (O_TMPFILE):
// if the process dies, even by SIGKILL, the kernel frees it and nothing is left in the
// folder. It gets a name, `<path>.tmp-<pid>-<n>`, only when it is put in place: linked under
// that name and at once renamed over the target (link() cannot replace a file, rename() can).
// Where the filesystem has no unnamed files (or PLANTARCH_NAMED_TEMPORARIES=1 is set, for
// tests), the temporary is named from the start; named temporaries are registered so that
// SIGINT and SIGTERM remove them (temporary_files.h).
//
// commit() puts the file in place, or, while an OutputSet is open, hands it to the set, which
// puts all its files in place together (OutputFiles.h). If the AtomicFile is destroyed
// uncommitted (an exception on the way), the temporary goes and the target is untouched.
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

    /// Creates the temporary file; throws Error when it cannot be created or `path` is a
    /// directory.
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

    /// Flushes the file and releases the buffer; the file is complete but not yet in place.
    /// Lets a caller finish several files before committing them all. An unnamed temporary
    /// keeps its descriptor open (it would vanish when closed) unless the process already
    /// holds many such: it is then named now, as a registered named temporary.
    void finish();
    /// finish() if needed, then puts the file in place, or hands it to the open OutputSet.
    void commit();

    const std::string& path() const { return path_; }
    /// The temporary's name; empty while it has none (an unnamed temporary).
    const std::string& temporaryPath() const { return temp_; }
    /// Bytes written so far (flushed or buffered).
    std::size_t size() const { return flushed_ + used_; }

    // ---- for OutputSet (output_set.cpp) ----
    /// Gives a finished unnamed temporary its name in the target's folder (registered for
    /// removal on SIGINT/SIGTERM); a named one is left as it is.
    void nameTemporary();
    /// Renames the named temporary over the target. Throws Error naming the target.
    void place();

private:
    void makeRoom(std::size_t size);
    void flushBuffer();
    void writeAll(const char* data, std::size_t size);
    void openNamed();
    void closeDescriptor();
    [[noreturn]] void fail(const std::string& what, int err) const;

    std::string path_;
    std::string temp_;  ///< the temporary's name; empty while it has none
    int fd_ = -1;
    int slot_ = -1;      ///< registration of temp_ for removal on signals
    bool held_ = false;  ///< an unnamed file whose open descriptor is counted as held
    bool finished_ = false;
    std::unique_ptr<char[]> buffer_;
    std::size_t capacity_ = 0;
    std::size_t used_ = 0;
    std::size_t flushed_ = 0;
    bool committed_ = false;
};

/// Hands a committed file to the OutputSet open in this process, if any; true when it took
/// it (output_set.cpp).
bool holdInOpenOutputSet(AtomicFile& file);

/// Writes `bytes` to `path` through an AtomicFile.
void writeWholeFile(const std::string& path, std::string_view bytes);

/// Throws plantarch::Error ("<what>: is a FIFO, not a file ...", naming the path) when `path`
/// names a FIFO, a device or a socket: putting a file in place renames over its target, which
/// would replace the node with a regular file. A symbolic link is replaced, not followed.
void refuseSpecialFile(const std::string& path, const char* what);

}  // namespace plantarch::io
