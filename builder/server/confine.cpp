// The files the builder reads for a species or a scene: only regular files under its output
// folder and the species library's. A species may name any path (a texture, an OBJ model),
// and an export embeds a texture's bytes as they are: without this, anyone who reaches the
// port could save a species whose texture is /etc/passwd and download it inside scene.glb.

#include <set>

#include "builder/server/server_impl.h"
#include "plantarch/Error.h"
#include "plantarch/OrganPrototypes.h"

namespace plantarch::builder {

namespace {

// One file a species names: its parameter (as a species edit names it) and value.
struct NamedFile {
    std::string parameter;
    std::string value;
};

std::vector<NamedFile> namedFiles(const SpeciesModel& species) {
    std::vector<NamedFile> files;
    for (const auto& [label, shoot] : species.shootTypes) {
        const std::string at = "shoot_types." + label + ".phytomer.";
        const PhytomerParameters& ph = shoot.phytomer_parameters;
        const LeafPrototype& leaf = ph.leaf.prototype;
        files.push_back({at + "leaf.prototype.OBJ_model_file", leaf.OBJ_model_file});
        for (const auto& [leaflet, image] : leaf.leaf_texture_file)
            files.push_back(
                {at + "leaf.prototype.leaf_texture_file (leaflet " + std::to_string(leaflet) + ")",
                 image});
        files.push_back({at + "internode.image_texture", ph.internode.image_texture});
        // A prototype function that is not a registered name is an OBJ file (or refused).
        for (const auto& [field, name] :
             {std::pair{"flower_prototype_function", ph.inflorescence.flower_prototype_function},
              std::pair{"fruit_prototype_function", ph.inflorescence.fruit_prototype_function}})
            if (isOBJPrototypeName(name) || name.find('/') != std::string::npos)
                files.push_back({at + "inflorescence." + field, name});
    }
    return files;
}

}  // namespace

std::string Server::Impl::readableText() const {
    std::string text;
    for (const fs::path& folder : readable) text += (text.empty() ? "" : " or ") + folder.string();
    return text;
}

void Server::Impl::confineSpecies(const SpeciesModel& species, const fs::path& speciesFile) const {
    std::error_code ec;
    const fs::path working = fs::current_path(ec);
    for (const NamedFile& f : namedFiles(species)) {
        if (f.value.empty()) continue;
        const std::string named = f.parameter + " = \"" + clip(f.value) + "\"";
        const std::string valid = " (valid: a file under " + readableText() + ")";
        if (f.value.find('\0') != std::string::npos)
            throw HttpError{400, named + ": not a file name" + valid};
        // Where the reader may look: the path itself when absolute, else from the species
        // file's folder or from the working folder. Each place that exists must be allowed.
        std::set<fs::path> places;
        const fs::path value(f.value);
        if (value.is_absolute()) {
            places.insert(value);
        } else {
            if (!speciesFile.empty())
                places.insert(fs::absolute(speciesFile).parent_path() / value);
            if (!working.empty()) places.insert(working / value);
        }
        bool found = false;
        for (const fs::path& place : places) {
            const fs::file_status status = fs::status(place, ec);
            if (!fs::exists(status)) continue;
            if (std::none_of(readable.begin(), readable.end(),
                             [&](const fs::path& folder) { return isUnder(place, folder); }))
                throw HttpError{403, named + ": a file outside the builder's folders" +
                                         (value.is_absolute() ? "" : " (" + place.string() + ")") +
                                         valid};
            if (!fs::is_regular_file(status))
                throw HttpError{400, named + ": " +
                                         (fs::is_directory(status)
                                              ? "a directory"
                                              : "not a regular file (a pipe, socket or device)") +
                                         valid};
            found = true;
        }
        if (!found) throw HttpError{400, named + ": no such file" + valid};
    }
}

void Server::Impl::confineScene(const Context& scene) const {
    for (MaterialID id = 0; id < scene.materialCount(); ++id) {
        const std::string& texture = scene.material(id).texture;
        if (texture.empty()) continue;
        std::error_code ec;
        const bool allowed =
            fs::is_regular_file(texture, ec) &&
            std::any_of(readable.begin(), readable.end(),
                        [&](const fs::path& folder) { return isUnder(texture, folder); });
        if (!allowed)
            throw Error(
                "a texture the builder does not read: not a regular file under its "
                "folders",
                {.parameter = "texture",
                 .value = clip(texture),
                 .validRange = "a file under " + readableText()});
    }
}

}  // namespace plantarch::builder
