#pragma once
// Input files as plantarch reads them. Every reader (species, plant structure and <helios>
// files, plant strings, projects, OBJ files and the .mtl files they name, attraction points,
// images and textures) opens a file without blocking and checks the opened file before
// reading a byte: anything but a regular file (a directory, a FIFO, a device, a socket) is
// refused, and so is a file over the size limit of its kind (docs/formats.md lists them).
// Text files that are UTF-16, UTF-32 or binary are named as such.

#include <cstdint>
#include <string>

namespace plantarch {

/// What an input file is read as; each kind has its size limit.
enum class InputFileKind {
    Species,           ///< species file, 16 MiB
    PlantStructure,    ///< plant structure or <helios> file, 256 MiB
    PlantStrings,      ///< file of plant strings, 256 MiB
    Project,           ///< project file, 16 MiB
    OBJ,               ///< OBJ file, 4 GiB
    Material,          ///< .mtl file named by an OBJ's mtllib, 64 MiB
    AttractionPoints,  ///< attraction point file, 256 MiB
    Image,             ///< image or texture, 256 MiB (and at most 16384 pixels a side)
    Weather,           ///< weather file, 64 MiB
};

/// The size limit of `kind`, bytes.
std::uint64_t inputFileLimit(InputFileKind kind);

/// Opens `path` as a file of `kind` would be read and closes it again: throws
/// plantarch::Error naming the path when it cannot be opened, is not a regular file, or is
/// over the kind's limit. `what` names the file in messages ("obstacle file"; empty: the
/// kind's own name). Never blocks, whatever the path names.
void checkInputFile(const std::string& path, InputFileKind kind, const std::string& what = "");

/// The whole content of `path`, read as a file of `kind` (checked as checkInputFile does; a
/// text kind also to be UTF-8 text, not UTF-16 or binary).
std::string readInputFile(const std::string& path, InputFileKind kind,
                          const std::string& what = "");

}  // namespace plantarch
