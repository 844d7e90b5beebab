// SPDX-License-Identifier: MIT
// A small CPU rasteriser for headless viewing: triangles of per-vertex values (Gouraud,
// perspective-correct), z-buffered, both faces drawn, seen through the reference renderer's
// pinhole camera (prt/io/camera.hpp), so a pixel sees what the reference's primary ray
// through the same image point sees.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/camera.hpp"
#include "prt/io/image_io.hpp"

namespace prt::view {

struct RasterMesh {
  const float* positions = nullptr;  // x,y,z per vertex (world)
  std::uint32_t vertex_count = 0;
  const std::uint32_t* indices = nullptr;  // three per triangle, each < vertex_count
  std::uint32_t triangle_count = 0;
};

// The bounds the reference renderer frames: every vertex some triangle uses (non-finite
// positions skipped). lo = hi = 0 for an empty mesh.
void triangle_bounds(const RasterMesh& mesh, glm::vec3* lo, glm::vec3* hi);

class Rasterizer {
 public:
  Rasterizer(const prt::io::Camera& camera, int width, int height);

  // Draws every triangle with `values` (one per vertex) interpolated over it; the nearest
  // surface wins. Triangles are clipped against a near plane in front of the eye.
  void draw(const RasterMesh& mesh, const glm::vec3* values);

  int width() const { return width_; }
  int height() const { return height_; }
  // Row-major from the top; covered[i] != 0 where a triangle was drawn.
  const std::vector<glm::vec3>& values() const { return values_; }
  const std::vector<std::uint8_t>& covered() const { return covered_; }

 private:
  struct ScreenVertex {
    float x, y;       // pixel coordinates (pixel centres at +0.5)
    float inv_depth;  // 1 / camera-space depth
    glm::vec3 value_over_depth;
  };
  struct CameraVertex {
    glm::vec3 position;  // camera space: x right, y up, z along the view direction
    glm::vec3 value;
  };

  prt::io::Camera camera_;
  int width_, height_;
  float near_;
  std::vector<glm::vec3> values_;
  std::vector<float> inv_depth_;
  std::vector<std::uint8_t> covered_;

  ScreenVertex project(const CameraVertex& v) const;
  void draw_clipped(const CameraVertex (&corners)[3]);
  void fill(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c);
};

// An image of the mesh with `values` per vertex, `supersample`² samples per pixel (box
// filtered); a sample that misses the mesh takes background(direction of its camera ray).
// LinearImage::coverage is the fraction of each pixel's samples that hit the mesh, as the
// reference renderer's images report it (auto_exposure_ev meters on it).
prt::io::LinearImage render_mesh(const prt::io::Camera& camera, int width, int height,
                                 int supersample, const RasterMesh& mesh, const glm::vec3* values,
                                 const std::function<glm::vec3(const glm::vec3&)>& background);

}  // namespace prt::view
