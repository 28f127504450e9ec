// The table of file formats plantarch writes (plantarch/OutputFormats.h) and the checks of a
// path's extension against it.

#include <cctype>
#include <filesystem>

#include "plantarch/Error.h"
#include "plantarch/OutputFormats.h"

namespace plantarch {

namespace {

// Every file format plantarch writes, by extension (lower case). Help texts, the checks
// before work and the error messages listing valid extensions are all made from this table.
constexpr OutputFormat kOutputFormats[] = {
    {".obj", "Wavefront OBJ mesh with its .mtl materials", kSceneOutput | kBuilderExport},
    {".ply", "labelled PLY mesh (or point cloud)", kSceneOutput | kScanOutput | kBuilderExport},
    {".glb", "binary glTF", kSceneOutput | kAnimationOutput | kBuilderExport},
    {".gltf", "glTF", kSceneOutput | kAnimationOutput | kBuilderExport},
    {".usda", "USD text", kSceneOutput | kAnimationOutput | kBuilderExport},
    {".usdz", "USD package (the .usda and its textures in one file)", kSceneOutput},
    {".png", "picture", kSceneOutput | kPictureOutput | kDepthOutput},
    {".npz", "NumPy point cloud (with --points)", kSceneOutput | kScanOutput},
    {".npy", "NumPy array of depths in metres", kDepthOutput},
    {".xml", "plant structure file", kPlantOutput | kBuilderExport},
    {".helios.xml", "plant structure file in the Helios layout", kPlantOutput},
    {".txt", "plant strings, one line per plant", kPlantOutput},
    {".csv", "quantitative structure model (cylinders)", kPlantOutput},
    {".skeleton.csv", "skeleton node table (id, parent, x, y, z, radius ...)", kPlantOutput},
    {".mtg", "MTG multiscale tree graph (OpenAlea)", kPlantOutput},
};

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

}  // namespace

std::span<const OutputFormat> outputFormats() {
    return kOutputFormats;
}

std::string lowerExtension(const std::string& path) {
    return lower(std::filesystem::path(path).extension().string());
}

const OutputFormat* outputFormat(const std::string& path, unsigned uses) {
    const std::string name = lower(std::filesystem::path(path).filename().string());
    const OutputFormat* best = nullptr;
    for (const OutputFormat& f : kOutputFormats)
        if ((f.uses & uses) && name.size() > f.extension.size() && name.ends_with(f.extension) &&
            (!best || f.extension.size() > best->extension.size()))
            best = &f;
    return best;
}

std::string outputExtensions(unsigned uses) {
    std::string list;
    for (const OutputFormat& f : kOutputFormats)
        if (f.uses & uses) list += (list.empty() ? "" : ", ") + std::string(f.extension);
    return list;
}

void requireOutputFormat(const std::string& path, unsigned uses, const std::string& what) {
    if (outputFormat(path, uses)) return;
    const std::string ext = lowerExtension(path);
    if (ext.empty())
        throw Error(what + ": the name has no extension",
                    {.file = path, .validRange = outputExtensions(uses)});
    throw Error(what, {.file = path, .value = ext, .validRange = outputExtensions(uses)});
}

void requireOutputFormat(const std::string& path,
                         std::initializer_list<std::string_view> extensions,
                         const std::string& what) {
    // The path's format as the table reads it (the longest ending), so that "a.helios.xml"
    // is not taken for a plain ".xml".
    // A name the table does not know (".json") is matched by its ending alone.
    const OutputFormat* format = outputFormat(path, ~0u);
    const std::string name = lower(std::filesystem::path(path).filename().string());
    std::string valid;
    for (std::string_view e : extensions) {
        if (format ? format->extension == e : name.size() > e.size() && name.ends_with(e)) return;
        valid += (valid.empty() ? "" : ", ") + std::string(e);
    }
    const std::string ext = format ? std::string(format->extension) : lowerExtension(path);
    if (ext.empty())
        throw Error(what + ": the name has no extension", {.file = path, .validRange = valid});
    throw Error(what, {.file = path, .value = ext, .validRange = valid});
}

}  // namespace plantarch
