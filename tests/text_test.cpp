// Captions drawn on pictures (drawText, textSize).

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "plantarch/Render.h"

using namespace plantarch;

namespace {

// Pixels of `im` in colour `c`, and the box they span.
struct Ink {
    int count = 0;
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};
Ink inkOf(const Image& im, std::array<std::uint8_t, 3> c) {
    Ink ink;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            if (im.pixel(x, y) == c) {
                ++ink.count;
                ink.x0 = std::min(ink.x0, x);
                ink.y0 = std::min(ink.y0, y);
                ink.x1 = std::max(ink.x1, x);
                ink.y1 = std::max(ink.y1, y);
            }
    return ink;
}

constexpr std::array<std::uint8_t, 3> kRed{200, 10, 10};

}  // namespace

TEST(Text, InkStaysInsideTheMeasuredBoxAndGrowsWithScale) {
    for (int scale : {1, 2, 3}) {
        Image im(400, 100);
        drawText(im, 10, 20, "10 cm", scale, kRed);
        const Ink ink = inkOf(im, kRed);
        const auto [w, h] = textSize("10 cm", scale);
        ASSERT_GT(ink.count, 0) << scale;
        EXPECT_GE(ink.x0, 10);
        EXPECT_GE(ink.y0, 20);
        EXPECT_LT(ink.x1, 10 + w) << scale;
        EXPECT_LT(ink.y1, 20 + h) << scale;
        // The glyphs are scaled blocks: ink grows with the square of the scale.
        Image one(400, 100);
        drawText(one, 10, 20, "10 cm", 1, kRed);
        EXPECT_EQ(ink.count, inkOf(one, kRed).count * scale * scale) << scale;
    }
    EXPECT_GT(textSize("side view", 2)[0], textSize("side", 2)[0]);
    EXPECT_EQ(textSize("", 2)[0], 0);
}

TEST(Text, ClipsAtTheImageEdgesAndDrawsUnknownCharactersAsQuestionMarks) {
    Image im(30, 12);
    drawText(im, -5, -3, "a long caption that runs off the picture", 2, kRed);
    drawText(im, 25, 8, "xyz", 3, kRed);  // mostly outside: no write past the pixels
    EXPECT_GT(inkOf(im, kRed).count, 0);
    Image a(80, 20), b(80, 20);
    drawText(a, 0, 0, "\x01\xff", 1, kRed);
    drawText(b, 0, 0, "??", 1, kRed);
    EXPECT_EQ(a.rgb, b.rgb);
    Image none(10, 10);
    drawText(none, 0, 0, "x", 0, kRed);  // scale 0 draws nothing
    EXPECT_EQ(inkOf(none, kRed).count, 0);
}
