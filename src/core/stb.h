#pragma once
// The image codecs of stb (stb_image to decode, stb_image_write to encode PNG), compiled once,
// in stb.cpp, with static linkage there: their symbols stay private to that file, so a program
// that links plantarch may compile its own copy of stb. The rest of plantarch calls these.

#include <cstdint>
#include <string>
#include <vector>

namespace plantarch::core {

/// Width, height and channels (1 grey to 4 RGBA) of the encoded image of `length` bytes at
/// `data`, read from its header; false when it cannot be read (see stbFailureReason()).
bool stbImageInfo(const std::uint8_t* data, int length, int& width, int& height, int& channels);

/// The image decoded to `channels` (1 to 4) per pixel, top row first, into `pixels`; its size
/// and the channels the file holds into the others. False when it cannot be decoded.
bool stbDecodeImage(const std::uint8_t* data, int length, int channels, int& width, int& height,
                    int& fileChannels, std::vector<std::uint8_t>& pixels);

/// Why the last stbImageInfo or stbDecodeImage failed ("unknown reason" when stb says nothing).
std::string stbFailureReason();

/// PNG bytes of an image of `channels` (1 to 4) per pixel, rows `stride` bytes apart, top row
/// first, appended to `out`; false when stb cannot encode it.
bool stbEncodePng(const std::uint8_t* pixels, int width, int height, int channels, int stride,
                  std::vector<std::uint8_t>& out);

/// PNG bytes of a one-channel 16-bit image (`pixels` width x height values, top row first),
/// appended to `out`; false when it cannot be compressed.
bool stbEncodePng16(const std::uint16_t* pixels, int width, int height,
                    std::vector<std::uint8_t>& out);

/// A one-channel image decoded at 16 bits per value (8-bit files scaled by 257), top row
/// first; false when it cannot be decoded (see stbFailureReason()).
bool stbDecodeImage16(const std::uint8_t* data, int length, int& width, int& height,
                      std::vector<std::uint16_t>& values);

}  // namespace plantarch::core
