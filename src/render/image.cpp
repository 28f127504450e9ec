// Images: PNG writing (atomic), image and texture reading, label colours, sRGB tables.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "core/atomic_file.h"
#include "core/image_file.h"
#include "core/stb.h"
#include "plantarch/Error.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Render.h"
#include "render/render_internal.h"

namespace plantarch {

namespace {

std::vector<std::uint8_t> pngBytes(const Image& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
        throw Error("image has no pixels or a wrong buffer size", {.file = path});
    std::vector<std::uint8_t> bytes;
    bytes.reserve(image.rgb.size() / 2 + 1024);
    if (!core::stbEncodePng(image.rgb.data(), image.width, image.height, 3, image.width * 3, bytes))
        throw Error("PNG encoding failed", {.file = path});
    return bytes;
}

}  // namespace

void writePNG(const Image& image, const std::string& path) {
    requireOutputFormat(path, {".png"}, "writePNG writes a PNG picture");
    const std::vector<std::uint8_t> bytes = pngBytes(image, path);
    io::writeWholeFile(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

std::string encodePNG(const Image& image) {
    const std::vector<std::uint8_t> bytes = pngBytes(image, "");
    return std::string(bytes.begin(), bytes.end());
}

void writeNPY(const std::vector<float>& values, const std::vector<std::size_t>& shape,
              const std::string& path) {
    requireOutputFormat(path, {".npy"}, "writeNPY writes a NumPy array");
    std::size_t count = 1;
    std::string dims;  // "(h, w)", or "(n,)" for one dimension, as Python writes tuples
    for (std::size_t d : shape) {
        count *= d;
        dims += (dims.empty() ? "" : ", ") + std::to_string(d);
    }
    if (shape.size() == 1) dims += ",";
    if (shape.empty() || count == 0 || count != values.size())
        throw Error("array shape and value count differ", {.file = path});
    // NPY 1.0: magic, version, header length, then a Python dict padded with spaces to a
    // multiple of 64 bytes (counting the 10 bytes before it) and ended by a newline.
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + dims + "), }";
    header.append(63 - (10 + header.size()) % 64, ' ');
    header += '\n';
    const std::size_t dataBytes = values.size() * sizeof(float);
    std::vector<std::uint8_t> bytes(10 + header.size() + dataBytes);
    const std::uint8_t magic[10] = {0x93,
                                    'N',
                                    'U',
                                    'M',
                                    'P',
                                    'Y',
                                    1,
                                    0,
                                    std::uint8_t(header.size() & 0xFF),
                                    std::uint8_t(header.size() >> 8)};
    std::memcpy(bytes.data(), magic, sizeof magic);
    std::memcpy(bytes.data() + 10, header.data(), header.size());
    std::memcpy(bytes.data() + 10 + header.size(), values.data(), dataBytes);
    io::writeWholeFile(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

void writeDepthNPY(const DepthImage& depth, const std::string& path) {
    requireOutputFormat(path, {".npy"}, "writeDepthNPY writes a NumPy array");
    if (depth.width <= 0 || depth.height <= 0 ||
        depth.depth.size() != std::size_t(depth.width) * std::size_t(depth.height))
        throw Error("depth image has no pixels or a wrong buffer size", {.file = path});
    writeNPY(depth.depth, {std::size_t(depth.height), std::size_t(depth.width)}, path);
}

namespace {

std::vector<std::uint8_t> png16Bytes(const Image16& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0 ||
        image.values.size() != std::size_t(image.width) * std::size_t(image.height))
        throw Error("image has no pixels or a wrong buffer size", {.file = path});
    std::vector<std::uint8_t> bytes;
    if (!core::stbEncodePng16(image.values.data(), image.width, image.height, bytes))
        throw Error("PNG encoding failed", {.file = path});
    return bytes;
}

}  // namespace

void writePNG16(const Image16& image, const std::string& path) {
    requireOutputFormat(path, {".png"}, "writePNG16 writes a PNG picture");
    const std::vector<std::uint8_t> bytes = png16Bytes(image, path);
    io::writeWholeFile(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

std::string encodePNG16(const Image16& image) {
    const std::vector<std::uint8_t> bytes = png16Bytes(image, "");
    return std::string(bytes.begin(), bytes.end());
}

Image16 readImage16(const std::string& path) {
    const io::DecodedImage decoded = io::readImageFile(path, 1);
    Image16 image;
    const auto* data = reinterpret_cast<const std::uint8_t*>(decoded.bytes.data());
    if (!core::stbDecodeImage16(data, int(decoded.bytes.size()), image.width, image.height,
                                image.values))
        throw Error("cannot decode the image: " + core::stbFailureReason(), {.file = path});
    return image;
}

Image depthPicture(const DepthImage& depth) {
    float lo = std::numeric_limits<float>::max(), hi = 0.0f;
    for (float d : depth.depth)
        if (d > 0.0f) {
            lo = std::min(lo, d);
            hi = std::max(hi, d);
        }
    Image image(depth.width, depth.height);
    const float span = hi > lo ? hi - lo : 1.0f;
    for (std::size_t i = 0; i < depth.depth.size(); ++i) {
        const float d = depth.depth[i];
        if (!(d > 0.0f)) continue;
        const auto grey = std::uint8_t(std::lround(255.0f - 195.0f * (d - lo) / span));
        image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = grey;
    }
    return image;
}

Image readImage(const std::string& path) {
    io::DecodedImage decoded = io::readImageFile(path, 3);
    Image image(decoded.width, decoded.height);
    image.rgb = std::move(decoded.pixels);
    return image;
}

// ---- label colours -----------------------------------------------------------------------

// An invertible scramble of 24-bit integers (xorshift steps and odd multipliers modulo 2^24
// are bijections that keep 0 at 0), so neighbouring IDs get visibly different colours.
namespace {
constexpr std::uint32_t kMask24 = 0xFFFFFFu;
constexpr std::uint32_t kMul1 = 0x9E3B5Du;  // odd
constexpr std::uint32_t kMul2 = 0x5BD1E5u;  // odd

std::uint32_t inverseOdd(std::uint32_t a) {
    // Newton iteration for the inverse modulo 2^24 (each step doubles the correct bits).
    std::uint32_t x = a;
    for (int i = 0; i < 5; ++i) x = (x * (2u - a * x)) & kMask24;
    return x;
}

std::uint32_t undoXorShift(std::uint32_t y, int shift) {
    std::uint32_t x = y;
    for (int i = 0; i < 24 / shift + 1; ++i) x = y ^ (x >> shift);
    return x & kMask24;
}

std::uint32_t scramble24(std::uint32_t x) {
    x &= kMask24;
    x ^= x >> 12;
    x = (x * kMul1) & kMask24;
    x ^= x >> 11;
    x = (x * kMul2) & kMask24;
    x ^= x >> 12;
    return x;
}

std::uint32_t unscramble24(std::uint32_t x) {
    x = undoXorShift(x, 12);
    x = (x * inverseOdd(kMul2)) & kMask24;
    x = undoXorShift(x, 11);
    x = (x * inverseOdd(kMul1)) & kMask24;
    x = undoXorShift(x, 12);
    return x;
}
}  // namespace

std::array<std::uint8_t, 3> objectLabelColor(ObjectID id) {
    if (id >= kMask24)
        throw Error("object ID too large for a 24-bit label colour",
                    {.value = std::to_string(id), .validRange = "0 to 16777214"});
    const std::uint32_t c = scramble24(id + 1);
    return {std::uint8_t(c >> 16), std::uint8_t(c >> 8), std::uint8_t(c)};
}

std::optional<ObjectID> objectIDFromLabelColor(std::array<std::uint8_t, 3> rgb) {
    const std::uint32_t c = (std::uint32_t(rgb[0]) << 16) | (std::uint32_t(rgb[1]) << 8) | rgb[2];
    if (c == 0) return std::nullopt;
    return unscramble24(c) - 1;
}

namespace render_detail {

// ---- sRGB ------------------------------------------------------------------------------

namespace {
struct SrgbTables {
    std::array<float, 256> toLinear{};
    // Encoding by table on a fine linear grid (4096 steps) keeps it fast and exact enough
    // that each byte is the rounded sRGB value of the grid point.
    std::array<std::uint8_t, 4097> toByte{};
    SrgbTables() {
        for (int i = 0; i < 256; ++i) toLinear[i] = srgbToLinear(float(i) / 255.0f);
        for (int i = 0; i <= 4096; ++i) {
            const float l = float(i) / 4096.0f;
            const float s =
                l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
            toByte[i] = std::uint8_t(std::lround(std::clamp(s, 0.0f, 1.0f) * 255.0f));
        }
    }
};
const SrgbTables& srgbTables() {
    static const SrgbTables tables;
    return tables;
}
}  // namespace

std::uint8_t linearToSrgbByte(float linear) {
    if (!(linear > 0.0f)) return 0;  // also catches NaN
    if (linear >= 1.0f) return 255;
    return srgbTables().toByte[std::size_t(linear * 4096.0f + 0.5f)];
}

float srgbByteToLinear(std::uint8_t value) {
    return srgbTables().toLinear[value];
}

// ---- textures --------------------------------------------------------------------------

Texture loadTexture(const std::string& path) {
    io::DecodedImage decoded = io::readTextureFile(path);
    return textureOfPixels(decoded.width, decoded.height, std::move(decoded.pixels));
}

Texture textureOfPixels(int width, int height, std::vector<std::uint8_t> rgba) {
    Texture t;
    t.width = width;
    t.height = height;
    t.rgba = std::move(rgba);
    glm::dvec3 sum(0.0);
    std::size_t opaque = 0;
    for (std::size_t i = 0; i < t.rgba.size(); i += 4) {
        if (t.rgba[i + 3] < 128) {
            t.hasMask = true;
            continue;
        }
        sum += glm::dvec3(srgbByteToLinear(t.rgba[i]), srgbByteToLinear(t.rgba[i + 1]),
                          srgbByteToLinear(t.rgba[i + 2]));
        ++opaque;
    }
    if (opaque > 0) t.meanColor = vec3(sum / double(opaque));
    return t;
}

namespace {
inline int wrap(int i, int n) {
    const int r = i % n;
    return r < 0 ? r + n : r;
}
}  // namespace

vec3 Texture::color(vec2 uv) const {
    // Texel centres at half-integers; row 0 of the image is the top (v = 1).
    const float x = uv.x * float(width) - 0.5f;
    const float y = (1.0f - uv.y) * float(height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = wrap(int(fx), width), x1 = wrap(int(fx) + 1, width);
    const int y0 = wrap(int(fy), height), y1 = wrap(int(fy) + 1, height);
    auto texel = [&](int tx, int ty) {
        const std::uint8_t* p = &rgba[(std::size_t(ty) * std::size_t(width) + std::size_t(tx)) * 4];
        return vec3(srgbByteToLinear(p[0]), srgbByteToLinear(p[1]), srgbByteToLinear(p[2]));
    };
    return (1.0f - ay) * ((1.0f - ax) * texel(x0, y0) + ax * texel(x1, y0)) +
           ay * ((1.0f - ax) * texel(x0, y1) + ax * texel(x1, y1));
}

float Texture::alpha(vec2 uv) const {
    const int x = wrap(int(std::floor(uv.x * float(width))), width);
    const int y = wrap(int(std::floor((1.0f - uv.y) * float(height))), height);
    return float(rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4 + 3]) / 255.0f;
}

}  // namespace render_detail
}  // namespace plantarch
