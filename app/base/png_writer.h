// PNG encoding of 8-bit images, on zlib alone: the report's maps and the charts are written
// without OpenCV's image codecs, whose dependencies (GDAL, GDCM, Poppler, ...) cost every run
// of `occlude` about 0.1 s and 50 MB before it starts (docs/results/speed/README.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace occlude::app {

/// Pixel layout of the rows given to EncodePng.
enum class PngPixels {
  kGrey,  ///< 1 byte a pixel
  kRgb,   ///< 3 bytes a pixel, red first
  kBgr,   ///< 3 bytes a pixel, blue first (OpenCV's order); written as RGB
  kRgba,  ///< 4 bytes a pixel
};

/// The PNG file (8 bits a channel, no interlace) of `height` rows of `width` pixels, row y at
/// rows + y * row_stride_bytes. Each row is filtered with the PNG filter that leaves the
/// smallest sum of absolute bytes (libpng's heuristic), then deflated (zlib, level 1, run-length
/// matches). Throws std::invalid_argument for a width or height < 1, rows == nullptr or a stride
/// shorter than a row; std::runtime_error when zlib fails.
std::string EncodePng(const std::uint8_t* rows, int width, int height, PngPixels pixels,
                      std::size_t row_stride_bytes);

}  // namespace occlude::app
