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

std::vector<MaskRegion> maskRegions(const std::vector<std::uint32_t>& labels, int width,
                                    int height) {
    if (width <= 0 || height <= 0 || labels.size() != std::size_t(width) * std::size_t(height))
        throw Error("the mask has no pixels or a wrong buffer size", {.parameter = "labels"});
    struct Scan {
        MaskRegion region;
        int maxX = -1, maxY = -1;
        std::size_t end = 0;  // index after the region's last pixel so far
    };
    std::map<std::uint32_t, Scan> scans;
    // Column-major, as COCO's run-length encoding counts.
    for (int x = 0; x < width; ++x)
        for (int y = 0; y < height; ++y) {
            const std::uint32_t label =
                labels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            if (label == 0) continue;
            auto [it, fresh] = scans.try_emplace(label);
            Scan& in = it->second;
            if (fresh) in.region.bbox = {x, y, 0, 0};
            const std::size_t k = std::size_t(x) * std::size_t(height) + std::size_t(y);
            if (!in.region.rle.empty() && in.end == k) {
                ++in.region.rle.back();
            } else {
                in.region.rle.push_back(std::uint32_t(k - in.end));
                in.region.rle.push_back(1);
            }
            in.end = k + 1;
            ++in.region.area;
            in.maxX = std::max(in.maxX, x);  // x only grows: bbox[0] is the first column
            in.region.bbox[1] = std::min(in.region.bbox[1], y);
            in.maxY = std::max(in.maxY, y);
        }
    std::vector<MaskRegion> out;
    out.reserve(scans.size());
    for (auto& [label, in] : scans) {
        in.region.label = label;
        in.region.rle.push_back(std::uint32_t(std::size_t(width) * std::size_t(height) - in.end));
        in.region.bbox[2] = in.maxX - in.region.bbox[0] + 1;
        in.region.bbox[3] = in.maxY - in.region.bbox[1] + 1;
        out.push_back(std::move(in.region));
    }
    return out;
}

std::string cocoAnnotations(const Context& context, const Image& objectMask,
                            const std::string& imageFile) {
    const int w = objectMask.width, h = objectMask.height;
    if (w <= 0 || h <= 0 || objectMask.rgb.size() != std::size_t(w) * std::size_t(h) * 3)
        throw Error("the object mask has no pixels or a wrong buffer size",
                    {.parameter = "objectMask"});
    // Object ID + 1 per pixel (0: background), as maskRegions reads labels.
    std::vector<std::uint32_t> labels(std::size_t(w) * std::size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (const auto id = objectIDFromLabelColor(objectMask.pixel(x, y)))
                labels[std::size_t(y) * std::size_t(w) + std::size_t(x)] = *id + 1;
    using json = nlohmann::json;
    json categories = json::array();
    for (std::size_t i = 1; i < kOrganLabels.size(); ++i)
        categories.push_back(
            {{"id", i}, {"name", std::string(kOrganLabels[i])}, {"supercategory", "plant"}});
    json annotations = json::array();
    const bool hasPlant = context.objectDataType("plantID") == DataType::Int;
    const bool hasOrgan = context.objectDataType("organ") == DataType::String;
    for (const MaskRegion& in : maskRegions(labels, w, h)) {
        const ObjectID id = in.label - 1;
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
        annotations.push_back({{"id", annotations.size() + 1},
                               {"image_id", 1},
                               {"category_id", category},
                               {"object_id", id},
                               {"plant_id", plant},
                               {"iscrowd", 0},
                               {"area", in.area},
                               {"bbox", in.bbox},
                               {"segmentation", {{"counts", in.rle}, {"size", {h, w}}}}});
    }
    json doc = {{"info", {{"description", "plantarch instance annotations"}}},
                {"images", {{{"id", 1}, {"file_name", imageFile}, {"width", w}, {"height", h}}}},
                {"categories", categories},
                {"annotations", annotations}};
    return doc.dump();
}

}  // namespace plantarch
