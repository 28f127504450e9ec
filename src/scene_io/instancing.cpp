// Instancing names and the check of Instancing::Gpu (instancing.h).

#include "scene_io/instancing.h"

#include <utility>

#include "plantarch/Error.h"

namespace plantarch {

namespace {
constexpr std::pair<Instancing, const char*> kInstancingNames[] = {
    {Instancing::None, "none"}, {Instancing::Shared, "shared"}, {Instancing::Gpu, "gpu"}};
}  // namespace

const char* instancingName(Instancing instancing) {
    for (const auto& [i, name] : kInstancingNames)
        if (i == instancing) return name;
    return "shared";
}

std::optional<Instancing> instancingFromName(std::string_view name) {
    for (const auto& [i, text] : kInstancingNames)
        if (name == text) return i;
    return std::nullopt;
}

namespace io {

void checkInstancing(const std::string& path, NodeLevel nodes, Instancing instancing,
                     bool animated) {
    if (instancing != Instancing::Gpu) return;
    if (animated)
        throw Error("gpu instances cannot be animated",
                    {.file = path,
                     .parameter = "instancing",
                     .value = "gpu",
                     .validRange = "shared or none in a growth animation"});
    if (nodes != NodeLevel::Organ)
        throw Error(
            "gpu instancing needs a node per organ",
            {.file = path, .parameter = "instancing", .value = "gpu", .validRange = "nodes organ"});
}

}  // namespace io

}  // namespace plantarch
