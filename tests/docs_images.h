#pragma once
// Helpers of the tests that make the docs' pictures: whether to write them full size
// (PLANTARCH_WRITE_DOCS_IMAGES set), where, and panels placed side by side.

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "plantarch/Render.h"

namespace plantarch::testing {

inline bool writingDocsImages() {
    return std::getenv("PLANTARCH_WRITE_DOCS_IMAGES") != nullptr;
}

inline std::string docsImagePath(const std::string& name) {
    return std::string(PLANTARCH_SOURCE_DIR) + "/docs/images/" + name;
}

/// Images of one height placed side by side, left to right.
inline Image strip(const std::vector<Image>& panels) {
    int width = 0;
    for (const Image& p : panels) width += p.width;
    Image out(width, panels.front().height);
    int x = 0;
    for (const Image& p : panels) {
        for (int y = 0; y < out.height; ++y)
            std::memcpy(&out.rgb[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * 3],
                        &p.rgb[std::size_t(y) * std::size_t(p.width) * 3],
                        std::size_t(p.width) * 3);
        x += p.width;
    }
    return out;
}

}  // namespace plantarch::testing
