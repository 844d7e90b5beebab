// SPDX-License-Identifier: MIT
#include "rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::view {
namespace {

glm::vec3 vertex_position(const RasterMesh& mesh, std::uint32_t index) {
  const float* p = mesh.positions + 3u * index;
  return {p[0], p[1], p[2]};
}

bool finite(const glm::vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

float edge(float ax, float ay, float bx, float by, float px, float py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

}  // namespace

void triangle_bounds(const RasterMesh& mesh, glm::vec3* lo, glm::vec3* hi) {
  *lo = glm::vec3(std::numeric_limits<float>::max());
  *hi = glm::vec3(-std::numeric_limits<float>::max());
  bool any = false;
  for (std::size_t i = 0; i < 3u * static_cast<std::size_t>(mesh.triangle_count); ++i) {
    const glm::vec3 p = vertex_position(mesh, mesh.indices[i]);
    if (!finite(p)) continue;
    *lo = glm::min(*lo, p);
    *hi = glm::max(*hi, p);
    any = true;
  }
  if (!any) *lo = *hi = glm::vec3(0.0f);
}

Rasterizer::Rasterizer(const prt::io::Camera& camera, int width, int height)
    : camera_(camera), width_(width), height_(height) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  values_.assign(pixels, glm::vec3(0.0f));
  inv_depth_.assign(pixels, 0.0f);
  covered_.assign(pixels, 0);
  near_ = 1e-4f;
}

Rasterizer::ScreenVertex Rasterizer::project(const CameraVertex& v) const {
  // Inverse of Camera::direction: image point (sx, sy) in [0,1]^2 of a camera-space point.
  const float tan_half = std::tan(glm::radians(camera_.vertical_fov_degrees) * 0.5f);
  const float inv_z = 1.0f / v.position.z;
  const float sx = 0.5f + 0.5f * v.position.x * inv_z / (tan_half * camera_.aspect);
  const float sy = 0.5f - 0.5f * v.position.y * inv_z / tan_half;
  return {sx * static_cast<float>(width_), sy * static_cast<float>(height_), inv_z,
          v.value * inv_z};
}

void Rasterizer::draw(const RasterMesh& mesh, const glm::vec3* values) {
  // The near plane scales with the scene so tiny and huge scenes both work.
  glm::vec3 lo, hi;
  triangle_bounds(mesh, &lo, &hi);
  near_ = std::max(1e-6f, 1e-5f * glm::length(hi - lo));
  for (std::uint32_t t = 0; t < mesh.triangle_count; ++t) {
    CameraVertex corners[3];
    bool usable = true;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = mesh.indices[3u * t + k];
      const glm::vec3 p = vertex_position(mesh, index);
      if (!finite(p)) usable = false;
      const glm::vec3 rel = p - camera_.eye;
      corners[k].position = {glm::dot(rel, camera_.right), glm::dot(rel, camera_.up),
                             glm::dot(rel, camera_.forward)};
      corners[k].value = values[index];
    }
    if (usable) draw_clipped(corners);
  }
}

// Sutherland-Hodgman against z >= near; the polygon (at most 4 corners) is drawn as a fan.
void Rasterizer::draw_clipped(const CameraVertex (&corners)[3]) {
  CameraVertex polygon[4];
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    const CameraVertex& a = corners[k];
    const CameraVertex& b = corners[(k + 1) % 3];
    const bool a_in = a.position.z >= near_, b_in = b.position.z >= near_;
    if (a_in) polygon[count++] = a;
    if (a_in != b_in) {
      const float t = (near_ - a.position.z) / (b.position.z - a.position.z);
      polygon[count++] = {glm::mix(a.position, b.position, t), glm::mix(a.value, b.value, t)};
    }
  }
  if (count < 3) return;
  const ScreenVertex first = project(polygon[0]);
  for (int k = 1; k + 1 < count; ++k) fill(first, project(polygon[k]), project(polygon[k + 1]));
}

void Rasterizer::fill(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
  const float area = edge(a.x, a.y, b.x, b.y, c.x, c.y);
  if (!(std::abs(area) > 0.0f)) return;  // degenerate on screen (or NaN)
  const float inv_area = 1.0f / area;    // its sign makes both windings (faces) draw
  // Clamp in float before converting: a vertex near the eye projects far off screen.
  const float w = static_cast<float>(width_ - 1), h = static_cast<float>(height_ - 1);
  const int x0 = static_cast<int>(std::clamp(std::floor(std::min({a.x, b.x, c.x})), 0.0f, w));
  const int x1 = static_cast<int>(std::clamp(std::ceil(std::max({a.x, b.x, c.x})), -1.0f, w));
  const int y0 = static_cast<int>(std::clamp(std::floor(std::min({a.y, b.y, c.y})), 0.0f, h));
  const int y1 = static_cast<int>(std::clamp(std::ceil(std::max({a.y, b.y, c.y})), -1.0f, h));
  for (int y = y0; y <= y1; ++y) {
    const float py = static_cast<float>(y) + 0.5f;
    for (int x = x0; x <= x1; ++x) {
      const float px = static_cast<float>(x) + 0.5f;
      const float wa = edge(b.x, b.y, c.x, c.y, px, py) * inv_area;
      const float wb = edge(c.x, c.y, a.x, a.y, px, py) * inv_area;
      const float wc = edge(a.x, a.y, b.x, b.y, px, py) * inv_area;
      if (wa < 0.0f || wb < 0.0f || wc < 0.0f) continue;
      const float inv_depth = wa * a.inv_depth + wb * b.inv_depth + wc * c.inv_depth;
      const std::size_t pixel = static_cast<std::size_t>(y) * width_ + x;
      if (inv_depth <= inv_depth_[pixel]) continue;  // larger 1/z is nearer
      inv_depth_[pixel] = inv_depth;
      values_[pixel] =
          (wa * a.value_over_depth + wb * b.value_over_depth + wc * c.value_over_depth) / inv_depth;
      covered_[pixel] = 1;
    }
  }
}

prt::io::LinearImage render_mesh(const prt::io::Camera& camera, int width, int height,
                                 int supersample, const RasterMesh& mesh, const glm::vec3* values,
                                 const std::function<glm::vec3(const glm::vec3&)>& background) {
  const int s = std::max(1, supersample);
  Rasterizer raster(camera, width * s, height * s);
  raster.draw(mesh, values);

  prt::io::LinearImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<std::size_t>(width) * height, glm::vec3(0.0f));
  image.coverage.assign(image.pixels.size(), 0.0f);
  const float samples = static_cast<float>(s * s);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      glm::vec3 sum(0.0f);
      int hits = 0;
      for (int j = 0; j < s; ++j) {
        for (int i = 0; i < s; ++i) {
          const int sx = x * s + i, sy = y * s + j;
          const std::size_t sample = static_cast<std::size_t>(sy) * raster.width() + sx;
          if (raster.covered()[sample]) {
            sum += raster.values()[sample];
            ++hits;
          } else {
            sum += background(
                camera.direction((sx + 0.5f) / raster.width(), (sy + 0.5f) / raster.height()));
          }
        }
      }
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      image.pixels[pixel] = sum / samples;
      image.coverage[pixel] = static_cast<float>(hits) / samples;
    }
  }
  return image;
}

}  // namespace prt::view
