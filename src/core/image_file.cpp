#include "core/image_file.h"

#include <climits>
#include <cstring>

#include "core/stb.h"
#include "plantarch/Error.h"

namespace plantarch::io {

namespace {

bool startsWith(std::string_view bytes, std::string_view magic) {
    return bytes.substr(0, magic.size()) == magic;
}

}  // namespace

std::string_view imageFormatName(std::string_view b) {
    using namespace std::string_view_literals;
    if (startsWith(b, "\x89PNG\r\n\x1a\n"sv)) return "PNG";
    if (startsWith(b, "\xFF\xD8\xFF"sv)) return "JPEG";
    if (startsWith(b, "GIF87a"sv) || startsWith(b, "GIF89a"sv)) return "GIF";
    if (startsWith(b, "BM"sv)) return "BMP";
    if (startsWith(b, "8BPS"sv)) return "PSD";
    if (startsWith(b, "#?RADIANCE"sv) || startsWith(b, "#?RGBE"sv)) return "HDR";
    if (startsWith(b, "\x53\x80\xF6\x34"sv)) return "PIC";
    if (b.size() >= 2 && b[0] == 'P' && (b[1] == '5' || b[1] == '6')) return "PNM";
    if (startsWith(b, "RIFF"sv) && b.substr(8, 4) == "WEBP") return "WebP";
    if (startsWith(b, "II*\0"sv) || startsWith(b, "MM\0*"sv)) return "TIFF";
    return "";
}

DecodedImage readImageFile(const std::string& path, int channels, const InputKind& kind,
                           bool pngOrJpeg) {
    DecodedImage image;
    image.bytes = readWholeFile(path, kind);
    const std::string_view bytes = image.bytes;
    const std::string_view format = imageFormatName(bytes);
    const std::string valid = pngOrJpeg ? "a PNG or JPEG image" : "an image (PNG, JPEG, ...)";
    if (format.empty())
        throw Error("not an image: no PNG, JPEG or other image header",
                    {.file = path, .validRange = valid});
    if (pngOrJpeg && format != "PNG" && format != "JPEG")
        throw Error("a " + std::string(format) + " image, not a PNG or JPEG",
                    {.file = path, .validRange = valid});
    image.format = format == "PNG"    ? ImageFormat::PNG
                   : format == "JPEG" ? ImageFormat::JPEG
                                      : ImageFormat::Other;
    if (bytes.size() > std::size_t(INT_MAX))
        throw Error("image file too large to decode", {.file = path});
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    const int length = int(bytes.size());
    int w = 0, h = 0, n = 0;
    if (!core::stbImageInfo(data, length, w, h, n))
        throw Error("cannot decode " + std::string(format) + " image: " + core::stbFailureReason(),
                    {.file = path, .validRange = valid});
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
        throw Error("image too large",
                    {.file = path,
                     .value = std::to_string(w) + " x " + std::to_string(h) + " pixels",
                     .validRange = "at most " + std::to_string(kMaxImageSide) + " pixels a side"});
    if (!core::stbDecodeImage(data, length, channels, w, h, n, image.pixels))
        throw Error("cannot decode " + std::string(format) + " image: " + core::stbFailureReason(),
                    {.file = path, .validRange = valid});
    image.width = w;
    image.height = h;
    image.fileChannels = n;
    return image;
}

}  // namespace plantarch::io
