// COCO-style instance annotations of an object label mask: one annotation per object seen,
// with its organ as the category, its pixel area, bounding box and mask as uncompressed RLE
// (column-major runs starting with background, as COCO's tools read them).

#include <algorithm>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/Render.h"

namespace plantarch {

namespace {

struct Instance {
    int minX = std::numeric_limits<int>::max(), minY = std::numeric_limits<int>::max();
    int maxX = -1, maxY = -1;
    std::size_t area = 0;
    std::vector<std::uint32_t> counts;  // alternating background / object runs
    std::size_t end = 0;                // index after the object's last pixel so far
};

}  // namespace

std::string cocoAnnotations(const Context& context, const Image& objectMask,
                            const std::string& imageFile) {
    const int w = objectMask.width, h = objectMask.height;
    if (w <= 0 || h <= 0 || objectMask.rgb.size() != std::size_t(w) * std::size_t(h) * 3)
        throw Error("the object mask has no pixels or a wrong buffer size",
                    {.parameter = "objectMask"});
    std::map<ObjectID, Instance> instances;
    // Column-major, as COCO's run-length encoding counts.
    for (int x = 0; x < w; ++x)
        for (int y = 0; y < h; ++y) {
            const auto id = objectIDFromLabelColor(objectMask.pixel(x, y));
            if (!id) continue;
            Instance& in = instances[*id];
            const std::size_t k = std::size_t(x) * std::size_t(h) + std::size_t(y);
            if (!in.counts.empty() && in.end == k) {
                ++in.counts.back();
            } else {
                in.counts.push_back(std::uint32_t(k - in.end));
                in.counts.push_back(1);
            }
            in.end = k + 1;
            ++in.area;
            in.minX = std::min(in.minX, x);
            in.maxX = std::max(in.maxX, x);
            in.minY = std::min(in.minY, y);
            in.maxY = std::max(in.maxY, y);
        }
    using json = nlohmann::json;
    json categories = json::array();
    for (std::size_t i = 1; i < kOrganLabels.size(); ++i)
        categories.push_back(
            {{"id", i}, {"name", std::string(kOrganLabels[i])}, {"supercategory", "plant"}});
    json annotations = json::array();
    const bool hasPlant = context.objectDataType("plantID") == DataType::Int;
    const bool hasOrgan = context.objectDataType("organ") == DataType::String;
    for (auto& [id, in] : instances) {
        in.counts.push_back(std::uint32_t(std::size_t(w) * std::size_t(h) - in.end));
        std::size_t category = 0;
        std::int32_t plant = -1;
        if (context.doesObjectExist(id)) {
            const std::string organ =
                hasOrgan ? context.objectDataString(id, "organ").value_or("") : "";
            for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
                if (organ == kOrganLabels[i]) category = i;
            if (organ == "trellis") category = 9;
            plant = hasPlant ? context.objectDataInt(id, "plantID").value_or(-1) : -1;
        }
        annotations.push_back(
            {{"id", annotations.size() + 1},
             {"image_id", 1},
             {"category_id", category},
             {"object_id", id},
             {"plant_id", plant},
             {"iscrowd", 0},
             {"area", in.area},
             {"bbox", {in.minX, in.minY, in.maxX - in.minX + 1, in.maxY - in.minY + 1}},
             {"segmentation", {{"counts", in.counts}, {"size", {h, w}}}}});
    }
    json doc = {{"info", {{"description", "plantarch instance annotations"}}},
                {"images", {{{"id", 1}, {"file_name", imageFile}, {"width", w}, {"height", h}}}},
                {"categories", categories},
                {"annotations", annotations}};
    return doc.dump();
}

}  // namespace plantarch
