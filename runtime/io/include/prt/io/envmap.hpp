// SPDX-License-Identifier: MIT
// Environment maps: Radiance .hdr images in one of three mappings, turned into radiance as a
// function of a world-space direction (glTF frame, +Y up). The direction convention of each
// mapping is normative and written in formats/SPEC.md §Environment maps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/error.hpp"

namespace prt::io {

enum class EnvMapping {
  Auto,           // detect from the image shape: 2:1 lat-long, 3:4 vertical cross, 1:1 angular
  LatLong,        // equirectangular
  VerticalCross,  // six square faces in a 3 wide x 4 high cross; the padding is ignored
  AngularProbe,   // Debevec's angular light-probe mapping (a disc in a square)
};

// Parses "auto" | "latlong" | "cross" | "probe"; throws Error on anything else.
EnvMapping parse_env_mapping(const std::string& name);
const char* env_mapping_name(EnvMapping mapping);
// The mapping an image of this shape has (2:1, 3:4, 1:1); Auto when the shape fits none.
EnvMapping detect_env_mapping(int width, int height);

// Replaces every NaN, infinite or negative channel value by 0 and returns how many texels (RGB
// triples) had at least one such value. Every EnvMap goes through it on construction.
std::size_t sanitize_radiance(std::vector<float>& rgb);

class EnvMap {
 public:
  // Linear RGB, row-major from the top row, width*height*3 floats. Auto detects the mapping from
  // the shape. Throws Error naming source when the size or the shape does not fit the mapping.
  // Bad texels are sanitised (sanitize_radiance); sanitized_texels() says how many there were.
  EnvMap(int width, int height, std::vector<float> rgb, EnvMapping mapping, std::string source);

  int width() const { return width_; }
  int height() const { return height_; }
  EnvMapping mapping() const { return mapping_; }
  const std::string& source() const { return source_; }
  const std::vector<float>& pixels() const { return rgb_; }
  std::size_t sanitized_texels() const { return sanitized_; }
  // Edge length of a cube face (VerticalCross only, else 0).
  int face_size() const { return mapping_ == EnvMapping::VerticalCross ? width_ / 3 : 0; }

  // Turns the whole environment: the light the image shows coming from d comes from R d
  // (L'(w) = L(R^T w)), the convention of prt_sh_rotate. radiance(), texel() and texel_of() all
  // see the turned map, so importance sampling (built from radiance()) and SH projection (from
  // texel()) follow; texel solid angles and pdfs in solid angle are unchanged by a rotation.
  // Throws Error when R is not a proper rotation (orthonormal to 1e-4, determinant +1).
  void set_rotation(const glm::mat3& rotation);
  const glm::mat3& rotation() const { return rotation_; }
  bool rotated() const { return rotated_; }

  // Radiance arriving from world direction dir (unit): bilinear within a face/region.
  glm::vec3 radiance(const glm::vec3& dir) const;

  // Where radiance(dir) reads: four texels (index y * width + x) and their weights (zero for
  // texels that do not count). Split out so a renderer can find the texels and prefetch them
  // before it traces a ray, and read them after: footprint_radiance(footprint(dir)) ==
  // radiance(dir).
  struct Footprint {
    std::uint32_t texel[4];
    float weight[4];
  };
  Footprint footprint(const glm::vec3& dir) const;
  glm::vec3 footprint_radiance(const Footprint& footprint) const;
  void prefetch(const Footprint& footprint) const;

  // Texel (x, y): its centre direction (world, after the rotation) and the solid angle it
  // covers. Returns false for texels that are not part of the mapping (cross padding, outside
  // the probe disc).
  bool texel(int x, int y, glm::vec3* dir, float* solid_angle) const;
  // The texel a world direction falls in (nearest), after the rotation.
  void texel_of(const glm::vec3& dir, int* x, int* y) const;
  // Inline: the renderer's bilinear lookups call it four times per radiance() sample.
  glm::vec3 texel_value(int x, int y) const {
    const float* p = rgb_.data() + (static_cast<std::size_t>(y) * width_ + x) * 3;
    return {p[0], p[1], p[2]};
  }

 private:
  int width_, height_;
  std::vector<float> rgb_;
  EnvMapping mapping_;
  std::string source_;
  std::size_t sanitized_ = 0;
  glm::mat3 rotation_{1.0f};  // world from image frame; identity unless set_rotation
  bool rotated_ = false;

  // The image-frame direction of a world direction (R^T d), or d itself when not rotated.
  glm::vec3 to_image_frame(const glm::vec3& dir) const;
  Footprint image_footprint(const glm::vec3& image_dir) const;
  Footprint latlong_footprint(const glm::vec3& image_dir) const;
  bool image_texel(int x, int y, glm::vec3* dir, float* solid_angle) const;
  void image_texel_of(const glm::vec3& image_dir, int* x, int* y) const;
};

// The rotation about world +Y by `degrees` (R = [[c,0,s],[0,1,0],[-s,0,c]] row-major, c = cos,
// s = sin): turns the light as `prt-bake reference --env-rotate` and prt_sh_rotate take it.
glm::mat3 rotation_about_y(double degrees);
// The same matrix as 9 row-major floats, the layout prt_sh_rotate takes.
void rotation_about_y_row_major(double degrees, float out[9]);

// atan2 in single precision without a libm call (Cephes' atanf: reduction to |t| <= tan(pi/8)
// and a degree-9 odd polynomial; error a few float ulps, like atan2f's). The per-sample direction
// lookups (lat-long texels, the sampling grid's cells) spend much of their time in atan2f.
inline float atan2_float(float y, float x) {
  constexpr float kPiF = 3.14159265358979f;
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  float t = hi > 0.0f ? lo / hi : 0.0f;  // in [0, 1]
  float base = 0.0f;
  if (t > 0.414213562f) {  // tan(pi/8): atan(t) = pi/4 + atan((t - 1) / (t + 1))
    base = 0.25f * kPiF;
    t = (t - 1.0f) / (t + 1.0f);
  }
  const float z = t * t;
  float angle = ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                  3.33329491539e-1f) *
                     z * t +
                 t) +
                base;
  if (ay > ax) angle = 0.5f * kPiF - angle;
  if (x < 0.0f) angle = kPiF - angle;
  return std::copysign(angle, y);
}

// Reads a Radiance .hdr file. NaN, Inf and negative texels are replaced by 0 and counted in one
// warning through `messages`; texels at RGBE's largest exponent (255, values of 2^119 and more)
// are kept and counted in another. Throws Error naming the file when it is not a readable .hdr
// image or its shape fits no mapping.
EnvMap load_envmap(const std::string& path, EnvMapping mapping, const MessageHook& messages = {});

// A constant environment of the given radiance (lat-long, tiny): for furnace tests.
EnvMap constant_envmap(const glm::vec3& radiance);

// The map (rotation included) resampled with radiance() onto six face_size x face_size RGB cube
// faces, in the order and orientation a cube prt_env_image has (prt/prt_env.h). For a vertical
// cross at its own face size the texel centres coincide, so this is the cross's texels.
std::vector<std::vector<float>> resample_to_cube(const EnvMap& map, int face_size);

}  // namespace prt::io
