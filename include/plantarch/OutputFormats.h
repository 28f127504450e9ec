#pragma once
// Every file format plantarch writes, by extension, declared once: the command line's checks
// and help texts, the Python writers, the builder's export list and their error messages are
// all made from this table, so a wrong extension is refused everywhere with the same line.

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

namespace plantarch {

/// What a file of a format can hold; each format declares the uses it serves.
enum OutputUse : unsigned {
    kSceneOutput = 1,      ///< a scene's geometry (writeOBJ, writePLY, writeGLTF ...)
    kPlantOutput = 2,      ///< plants as plants: structure files, strings, cylinders
    kAnimationOutput = 4,  ///< a growth animation
    kPictureOutput = 8,    ///< a picture
    kScanOutput = 16,      ///< a labelled point cloud
    kDepthOutput = 32,     ///< a depth image
    kBuilderExport = 64,   ///< offered by the project builder's export
};

/// One file format plantarch writes.
struct OutputFormat {
    std::string_view extension;    ///< lower case, with its dot: ".obj", ".helios.xml"
    std::string_view description;  ///< for help texts and errors
    unsigned uses;                 ///< OutputUse bits
};

/// Every output format, in the order they are listed to users.
std::span<const OutputFormat> outputFormats();
/// The format of `path` (its name's ending, in any case; the longest match, so that
/// "a.helios.xml" is ".helios.xml") among those serving one of `uses`; null when none.
const OutputFormat* outputFormat(const std::string& path, unsigned uses);
/// The extensions of the formats serving one of `uses`, comma separated, for help texts.
std::string outputExtensions(unsigned uses);
/// Throws plantarch::Error "`what`" naming the path, its extension and the valid extensions
/// unless `path` has a format serving one of `uses`.
void requireOutputFormat(const std::string& path, unsigned uses, const std::string& what);
/// The same for a writer of one format (or a few): throws unless `path` ends with one of
/// `extensions` (as listed in the table, e.g. {".glb", ".gltf"}).
void requireOutputFormat(const std::string& path,
                         std::initializer_list<std::string_view> extensions,
                         const std::string& what);
/// A path's extension in lower case, with its dot (".obj"); empty when it has none.
std::string lowerExtension(const std::string& path);

}  // namespace plantarch
