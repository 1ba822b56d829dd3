// EncodePng (base/png_writer.h): files that another decoder (OpenCV's codecs) reads back pixel
// for pixel in every layout, every row filter exercised, the bytes the format fixes, and bad
// arguments refused.
#include "base/png_writer.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace occlude::app {
namespace {

cv::Mat Decode(const std::string& png) {
  const cv::Mat bytes(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data()));
  return cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
}

std::uint32_t U32At(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8U) | static_cast<std::uint8_t>(s[at + k]);
  return v;
}

// Noise, gradients along and across the rows and flat runs, for the row filters to choose among.
std::vector<std::uint8_t> TestImage(int width, int height, int channels, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width * height * channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        int v = 0;
        switch ((y / 4) % 4) {
          case 0:
            v = static_cast<int>(rng() % 256U);
            break;
          case 1:
            v = 3 * x + c;
            break;
          case 2:
            v = 5 * y + 7 * c;
            break;
          default:
            v = 40 * c + (x / 9) * 11 + (y / 7) * 13;
            break;
        }
        px[static_cast<std::size_t>((y * width + x) * channels + c)] = static_cast<std::uint8_t>(v);
      }
    }
  }
  return px;
}

TEST(EncodePngTest, OpenCvDecodesEveryLayoutPixelForPixel) {
  struct Case {
    PngPixels pixels;
    int channels;
  };
  for (const Case c : {Case{PngPixels::kGrey, 1}, Case{PngPixels::kRgb, 3},
                       Case{PngPixels::kBgr, 3}, Case{PngPixels::kRgba, 4}}) {
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{97, 61}}) {
      const std::vector<std::uint8_t> px = TestImage(w, h, c.channels, 7U);
      const cv::Mat m =
          Decode(EncodePng(px.data(), w, h, c.pixels, static_cast<std::size_t>(w * c.channels)));
      ASSERT_FALSE(m.empty()) << c.channels << " " << w;
      ASSERT_EQ(m.cols, w);
      ASSERT_EQ(m.rows, h);
      ASSERT_EQ(m.channels(), c.channels);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          for (int k = 0; k < c.channels; ++k) {
            // OpenCV decodes to BGR(A): its channel k is the file's channel 2 - k for colour.
            const int file_channel = c.channels >= 3 && k < 3 ? 2 - k : k;
            // The file holds RGB; kBgr input was blue first, so the file's red is input's 2.
            const int input_channel = c.pixels == PngPixels::kBgr ? 2 - file_channel : file_channel;
            ASSERT_EQ(m.ptr<std::uint8_t>(y)[x * c.channels + k],
                      px[static_cast<std::size_t>((y * w + x) * c.channels + input_channel)])
                << c.channels << " " << w << "x" << h << " at " << x << "," << y << " ch " << k;
          }
        }
      }
    }
  }
}

TEST(EncodePngTest, ReadsRowsThroughTheStride) {
  const int w = 5, h = 4, stride = 19;  // 15 bytes of pixels, 4 of padding a row
  std::vector<std::uint8_t> rows(static_cast<std::size_t>(stride * h), 0xee);
  for (int y = 0; y < h; ++y)
    for (int i = 0; i < 3 * w; ++i)
      rows[static_cast<std::size_t>(y * stride + i)] = static_cast<std::uint8_t>(10 * y + i);
  const cv::Mat m = Decode(EncodePng(rows.data(), w, h, PngPixels::kRgb, stride));
  ASSERT_EQ(m.rows, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const cv::Vec3b bgr = m.at<cv::Vec3b>(y, x);
      EXPECT_EQ(bgr[2], 10 * y + 3 * x);      // red
      EXPECT_EQ(bgr[0], 10 * y + 3 * x + 2);  // blue
    }
  }
}

TEST(EncodePngTest, SignatureHeaderAndChunkChecksums) {
  const std::vector<std::uint8_t> px = TestImage(300, 2, 3, 1U);
  const std::string png = EncodePng(px.data(), 300, 2, PngPixels::kRgb, 900);
  ASSERT_GT(png.size(), 8U + 25U + 12U + 12U);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(U32At(png, 8), 13U);  // IHDR length
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(U32At(png, 16), 300U);          // width
  EXPECT_EQ(U32At(png, 20), 2U);            // height
  EXPECT_EQ(static_cast<int>(png[24]), 8);  // bit depth
  EXPECT_EQ(static_cast<int>(png[25]), 2);  // truecolour
  // Every chunk's CRC-32 covers its type and data; IEND closes the file.
  std::size_t at = 8;
  std::vector<std::string> types;
  while (at < png.size()) {
    const std::uint32_t length = U32At(png, at);
    const auto* type_and_data = reinterpret_cast<const Bytef*>(png.data() + at + 4);
    EXPECT_EQ(U32At(png, at + 8 + length),
              static_cast<std::uint32_t>(crc32(0L, type_and_data, length + 4U)));
    types.push_back(png.substr(at + 4, 4));
    at += 12U + length;
  }
  EXPECT_EQ(at, png.size());
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
}

TEST(EncodePngTest, FlatImagesCompressToAFewHundredBytes) {
  const std::vector<std::uint8_t> white(3U * 1000U * 800U, 255);
  EXPECT_LT(EncodePng(white.data(), 1000, 800, PngPixels::kRgb, 3000).size(), 5000U);
}

TEST(EncodePngTest, RefusesEmptyImagesAndShortStrides) {
  const std::vector<std::uint8_t> px(12, 0);
  EXPECT_THROW(EncodePng(px.data(), 0, 1, PngPixels::kRgb, 3), std::invalid_argument);
  EXPECT_THROW(EncodePng(px.data(), 1, 0, PngPixels::kRgb, 3), std::invalid_argument);
  EXPECT_THROW(EncodePng(nullptr, 1, 1, PngPixels::kRgb, 3), std::invalid_argument);
  EXPECT_THROW(EncodePng(px.data(), 2, 1, PngPixels::kRgb, 5), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::app
