// stb's image codecs, the one place they are compiled (stb.h).

#include "core/stb.h"

// GCC sees stb's decoder state as maybe uninitialized where the decoder is inlined into the
// functions below (stb_image fills it before use); the whole file, popped at its end (it may
// share a unity batch with other files).
#if defined(__GNUC__)
#pragma GCC diagnostic push
#if !defined(__clang__)  // a GCC warning clang does not know
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
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

void appendBigEndian32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

// One PNG chunk: length, type, data, CRC of type and data.
void appendChunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data,
                 std::size_t length) {
    appendBigEndian32(out, std::uint32_t(length));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    if (length > 0) out.insert(out.end(), data, data + length);
    appendBigEndian32(out, stbiw__crc32(out.data() + start, int(length + 4)));
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

bool stbEncodePng16(const std::uint16_t* pixels, int width, int height,
                    std::vector<std::uint8_t>& out) {
    // Rows of filter type 0 (none) and big-endian samples, deflated by stb's compressor.
    const std::size_t rowBytes = 1 + 2 * std::size_t(width);
    if (width <= 0 || height <= 0 || rowBytes * std::size_t(height) > 0x7FFFFFFFu) return false;
    std::vector<std::uint8_t> raw(rowBytes * std::size_t(height));
    for (int y = 0; y < height; ++y) {
        std::uint8_t* row = raw.data() + rowBytes * std::size_t(y);
        row[0] = 0;
        const std::uint16_t* in = pixels + std::size_t(y) * std::size_t(width);
        for (int x = 0; x < width; ++x) {
            row[1 + 2 * x] = std::uint8_t(in[x] >> 8);
            row[2 + 2 * x] = std::uint8_t(in[x] & 0xFF);
        }
    }
    int zlength = 0;
    unsigned char* z = stbi_zlib_compress(raw.data(), int(raw.size()), &zlength, 8);
    if (!z) return false;
    static const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    out.insert(out.end(), signature, signature + 8);
    std::vector<std::uint8_t> header;
    appendBigEndian32(header, std::uint32_t(width));
    appendBigEndian32(header, std::uint32_t(height));
    header.insert(header.end(), {16, 0, 0, 0, 0});  // 16 bits, grey, deflate, filters, no interlace
    appendChunk(out, "IHDR", header.data(), header.size());
    appendChunk(out, "IDAT", z, std::size_t(zlength));
    appendChunk(out, "IEND", nullptr, 0);
    STBIW_FREE(z);
    return true;
}

bool stbDecodeImage16(const std::uint8_t* data, int length, int& width, int& height,
                      std::vector<std::uint16_t>& values) {
    int channels = 0;
    stbi_us* decoded = stbi_load_16_from_memory(data, length, &width, &height, &channels, 1);
    if (!decoded) return false;
    values.assign(decoded, decoded + std::size_t(width) * std::size_t(height));
    stbi_image_free(decoded);
    return true;
}

}  // namespace plantarch::core

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
