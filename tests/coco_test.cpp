// COCO-style annotations of an object mask: every object in view once, its RLE mask exactly
// its pixels in the mask, its area, box, category and plant as the scene says.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;
using json = nlohmann::json;

TEST(Coco, AnnotationsDecodeToTheObjectMaskPixels) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30);
    RenderOptions o;
    o.width = 160;
    o.height = 120;
    o.mode = RenderMode::LabelObject;
    const Image mask = render(ctx, o);
    const json doc = json::parse(cocoAnnotations(ctx, mask, "bean.png"));
    EXPECT_EQ(doc["images"][0]["file_name"], "bean.png");
    EXPECT_EQ(doc["images"][0]["width"], 160);
    ASSERT_EQ(doc["categories"].size(), kOrganLabels.size() - 1);
    EXPECT_EQ(doc["categories"][2]["name"], "leaf");  // id 3
    std::vector<int> seen(std::size_t(160 * 120), -1);
    std::size_t objects = 0;
    for (int x = 0; x < 160; ++x)
        for (int y = 0; y < 120; ++y)
            if (auto id = objectIDFromLabelColor(mask.pixel(x, y)))
                seen[std::size_t(x * 120 + y)] = int(*id);
    ASSERT_GT(doc["annotations"].size(), 10u);
    for (const json& a : doc["annotations"]) {
        const int id = a["object_id"];
        ASSERT_TRUE(ctx.doesObjectExist(ObjectID(id)));
        EXPECT_EQ(std::string(kOrganLabels[a["category_id"].get<std::size_t>()]),
                  ctx.objectDataString(ObjectID(id), "organ").value());
        EXPECT_EQ(a["plant_id"], 0);
        // Decode the column-major RLE and compare it with the mask, pixel by pixel.
        std::size_t k = 0, area = 0;
        bool on = false;
        int minX = 1 << 30, maxX = -1, minY = 1 << 30, maxY = -1;
        for (std::size_t run : a["segmentation"]["counts"]) {
            for (std::size_t r = 0; r < run; ++r, ++k) {
                ASSERT_LT(k, seen.size());
                EXPECT_EQ(seen[k] == id, on);
                if (on) {
                    ++area;
                    const int x = int(k / 120), y = int(k % 120);
                    minX = std::min(minX, x), maxX = std::max(maxX, x);
                    minY = std::min(minY, y), maxY = std::max(maxY, y);
                }
            }
            on = !on;
        }
        EXPECT_EQ(k, seen.size());
        EXPECT_EQ(a["area"], area);
        EXPECT_EQ(a["bbox"], json({minX, minY, maxX - minX + 1, maxY - minY + 1}));
        ++objects;
    }
    std::size_t visible = 0;
    std::vector<bool> counted(ctx.objectIDLimit(), false);
    for (int v : seen)
        if (v >= 0 && !counted[std::size_t(v)]) counted[std::size_t(v)] = true, ++visible;
    EXPECT_EQ(objects, visible);
}

TEST(Coco, EmptyMaskIsAnError) {
    Context ctx;
    EXPECT_THROW(cocoAnnotations(ctx, Image(), "x.png"), Error);
}
