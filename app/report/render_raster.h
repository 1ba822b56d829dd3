// A small z-buffered triangle rasterizer for the report's orthographic views:
// surfaces are drawn into a G-buffer (depth, surface id, an interpolated scalar
// per pixel such as a signed distance, and a Lambert shade), which a colour
// function then turns into an RGB image, supersampled and box-filtered down.
// Plain C++ (no OpenCV), so tests can inspect pixels.
//
// Frames: points are in L (mm); an OrthoView looks along `view_L` with `up_L`
// up the image and `right_L` = up x (-view) to the right.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app::render {

using Rgb = std::array<std::uint8_t, 3>;

/// Row-major 8-bit RGB image.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 * width * height

  Image() = default;
  Image(int w, int h, Rgb fill);
  Rgb At(int x, int y) const {
    const auto i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  void Set(int x, int y, Rgb c) {
    const auto i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(x));
    rgb[i] = c[0];
    rgb[i + 1] = c[1];
    rgb[i + 2] = c[2];
  }
};

/// Orthographic camera: image pixel (x right, y down) of a point in L.
struct OrthoView {
  Eigen::Vector3d right_L = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up_L = Eigen::Vector3d::UnitY();
  Eigen::Vector3d view_L = -Eigen::Vector3d::UnitZ();  ///< into the screen
  Eigen::Vector2d centre_mm =
      Eigen::Vector2d::Zero();  ///< (right, up) coordinates at the image centre
  double px_per_mm = 10.0;
  int width = 800;
  int height = 600;
  Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();  ///< where the view sits in a larger image

  /// Pixel coordinates (continuous; pixel (i, j) covers [i, i+1) x [j, j+1)).
  Eigen::Vector2d ToPixel(const Eigen::Vector3d& p_L) const {
    return offset_px + Eigen::Vector2d(0.5 * width + (p_L.dot(right_L) - centre_mm.x()) * px_per_mm,
                                       0.5 * height - (p_L.dot(up_L) - centre_mm.y()) * px_per_mm);
  }
  double Depth(const Eigen::Vector3d& p_L) const { return p_L.dot(view_L); }
  /// The same view with `factor` times the pixels.
  OrthoView Scaled(double factor) const;
};

/// A view looking along `view_L` with `up_L` (made perpendicular) up, framing
/// `points_L` in width x height pixels with `margin_px` around them.
OrthoView FitView(const Eigen::Vector3d& view_L, const Eigen::Vector3d& up_L,
                  const std::vector<Eigen::Vector3d>& points_L, int width, int height,
                  int margin_px);

/// One mesh to draw: its pose in L, a scalar per vertex (or none) and an id (>= 0).
struct Surface {
  const io::TriangleMesh* mesh = nullptr;
  Eigen::Isometry3d X_LM = Eigen::Isometry3d::Identity();
  const std::vector<float>* vertex_values = nullptr;  ///< size = vertices, or null (value 0)
  int id = 0;
};

/// Per-pixel result of rasterization; id -1 = background.
struct GBuffer {
  int width = 0;
  int height = 0;
  std::vector<float> depth, value, shade;
  std::vector<std::int16_t> id;
};

/// Draws the surfaces (nearest wins; shade = ambient + Lambert from a light near
/// the viewer, back faces darker).
GBuffer Rasterize(const OrthoView& view, const std::vector<Surface>& surfaces);

/// Colours a G-buffer: colour(id, value) -> Rgb times the pixel's shade, `background` where
/// nothing was drawn; then averages `factor` x `factor` blocks (the supersampling factor the
/// view was scaled by). A template, so that the colour of each of the millions of sub-pixels is
/// an inlined call.
template <typename Colour>
Image Resolve(const GBuffer& g, const Colour& colour, Rgb background, int factor) {
  const int w = g.width / factor;
  const int h = g.height / factor;
  Image out(w, h, background);
  const float norm = 1.0f / static_cast<float>(factor * factor);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float acc[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const std::size_t row =
            static_cast<std::size_t>(y * factor + dy) * static_cast<std::size_t>(g.width);
        for (int dx = 0; dx < factor; ++dx) {
          const std::size_t i = row + static_cast<std::size_t>(x * factor + dx);
          if (g.id[i] < 0) {
            for (std::size_t k = 0; k < 3; ++k) acc[k] += background[k];
            continue;
          }
          const Rgb c = colour(static_cast<int>(g.id[i]), g.value[i]);
          for (std::size_t k = 0; k < 3; ++k) acc[k] += std::min(255.0f, c[k] * g.shade[i]);
        }
      }
      out.Set(x, y,
              {static_cast<std::uint8_t>(acc[0] * norm + 0.5f),
               static_cast<std::uint8_t>(acc[1] * norm + 0.5f),
               static_cast<std::uint8_t>(acc[2] * norm + 0.5f)});
    }
  }
  return out;
}

/// Area-weighted unit vertex normals of a mesh (in its own frame).
std::vector<Eigen::Vector3f> VertexNormals(const io::TriangleMesh& mesh);

}  // namespace occlude::app::render
