#pragma once
// Reading input files whole, with one clear line when that is not possible: a directory
// where a file was expected is named as such (reading one would look like an empty file).

#include <string>
#include <string_view>

namespace plantarch::io {

/// `what` with "a" or "an" in front: "an OBJ file", "a species file".
std::string withArticle(std::string_view what);

/// Throws plantarch::Error "is a directory, not a <what>" naming `path` when it is one.
void rejectDirectory(const std::string& path, std::string_view what);

/// "cannot open <what>: <the system's reason>", from errno as a failed open left it.
std::string cannotOpen(std::string_view what);

/// The whole content of the file at `path`. Throws plantarch::Error naming `path` when it is
/// a directory, cannot be opened ("cannot open <what>") or read.
std::string readWholeFile(const std::string& path, std::string_view what);

}  // namespace plantarch::io
