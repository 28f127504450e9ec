// Captions on pictures: one line of ASCII text in stb_easy_font's built-in segment font, whose
// glyphs are axis-aligned rectangles (quads) in font units; each is filled as a block of
// scale x scale pixels per unit.

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "plantarch/Render.h"

namespace plantarch {

namespace {

// One vertex of stb_easy_font's output: position (font units, y down) and a colour.
struct FontVertex {
    float x, y, z;
    unsigned char color[4];
};
static_assert(sizeof(FontVertex) == 16, "stb_easy_font writes 16-byte vertices");

// The text as the font takes it: one line, printable ASCII only.
std::string printable(std::string_view text) {
    std::string s(text);
    for (char& c : s)
        if (c < 32 || c > 126) c = '?';
    return s;
}

// The font's quads for `text`, four vertices each.
std::vector<FontVertex> quadsOf(std::string& text) {
    // About 270 bytes a character by the font's own estimate; twice that for safety.
    std::vector<FontVertex> buffer(text.size() * 40 + 4);
    const int quads = stb_easy_font_print(
        0.0f, 0.0f, text.data(), nullptr, buffer.data(),
        int(std::min<std::size_t>(buffer.size() * sizeof(FontVertex), std::size_t(1) << 30)));
    buffer.resize(std::size_t(quads) * 4);
    return buffer;
}

}  // namespace

void drawText(Image& image, int x, int y, std::string_view text, int scale,
              std::array<std::uint8_t, 3> color) {
    if (scale < 1 || text.empty()) return;
    std::string line = printable(text);
    const std::vector<FontVertex> v = quadsOf(line);
    for (std::size_t q = 0; q + 3 < v.size(); q += 4) {
        float x0 = v[q].x, x1 = v[q].x, y0 = v[q].y, y1 = v[q].y;
        for (std::size_t k = 1; k < 4; ++k) {
            x0 = std::min(x0, v[q + k].x);
            x1 = std::max(x1, v[q + k].x);
            y0 = std::min(y0, v[q + k].y);
            y1 = std::max(y1, v[q + k].y);
        }
        const int px0 = std::max(0, x + int(x0 * float(scale)));
        const int px1 = std::min(image.width, x + int(x1 * float(scale)));
        const int py0 = std::max(0, y + int(y0 * float(scale)));
        const int py1 = std::min(image.height, y + int(y1 * float(scale)));
        for (int py = py0; py < py1; ++py)
            for (int px = px0; px < px1; ++px)
                std::memcpy(
                    &image.rgb[(std::size_t(py) * std::size_t(image.width) + std::size_t(px)) * 3],
                    color.data(), 3);
    }
}

std::array<int, 2> textSize(std::string_view text, int scale) {
    if (text.empty()) return {0, 0};
    std::string line = printable(text);
    return {stb_easy_font_width(line.data()) * scale, stb_easy_font_height(line.data()) * scale};
}

}  // namespace plantarch
