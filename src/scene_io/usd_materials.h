#pragma once
// Textured materials of USD files (UsdOptions::appearance): a UsdPreviewSurface network per
// scene material under /plantarch/Looks (UsdUVTexture shaders reading primvars:st through a
// UsdPrimvarReader_float2), GeomSubsets binding each mesh's faces to their materials, the PNG
// maps as files beside the .usda, and the .usdz package (a zip archive, stored, each file's
// data 64-byte aligned, the root layer first).

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"

namespace plantarch::io {

class MaterialLooks;

class UsdLooks {
public:
    /// With MaterialStyle::Textured, draws the maps of the materials the exported objects of
    /// `contexts` use; their files are named `<prefix><texture>_<map>.png`. Flat: inactive.
    UsdLooks(std::span<const Context* const> contexts, const UsdOptions& options,
             const std::string& prefix);
    ~UsdLooks();

    bool active() const { return looks_ != nullptr; }
    /// `def Scope "Looks"` with a Material per scene material, for inside /plantarch (each
    /// line indented by 4 spaces); "" when inactive.
    std::string scope() const;
    /// GeomSubsets (family materialBind) binding the faces of `objects`, in that order, to
    /// their materials, each line indented by 12 spaces; "" when inactive.
    std::string subsets(const Context& context, std::span<const ObjectID> objects) const;
    /// The texture files: name and PNG bytes.
    std::vector<std::pair<std::string, std::string_view>> files() const;

private:
    std::unique_ptr<MaterialLooks> looks_;
    std::string prefix_;
    std::vector<Material> materials_;  // in Looks order
};

/// Writes a USDZ package of `files` (name, bytes; the root layer first) to `out`: a zip
/// archive without compression whose every file's data starts at a multiple of 64 bytes.
/// Throws plantarch::Error naming `out` when the package would pass 4 GB.
void writeUsdz(AtomicFile& out, std::span<const std::pair<std::string, std::string_view>> files);

}  // namespace plantarch::io
