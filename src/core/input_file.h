#pragma once
// Opening and reading input files, the one way every reader of plantarch does it.
//
// A path read from the command line or named inside another file is opened without blocking
// (O_NONBLOCK, so a FIFO with no writer does not wait), then the opened descriptor is
// checked (fstat, so nothing can be swapped in between): anything but a regular file (a
// directory, a FIFO, a device, a socket) is refused, and so is a file over the size limit of
// its kind, before a byte is read. Each refusal is one line naming the file:
//
//   /dev/zero: is a device, not a species file
//   big.obj: too large for an OBJ file: 5.1 GiB (5476083712 bytes) (valid: at most 4 GiB)
//
// Text kinds are also checked to be text: UTF-16 or UTF-32 text, or binary data (a NUL
// byte), is named as such instead of being parsed as garbage.

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

namespace plantarch::io {

inline constexpr std::uint64_t kMiB = std::uint64_t(1) << 20;

/// What a file is read as: its name in messages, its size limit, whether it is text.
struct InputKind {
    std::string_view what;  ///< "species file"
    std::uint64_t maxBytes;
    bool text = true;
    /// The same limit under another name ("obstacle file" for an OBJ file).
    constexpr InputKind named(std::string_view name) const { return {name, maxBytes, text}; }
};

// The kinds plantarch reads and their limits (docs/formats.md lists them).
inline constexpr InputKind kSpeciesFile{"species file", 16 * kMiB};
inline constexpr InputKind kPlantFile{"plant structure file", 256 * kMiB};  // also <helios>
inline constexpr InputKind kPlantStringFile{"plant string file", 256 * kMiB};
inline constexpr InputKind kProjectFile{"project file", 16 * kMiB};
inline constexpr InputKind kDatasetSpecFile{"dataset spec", 16 * kMiB};
inline constexpr InputKind kOBJFile{"OBJ file", 4096 * kMiB};
inline constexpr InputKind kMTLFile{"material file", 64 * kMiB};
inline constexpr InputKind kAttractionFile{"attraction point file", 256 * kMiB};
inline constexpr InputKind kWeatherFile{"weather file", 64 * kMiB};
inline constexpr InputKind kImageFile{"image file", 256 * kMiB, false};

/// `what` with "a" or "an" in front: "an OBJ file", "a species file".
std::string withArticle(std::string_view what);

/// "cannot open <what>: <the system's reason>", from errno as a failed open left it.
std::string cannotOpen(std::string_view what);

/// "12 bytes", "3.2 MiB (3355443 bytes)": a file size for messages.
std::string sizeText(std::uint64_t bytes);

/// An input file opened for reading and checked (see above). Throws plantarch::Error naming
/// the path when it cannot be opened, is not a regular file or is over its kind's limit.
class InputFile {
public:
    InputFile(const std::string& path, const InputKind& kind);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::string& path() const { return path_; }
    /// The size fstat gave when it was opened.
    std::uint64_t size() const { return size_; }

    /// Reads up to `n` bytes into `buffer`; 0 at the end of the file. Throws when reading
    /// fails or the file has grown past its limit meanwhile.
    std::size_t read(char* buffer, std::size_t n);
    /// Everything from where reading stands to the end; a text kind is checked to be text.
    std::string readAll();

private:
    std::string path_;
    InputKind kind_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
    std::uint64_t read_ = 0;
};

/// Calls f(line, number) for each line of `file` from where reading stands (without its
/// '\n'; numbers from 1), in blocks of up to 1 MiB.
template <class F>
void forEachLine(InputFile& file, F&& f) {
    const std::size_t blockSize = std::size_t(std::min<std::uint64_t>(file.size() + 1, kMiB));
    std::string block(std::max<std::size_t>(blockSize, 4096), '\0');
    std::string carry;
    int number = 0;
    for (std::size_t n; (n = file.read(block.data(), block.size())) > 0;) {
        const std::string_view data(block.data(), n);
        std::size_t start = 0;
        for (std::size_t nl; (nl = data.find('\n', start)) != std::string_view::npos;
             start = nl + 1) {
            if (carry.empty()) {
                f(data.substr(start, nl - start), ++number);
            } else {
                carry.append(data.substr(start, nl - start));
                f(std::string_view(carry), ++number);
                carry.clear();
            }
        }
        carry.append(data.substr(start));
    }
    if (!carry.empty()) f(std::string_view(carry), ++number);
}

/// The whole content of the file at `path`, read as `kind` (see above).
std::string readWholeFile(const std::string& path, const InputKind& kind);
/// As above for a file of no kind of its own (a limit of 256 MiB, text).
std::string readWholeFile(const std::string& path, std::string_view what);

/// Opens `path` as `kind` and closes it: throws what reading it would throw before the first
/// byte (for a file handed to another library, or checked before work starts).
void checkInputFile(const std::string& path, const InputKind& kind);

/// Throws plantarch::Error naming `path` when `start`, the first bytes (or all) of a file of
/// `kind`, is UTF-16 or UTF-32 text, or holds a NUL byte (binary data, not text).
void checkText(std::string_view start, const std::string& path, const InputKind& kind);

}  // namespace plantarch::io
