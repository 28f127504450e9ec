// The files a species names (leaf textures and OBJ models, stem textures, flower and fruit
// .obj models): resolved relative to the species file's folder, and checked before anything
// reads or embeds them.

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "core/image_file.h"
#include "core/input_file.h"
#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/OrganPrototypes.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

namespace fs = std::filesystem;

// What a file named in a species is: a stem texture (an image), a leaf image (its alpha
// channel outlines the leaf), an OBJ model of a leaf, or of a flower or fruit.
enum class FileKind { Texture, LeafImage, LeafModel, FloralModel };

struct NamedFile {
    FileKind kind;
    bool normalize = false;  // an OBJ model's normalize_OBJ_model
};

// Calls f(parameter path, path field, what it is) for every file a shoot type names.
template <class Params, class F>
void eachNamedFile(const std::string& label, Params& p, F&& f) {
    auto& ph = p.phytomer_parameters;
    const std::string phytomer = label + ".phytomer.";
    auto& proto = ph.leaf.prototype;
    if (!proto.OBJ_model_file.empty())
        f(phytomer + "leaf.prototype.OBJ_model_file", proto.OBJ_model_file,
          NamedFile{FileKind::LeafModel, proto.normalize_OBJ_model});
    for (auto& [leaflet, file] : proto.leaf_texture_file)
        f(phytomer + "leaf.prototype.leaf_texture_file." + std::to_string(leaflet), file,
          NamedFile{FileKind::LeafImage});
    if (!ph.internode.image_texture.empty())
        f(phytomer + "internode.image_texture", ph.internode.image_texture,
          NamedFile{FileKind::Texture});
    auto& inflorescence = ph.inflorescence;
    for (auto* fn :
         {&inflorescence.flower_prototype_function, &inflorescence.fruit_prototype_function})
        if (isOBJPrototypeName(*fn))
            f(phytomer + "inflorescence." +
                  (fn == &inflorescence.flower_prototype_function ? "flower" : "fruit") +
                  "_prototype_function",
              *fn, NamedFile{FileKind::FloralModel, inflorescence.normalize_OBJ_model});
}

// Reads a file as what it must be, throwing plantarch::Error naming `path` when it is not: a
// texture a PNG or JPEG image of sane size, a leaf image one whose alpha channel outlines a
// leaf, an OBJ model an OBJ file that makes a prototype (the same reading as when the organ
// is made). Each is first a regular file within its size limit.
void checkFile(const std::string& path, const NamedFile& named) {
    switch (named.kind) {
        case FileKind::Texture:
            io::readTextureFile(path);
            return;
        case FileKind::LeafImage:
            traceLeafImage(path);
            return;
        case FileKind::LeafModel:
        case FileKind::FloralModel:
            loadOBJPrototype(path, named.normalize);
            return;
    }
}

}  // namespace

std::string speciesFilePath(const SpeciesModel& species, const std::string& file) {
    if (file.empty() || fs::path(file).is_absolute()) return file;
    const fs::path folder = fs::path(species.sourceFile).parent_path();
    if (folder.empty()) return file;
    return (folder / file).lexically_normal().string();
}

std::map<std::string, ShootParameters> speciesShootTypes(const SpeciesModel& species) {
    std::map<std::string, ShootParameters> types = species.shootTypes;
    for (auto& [label, params] : types)
        eachNamedFile(label, params, [&](const std::string&, std::string& file, const NamedFile&) {
            file = speciesFilePath(species, file);
        });
    return types;
}

namespace {

// The error of a file named at `parameter`, placed at the species file's line naming it; a
// place inside the file (an OBJ's line) is kept in the message.
Error fileError(const SpeciesModel& species, const std::string& parameter, const std::string& path,
                const NamedFile& named, const Error& e) {
    const bool inside = e.line() > 0 || !e.parameter().empty();
    const std::string message = inside ? formatError(e.message(), {.file = e.file(),
                                                                   .line = e.line(),
                                                                   .parameter = e.parameter(),
                                                                   .value = e.value()})
                                       : e.message();
    const char* valid = named.kind == FileKind::Texture     ? "a PNG or JPEG image"
                        : named.kind == FileKind::LeafImage ? "a PNG image with alpha"
                                                            : "an OBJ file";
    return Error(message, {.file = species.sourceFile,
                           .line = species.lineOf(parameter),
                           .parameter = parameter,
                           .value = path,
                           .validRange = e.validRange().empty() ? valid : e.validRange()});
}

}  // namespace

std::vector<Error> checkSpeciesFiles(const SpeciesModel& species) {
    std::vector<Error> errors;
    std::set<std::string> checked;  // each file once, at the first parameter naming it
    for (const auto& [label, params] : species.shootTypes)
        eachNamedFile(
            label, params,
            [&](const std::string& parameter, const std::string& file, const NamedFile& named) {
                const std::string path = speciesFilePath(species, file);
                if (!checked.insert(path).second) return;
                try {
                    checkFile(path, named);
                } catch (const Error& e) {
                    errors.push_back(fileError(species, parameter, path, named, e));
                }
            });
    std::stable_sort(errors.begin(), errors.end(),
                     [](const Error& a, const Error& b) { return a.line() < b.line(); });
    return errors;
}

int SpeciesModel::lineOf(std::string path) const {
    while (!path.empty()) {
        const auto it = lines.find(path);
        if (it != lines.end()) return it->second;
        const auto dot = path.rfind('.');
        if (dot == std::string::npos) break;
        path.resize(dot);
    }
    return 0;
}

}  // namespace plantarch
