#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/image_file.h"
#include "plantarch/Error.h"
#include "plantarch/InputFiles.h"

namespace plantarch::io {

namespace {

// What a file that is not a regular one is, for "is a FIFO, not a species file".
const char* fileTypeName(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

[[noreturn]] void tooLarge(const std::string& path, const InputKind& kind, std::uint64_t bytes) {
    throw Error("too large for " + withArticle(kind.what) + ": " + sizeText(bytes),
                {.file = path, .validRange = "at most " + sizeText(kind.maxBytes)});
}

int lineOf(std::string_view text, std::size_t offset) {
    return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(offset), '\n'));
}

}  // namespace

std::string withArticle(std::string_view what) {
    const bool vowel =
        !what.empty() && std::string_view("aeiouAEIOU").find(what[0]) != std::string_view::npos;
    return (vowel ? "an " : "a ") + std::string(what);
}

std::string cannotOpen(std::string_view what) {
    const int err = errno;
    std::string text = "cannot open " + std::string(what);
    if (err != 0) text += std::string(": ") + std::strerror(err);
    return text;
}

std::string sizeText(std::uint64_t bytes) {
    if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
    static const char* const units[] = {"KiB", "MiB", "GiB", "TiB"};
    double v = double(bytes);
    int unit = -1;
    while (v >= 1024.0 && unit < 3) {
        v /= 1024.0;
        ++unit;
    }
    char number[32];
    if (v == double(std::uint64_t(v)))
        std::snprintf(number, sizeof number, "%.0f", v);
    else
        std::snprintf(number, sizeof number, "%.1f", v);
    std::string text = std::string(number) + " " + units[unit];
    // A round number of units says it all; any other keeps the exact count.
    if (bytes % (std::uint64_t(1) << (10 * (unit + 1))) != 0)
        text += " (" + std::to_string(bytes) + " bytes)";
    return text;
}

// ---- InputFile ---------------------------------------------------------------------------

InputFile::InputFile(const std::string& path, const InputKind& kind) : path_(path), kind_(kind) {
    if (path.empty())
        throw Error("no file named: an empty path", {.validRange = withArticle(kind.what)});
    errno = 0;
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd_ < 0) {
        if (errno == EISDIR)  // not reached on Linux (a directory opens read-only)
            throw Error("is a directory, not " + withArticle(kind.what), {.file = path});
        throw Error(cannotOpen(kind.what), {.file = path});
    }
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
        const std::string why = std::strerror(errno);
        ::close(fd_);
        throw Error("cannot read " + std::string(kind.what) + ": " + why, {.file = path});
    }
    if (!S_ISREG(st.st_mode)) {
        ::close(fd_);
        throw Error(
            std::string("is ") + fileTypeName(st.st_mode) + ", not " + withArticle(kind.what),
            {.file = path});
    }
    size_ = std::uint64_t(st.st_size);
    if (size_ > kind.maxBytes) {
        ::close(fd_);
        tooLarge(path, kind, size_);
    }
    // Reading a regular file never blocks; plain blocking reads from here on.
    const int flags = ::fcntl(fd_, F_GETFL);
    if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
}

InputFile::~InputFile() {
    if (fd_ >= 0) ::close(fd_);
}

std::size_t InputFile::read(char* buffer, std::size_t n) {
    for (;;) {
        const ssize_t got = ::read(fd_, buffer, n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0)
            throw Error("cannot read " + std::string(kind_.what) + ": " + std::strerror(errno),
                        {.file = path_});
        read_ += std::uint64_t(got);
        if (read_ > kind_.maxBytes) tooLarge(path_, kind_, read_);  // it grew meanwhile
        return std::size_t(got);
    }
}

std::string InputFile::readAll() {
    std::string text;
    std::size_t used = 0;
    // The size fstat gave, and one byte more to see the end (or growth) at once.
    text.resize(std::size_t(size_ - std::min(size_, read_)) + 1);
    for (;;) {
        if (used == text.size()) text.resize(std::max<std::size_t>(2 * text.size(), 4096));
        const std::size_t got = read(text.data() + used, text.size() - used);
        if (got == 0) break;
        used += got;
    }
    text.resize(used);
    if (kind_.text) checkText(text, path_, kind_);
    return text;
}

std::string readWholeFile(const std::string& path, const InputKind& kind) {
    return InputFile(path, kind).readAll();
}

std::string readWholeFile(const std::string& path, std::string_view what) {
    return readWholeFile(path, InputKind{what, 256 * kMiB});
}

void checkInputFile(const std::string& path, const InputKind& kind) {
    InputFile file(path, kind);
}

void checkText(std::string_view start, const std::string& path, const InputKind& kind) {
    const auto byte = [&](std::size_t i) {
        return i < start.size() ? static_cast<unsigned char>(start[i]) : 0x100u;
    };
    const bool utf32 =
        (byte(0) == 0xFF && byte(1) == 0xFE && byte(2) == 0 && byte(3) == 0) ||
        (byte(0) == 0 && byte(1) == 0 && byte(2) == 0xFE && byte(3) == 0xFF) ||
        (byte(0) != 0 && byte(0) < 0x80 && byte(1) == 0 && byte(2) == 0 && byte(3) == 0) ||
        (byte(0) == 0 && byte(1) == 0 && byte(2) == 0 && byte(3) != 0 && byte(3) < 0x80);
    if (utf32)
        throw Error("is UTF-32 text; plantarch reads " + std::string(kind.what) +
                        "s as UTF-8 (save it as UTF-8)",
                    {.file = path});
    const bool utf16 = (byte(0) == 0xFF && byte(1) == 0xFE) ||
                       (byte(0) == 0xFE && byte(1) == 0xFF) ||
                       (byte(0) != 0 && byte(0) < 0x80 && byte(1) == 0) ||
                       (byte(0) == 0 && byte(1) != 0 && byte(1) < 0x80);
    if (utf16)
        throw Error("is UTF-16 text; plantarch reads " + std::string(kind.what) +
                        "s as UTF-8 (save it as UTF-8)",
                    {.file = path});
    // A PNG or JPEG image renamed (signatures no text starts with) is named as such.
    if (const std::string_view image = imageFormatName(start); image == "PNG" || image == "JPEG")
        throw Error("is " + withArticle(image) + " image, not " + withArticle(kind.what),
                    {.file = path});
    const std::size_t nul = start.find('\0');
    if (nul != std::string_view::npos)
        throw Error("binary data (a NUL byte), not " + withArticle(kind.what),
                    {.file = path, .line = lineOf(start, nul)});
}

}  // namespace plantarch::io

namespace plantarch {

namespace {

io::InputKind kindOf(InputFileKind kind) {
    switch (kind) {
        case InputFileKind::Species:
            return io::kSpeciesFile;
        case InputFileKind::PlantStructure:
            return io::kPlantFile;
        case InputFileKind::PlantStrings:
            return io::kPlantStringFile;
        case InputFileKind::Project:
            return io::kProjectFile;
        case InputFileKind::OBJ:
            return io::kOBJFile;
        case InputFileKind::Material:
            return io::kMTLFile;
        case InputFileKind::AttractionPoints:
            return io::kAttractionFile;
        case InputFileKind::Image:
            return io::kImageFile;
        case InputFileKind::Weather:
            return io::kWeatherFile;
    }
    return io::kImageFile;
}

}  // namespace

std::uint64_t inputFileLimit(InputFileKind kind) {
    return kindOf(kind).maxBytes;
}

void checkInputFile(const std::string& path, InputFileKind kind, const std::string& what) {
    const io::InputKind k = kindOf(kind);
    io::checkInputFile(path, what.empty() ? k : k.named(what));
}

std::string readInputFile(const std::string& path, InputFileKind kind, const std::string& what) {
    const io::InputKind k = kindOf(kind);
    return io::readWholeFile(path, what.empty() ? k : k.named(what));
}

}  // namespace plantarch
