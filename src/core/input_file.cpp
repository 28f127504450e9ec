#include "core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "plantarch/Error.h"

namespace plantarch::io {

std::string withArticle(std::string_view what) {
    const bool vowel =
        !what.empty() && std::string_view("aeiouAEIOU").find(what[0]) != std::string_view::npos;
    return (vowel ? "an " : "a ") + std::string(what);
}

void rejectDirectory(const std::string& path, std::string_view what) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw Error("is a directory, not " + withArticle(what), {.file = path});
}

std::string cannotOpen(std::string_view what) {
    const int err = errno;
    std::string text = "cannot open " + std::string(what);
    if (err != 0) text += std::string(": ") + std::strerror(err);
    return text;
}

std::string readWholeFile(const std::string& path, std::string_view what) {
    rejectDirectory(path, what);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(cannotOpen(what), {.file = path});
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error("cannot read " + std::string(what), {.file = path});
    return text.str();
}

}  // namespace plantarch::io
