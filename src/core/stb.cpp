// stb's image codecs, the one place they are compiled (stb.h).

#include "core/stb.h"

// GCC sees stb's decoder state as maybe uninitialized where the decoder is inlined into the
// functions below (stb_image fills it before use); the whole file, popped at its end (it may
// share a unity batch with other files).
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO  // files are read by InputFile only
#include <stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO  // PNG bytes go to memory; files are written atomically
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace plantarch::core {

namespace {

void appendPngBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

bool stbImageInfo(const std::uint8_t* data, int length, int& width, int& height, int& channels) {
    return stbi_info_from_memory(data, length, &width, &height, &channels) != 0;
}

bool stbDecodeImage(const std::uint8_t* data, int length, int channels, int& width, int& height,
                    int& fileChannels, std::vector<std::uint8_t>& pixels) {
    stbi_uc* decoded =
        stbi_load_from_memory(data, length, &width, &height, &fileChannels, channels);
    if (!decoded) return false;
    pixels.assign(decoded,
                  decoded + std::size_t(width) * std::size_t(height) * std::size_t(channels));
    stbi_image_free(decoded);
    return true;
}

std::string stbFailureReason() {
    const char* why = stbi_failure_reason();
    return why ? why : "unknown reason";
}

bool stbEncodePng(const std::uint8_t* pixels, int width, int height, int channels, int stride,
                  std::vector<std::uint8_t>& out) {
    return stbi_write_png_to_func(appendPngBytes, &out, width, height, channels, pixels, stride) !=
           0;
}

}  // namespace plantarch::core

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
