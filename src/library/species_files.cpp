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
#include "plantarch/OrganPrototypes.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

namespace fs = std::filesystem;

enum class FileKind { Texture, OBJModel };

// Calls f(parameter path, path field, kind) for every file a shoot type names.
template <class Params, class F>
void eachNamedFile(const std::string& label, Params& p, F&& f) {
    auto& ph = p.phytomer_parameters;
    const std::string phytomer = label + ".phytomer.";
    auto& proto = ph.leaf.prototype;
    if (!proto.OBJ_model_file.empty())
        f(phytomer + "leaf.prototype.OBJ_model_file", proto.OBJ_model_file, FileKind::OBJModel);
    for (auto& [leaflet, file] : proto.leaf_texture_file)
        f(phytomer + "leaf.prototype.leaf_texture_file." + std::to_string(leaflet), file,
          FileKind::Texture);
    if (!ph.internode.image_texture.empty())
        f(phytomer + "internode.image_texture", ph.internode.image_texture, FileKind::Texture);
    for (auto* fn :
         {&ph.inflorescence.flower_prototype_function, &ph.inflorescence.fruit_prototype_function})
        if (isOBJPrototypeName(*fn))
            f(phytomer + "inflorescence." +
                  (fn == &ph.inflorescence.flower_prototype_function ? "flower" : "fruit") +
                  "_prototype_function",
              *fn, FileKind::OBJModel);
}

// The line of `path` (or of the nearest enclosing path) in the species file.
int lineOf(const SpeciesModel& s, std::string path) {
    while (!path.empty()) {
        const auto it = s.lines.find(path);
        if (it != s.lines.end()) return it->second;
        const auto dot = path.rfind('.');
        if (dot == std::string::npos) break;
        path.resize(dot);
    }
    return 0;
}

// Reads what a file of `kind` must be, throwing plantarch::Error naming `path` when it is not:
// a texture decoded as a PNG or JPEG image of sane size, an OBJ model a regular text file
// within the OBJ limit (its content is read when the organ is made).
void checkFile(const std::string& path, FileKind kind) {
    if (kind == FileKind::Texture) {
        io::readTextureFile(path);
        return;
    }
    constexpr io::InputKind kModel = io::kOBJFile.named("OBJ model");
    io::InputFile file(path, kModel);
    char start[4096];
    std::size_t n = 0;
    for (std::size_t got; n < sizeof start && (got = file.read(start + n, sizeof start - n)) > 0;)
        n += got;
    io::checkText(std::string_view(start, n), path, kModel);
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
        eachNamedFile(label, params, [&](const std::string&, std::string& file, FileKind) {
            file = speciesFilePath(species, file);
        });
    return types;
}

std::vector<Error> checkSpeciesFiles(const SpeciesModel& species) {
    std::vector<Error> errors;
    std::set<std::string> checked;  // each file once, at the first parameter naming it
    for (const auto& [label, params] : species.shootTypes)
        eachNamedFile(label, params,
                      [&](const std::string& parameter, const std::string& file, FileKind kind) {
                          const std::string path = speciesFilePath(species, file);
                          if (!checked.insert(path).second) return;
                          try {
                              checkFile(path, kind);
                          } catch (const Error& e) {
                              const char* valid =
                                  kind == FileKind::Texture ? "a PNG or JPEG image" : "an OBJ file";
                              errors.emplace_back(e.message(),
                                                  ErrorContext{.file = species.sourceFile,
                                                               .line = lineOf(species, parameter),
                                                               .parameter = parameter,
                                                               .value = path,
                                                               .validRange = e.validRange().empty()
                                                                                 ? valid
                                                                                 : e.validRange()});
                          }
                      });
    std::stable_sort(errors.begin(), errors.end(),
                     [](const Error& a, const Error& b) { return a.line() < b.line(); });
    return errors;
}

}  // namespace plantarch
