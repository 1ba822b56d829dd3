// PNG encoding (png_writer.h): signature, IHDR, one IDAT of the filtered rows deflated by
// zlib, IEND; each chunk's CRC-32 by zlib's crc32.
#include "base/png_writer.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace occlude::app {
namespace {

constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

void PutU32(std::uint32_t v, std::string* out) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out->push_back(static_cast<char>((v >> static_cast<unsigned>(shift)) & 0xffU));
}

void PutChunk(const char (&type)[5], const std::uint8_t* data, std::size_t size, std::string* out) {
  PutU32(static_cast<std::uint32_t>(size), out);
  const std::size_t type_at = out->size();
  out->append(type, 4);
  if (size > 0) out->append(reinterpret_cast<const char*>(data), size);
  const auto* crc_from = reinterpret_cast<const Bytef*>(out->data() + type_at);
  PutU32(static_cast<std::uint32_t>(crc32(0L, crc_from, static_cast<uInt>(size + 4))), out);
}

// Bytes a pixel and PNG colour type (greyscale 0, truecolour 2, truecolour with alpha 6) of
// the written pixels.
struct Layout {
  int channels;
  std::uint8_t colour_type;
};

Layout LayoutOf(PngPixels pixels) {
  switch (pixels) {
    case PngPixels::kGrey:
      return {1, 0};
    case PngPixels::kRgb:
    case PngPixels::kBgr:
      return {3, 2};
    case PngPixels::kRgba:
      return {4, 6};
  }
  return {3, 2};
}

std::uint8_t Paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(a);
  return static_cast<std::uint8_t>(pb <= pc ? b : c);
}

// Writes filter type `type` of `row` (above: the previous row, zeros for the first) into
// out[1..], out[0] = type; returns the sum of the filtered bytes read as signed. One loop a
// filter, so that none tests the type byte by byte.
std::size_t Filter(int type, const std::vector<std::uint8_t>& row,
                   const std::vector<std::uint8_t>& above, int bpp, std::uint8_t* out) {
  out[0] = static_cast<std::uint8_t>(type);
  const std::uint8_t* x = row.data();
  const std::uint8_t* b = above.data();
  const std::size_t n = row.size();
  const auto step = static_cast<std::size_t>(bpp);
  std::uint8_t* f = out + 1;
  // The first pixel has no left neighbour (a = c = 0): Sub is None there, Average halves b and
  // Paeth predicts b.
  const std::size_t first = std::min(step, n);
  switch (type) {
    case 0:
      std::copy(x, x + n, f);
      break;
    case 1:
      std::copy(x, x + first, f);
      for (std::size_t i = first; i < n; ++i) f[i] = static_cast<std::uint8_t>(x[i] - x[i - step]);
      break;
    case 2:
      for (std::size_t i = 0; i < n; ++i) f[i] = static_cast<std::uint8_t>(x[i] - b[i]);
      break;
    case 3:
      for (std::size_t i = 0; i < first; ++i) f[i] = static_cast<std::uint8_t>(x[i] - b[i] / 2);
      for (std::size_t i = first; i < n; ++i)
        f[i] = static_cast<std::uint8_t>(x[i] - (x[i - step] + b[i]) / 2);
      break;
    default:
      for (std::size_t i = 0; i < first; ++i) f[i] = static_cast<std::uint8_t>(x[i] - b[i]);
      for (std::size_t i = first; i < n; ++i)
        f[i] = static_cast<std::uint8_t>(x[i] - Paeth(x[i - step], b[i], b[i - step]));
      break;
  }
  std::size_t cost = 0;
  for (std::size_t i = 0; i < n; ++i) cost += f[i] < 128U ? f[i] : 256U - f[i];
  return cost;
}

// Row y of the image in the file's channel order.
void ReadRow(const std::uint8_t* rows, int y, std::size_t stride, PngPixels pixels,
             std::vector<std::uint8_t>* row) {
  const std::uint8_t* src = rows + static_cast<std::size_t>(y) * stride;
  std::copy(src, src + row->size(), row->begin());
  if (pixels != PngPixels::kBgr) return;
  for (std::size_t i = 0; i + 2 < row->size(); i += 3) std::swap((*row)[i], (*row)[i + 2]);
}

// The zlib stream of the filtered rows: level 1 with run-length matches, which on the report's
// maps is 2-3 times as fast as level 6 and within 10 % of its size.
std::vector<std::uint8_t> Deflate(const std::vector<std::uint8_t>& raw) {
  z_stream z{};
  if (deflateInit2(&z, 1, Z_DEFLATED, 15, 8, Z_RLE) != Z_OK)
    throw std::runtime_error("PNG encoding: zlib's deflateInit2 failed");
  std::vector<std::uint8_t> out(deflateBound(&z, static_cast<uLong>(raw.size())));
  z.next_in = const_cast<Bytef*>(raw.data());
  z.avail_in = static_cast<uInt>(raw.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("PNG encoding: zlib's deflate failed");
  return out;
}

}  // namespace

std::string EncodePng(const std::uint8_t* rows, int width, int height, PngPixels pixels,
                      std::size_t row_stride_bytes) {
  const Layout layout = LayoutOf(pixels);
  const int bpp = layout.channels;
  if (rows == nullptr || width < 1 || height < 1 ||
      static_cast<std::size_t>(width) > std::numeric_limits<std::uint32_t>::max() / 4U ||
      row_stride_bytes < static_cast<std::size_t>(width) * static_cast<std::size_t>(bpp)) {
    throw std::invalid_argument("EncodePng: an image needs pixels, a width and height >= 1 and " +
                                std::string("a row stride of at least width * channels bytes"));
  }
  const std::size_t row_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(bpp);
  std::vector<std::uint8_t> raw((row_bytes + 1) * static_cast<std::size_t>(height));
  std::vector<std::uint8_t> row(row_bytes), above(row_bytes, 0), trial(row_bytes + 1);
  for (int y = 0; y < height; ++y) {
    ReadRow(rows, y, row_stride_bytes, pixels, &row);
    std::uint8_t* out = raw.data() + static_cast<std::size_t>(y) * (row_bytes + 1);
    std::size_t best = Filter(0, row, above, bpp, out);
    for (int type = 1; type <= 4 && best > 0; ++type) {
      const std::size_t cost = Filter(type, row, above, bpp, trial.data());
      if (cost < best) {
        best = cost;
        std::copy(trial.begin(), trial.end(), out);
      }
    }
    row.swap(above);
  }
  std::string header;
  PutU32(static_cast<std::uint32_t>(width), &header);
  PutU32(static_cast<std::uint32_t>(height), &header);
  header += static_cast<char>(8);  // bits a channel
  header += static_cast<char>(layout.colour_type);
  header.append(3, '\0');  // deflate, adaptive filtering, no interlace
  const std::vector<std::uint8_t> idat = Deflate(raw);
  std::string png(kSignature.begin(), kSignature.end());
  PutChunk("IHDR", reinterpret_cast<const std::uint8_t*>(header.data()), header.size(), &png);
  PutChunk("IDAT", idat.data(), idat.size(), &png);
  PutChunk("IEND", nullptr, 0, &png);
  return png;
}

}  // namespace occlude::app
