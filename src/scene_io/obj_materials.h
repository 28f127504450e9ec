#pragma once
// Textured materials of an OBJ's material library (ObjOptions::appearance): the maps drawn for
// the scene (material_textures.h) as PNG files beside the .mtl, and each material's lines.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"

namespace plantarch::io {

class MaterialLooks;

class ObjTextures {
public:
    /// With MaterialStyle::Textured, draws the maps of the exported objects' materials and
    /// writes their PNG files (base colour, alpha where a leaf needs it, normal, roughness)
    /// into `dir` as `<prefix><texture>_<map>.png`, each an AtomicFile appended to `files`,
    /// finished but not committed. Flat: nothing.
    ObjTextures(const Context& context, const ObjOptions& options, const std::filesystem::path& dir,
                const std::string& prefix, std::vector<AtomicFile>& files);
    ~ObjTextures();

    /// The .mtl lines that follow a material's Kd..illum lines: "" when flat; else its PBR
    /// factors (Pr, Pm) and, when textured, Kd 1 1 1 (the map carries the colour), map_Kd,
    /// map_d, norm, map_Bump and map_Pr.
    std::string lines(const Material& material) const;

private:
    std::unique_ptr<MaterialLooks> looks_;
    std::string prefix_;
};

}  // namespace plantarch::io
