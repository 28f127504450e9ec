#pragma once
// Image files read and decoded the one way every reader of plantarch does it: opened as an
// input file (core/input_file.h: a regular file within the image limit), its size in pixels
// checked before it is decoded, then decoded (stb_image) from the bytes read, so what is
// decoded is what a caller goes on to use or embed.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"

namespace plantarch::io {

/// The largest width or height of an image read (16384 pixels).
inline constexpr int kMaxImageSide = 16384;

/// A texture named by a species, a plant file or a material: PNG or JPEG only (what glTF
/// embeds).
inline constexpr InputKind kTextureFile = kImageFile.named("texture image");

enum class ImageFormat { PNG, JPEG, Other };

struct DecodedImage {
    int width = 0, height = 0;
    int fileChannels = 0;  ///< channels the file holds (1 grey to 4 RGBA)
    ImageFormat format = ImageFormat::Other;
    std::vector<std::uint8_t> pixels;  ///< width x height x the channels asked for, top row first
    std::string bytes;                 ///< the file as read
};

/// "PNG", "JPEG", "GIF", "BMP"... from the first bytes; "" when none is recognised.
std::string_view imageFormatName(std::string_view bytes);

/// Reads the image at `path` as `kind` and decodes it to `channels` (1 to 4) per pixel.
/// `pngOrJpeg`: any other format is refused. Throws plantarch::Error naming the path: not an
/// image, not a PNG or JPEG, corrupt, more than kMaxImageSide pixels a side, or what
/// InputFile throws.
DecodedImage readImageFile(const std::string& path, int channels,
                           const InputKind& kind = kImageFile, bool pngOrJpeg = false);

/// A texture (kTextureFile, PNG or JPEG) read and decoded to RGBA.
inline DecodedImage readTextureFile(const std::string& path) {
    return readImageFile(path, 4, kTextureFile, true);
}

}  // namespace plantarch::io
