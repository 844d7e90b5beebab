// SPDX-License-Identifier: MIT
// Environment maps: the three mappings of formats/SPEC.md §Environment maps. World frame: glTF,
// +Y up, the "front" of every mapping (lat-long and probe image centre, cross centre face) at -Z,
// image right = +X, image up = +Y.
#include "prt/io/envmap.hpp"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hdr_stream.hpp"
#include "prt/io/error.hpp"
#include "prt/io/file.hpp"

namespace prt::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Vertical cross (HDRShop): face [col,row] in the 3x4 grid, and the world direction of face
// coordinates (u right, v up, both in [-1,1]) as the image shows them.
enum CubeFace { kPosX, kNegX, kPosY, kNegY, kPosZ, kNegZ, kNoFace };

CubeFace cross_face_at(int col, int row) {
  if (col == 1) {
    switch (row) {
      case 0:
        return kPosY;
      case 1:
        return kNegZ;
      case 2:
        return kNegY;
      case 3:
        return kPosZ;
      default:
        return kNoFace;
    }
  }
  if (row == 1) return col == 0 ? kNegX : (col == 2 ? kPosX : kNoFace);
  return kNoFace;
}

void cross_face_cell(CubeFace face, int* col, int* row) {
  static const int kCells[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 3}, {1, 1}};
  *col = kCells[face][0];
  *row = kCells[face][1];
}

glm::dvec3 cross_face_direction(CubeFace face, double u, double v) {
  switch (face) {
    case kPosX:
      return {1.0, v, u};
    case kNegX:
      return {-1.0, v, -u};
    case kPosY:
      return {u, 1.0, v};
    case kNegY:
      return {u, -1.0, -v};
    case kPosZ:
      return {u, -v, 1.0};  // the back face is stored upside down
    case kNegZ:
      return {u, v, -1.0};
    default:
      return {0.0, 0.0, 0.0};
  }
}

// Inverse of cross_face_direction: the face dir falls on and its (u, v).
CubeFace cross_face_of(const glm::dvec3& d, double* u, double* v) {
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  if (ax >= ay && ax >= az) {
    if (d.x > 0) {
      *u = d.z / ax;
      *v = d.y / ax;
      return kPosX;
    }
    *u = -d.z / ax;
    *v = d.y / ax;
    return kNegX;
  }
  if (ay >= az) {
    if (d.y > 0) {
      *u = d.x / ay;
      *v = d.z / ay;
      return kPosY;
    }
    *u = d.x / ay;
    *v = -d.z / ay;
    return kNegY;
  }
  if (d.z > 0) {
    *u = d.x / az;
    *v = -d.y / az;
    return kPosZ;
  }
  *u = d.x / az;
  *v = d.y / az;
  return kNegZ;
}

// Solid angle of the cube-face rectangle [0,x]x[0,y] at distance 1 (signed, exact).
double cube_corner_solid_angle(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

double cube_texel_solid_angle(double u0, double v0, double u1, double v1) {
  return std::abs(cube_corner_solid_angle(u1, v1) - cube_corner_solid_angle(u0, v1) -
                  cube_corner_solid_angle(u1, v0) + cube_corner_solid_angle(u0, v0));
}

glm::vec3 normalised(const glm::dvec3& d) {
  return glm::vec3(glm::normalize(d));
}

}  // namespace

EnvMapping parse_env_mapping(const std::string& name) {
  if (name == "auto") return EnvMapping::Auto;
  if (name == "latlong") return EnvMapping::LatLong;
  if (name == "cross") return EnvMapping::VerticalCross;
  if (name == "probe") return EnvMapping::AngularProbe;
  throw Error("unknown environment mapping '" + name +
              "' (expected auto, latlong, cross or probe)");
}

const char* env_mapping_name(EnvMapping mapping) {
  switch (mapping) {
    case EnvMapping::Auto:
      return "auto";
    case EnvMapping::LatLong:
      return "latlong";
    case EnvMapping::VerticalCross:
      return "cross";
    case EnvMapping::AngularProbe:
      return "probe";
  }
  return "?";
}

EnvMapping detect_env_mapping(int width, int height) {
  if (width <= 0 || height <= 0) return EnvMapping::Auto;
  if (width == 2 * height) return EnvMapping::LatLong;
  if (width % 3 == 0 && height % 4 == 0 && width / 3 == height / 4)
    return EnvMapping::VerticalCross;
  if (width == height) return EnvMapping::AngularProbe;
  return EnvMapping::Auto;
}

std::size_t sanitize_radiance(std::vector<float>& rgb) {
  std::size_t bad_texels = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
    bool bad = false;
    for (std::size_t c = 0; c < 3; ++c) {
      float& value = rgb[i + c];
      if (!std::isfinite(value) || value < 0.0f) {
        value = 0.0f;
        bad = true;
      }
    }
    if (bad) ++bad_texels;
  }
  return bad_texels;
}

EnvMap::EnvMap(int width, int height, std::vector<float> rgb, EnvMapping mapping,
               std::string source)
    : width_(width),
      height_(height),
      rgb_(std::move(rgb)),
      mapping_(mapping),
      source_(std::move(source)) {
  const std::string shape = std::to_string(width) + "x" + std::to_string(height);
  if (width <= 0 || height <= 0 ||
      rgb_.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw Error(source_ + ": environment map of " + shape + " texels needs " +
                "width*height*3 floats, got " + std::to_string(rgb_.size()));
  }
  const EnvMapping detected = detect_env_mapping(width, height);
  if (mapping_ == EnvMapping::Auto) {
    if (detected == EnvMapping::Auto) {
      throw Error(source_ + ": cannot tell the environment mapping from the image shape " + shape +
                  " (expected 2:1 lat-long, 3:4 vertical cross or 1:1 angular probe)");
    }
    mapping_ = detected;
  }
  const bool fits =
      (mapping_ == EnvMapping::LatLong && width >= 2 && height >= 1) ||
      (mapping_ == EnvMapping::VerticalCross && detected == EnvMapping::VerticalCross) ||
      (mapping_ == EnvMapping::AngularProbe && width == height);
  if (!fits) {
    throw Error(source_ + ": image shape " + shape + " does not fit the " +
                env_mapping_name(mapping_) + " mapping");
  }
  sanitized_ = sanitize_radiance(rgb_);
}

bool EnvMap::image_texel(int x, int y, glm::vec3* dir, float* solid_angle) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return false;
  if (!dir && !solid_angle && mapping_ == EnvMapping::LatLong) return true;
  switch (mapping_) {
    case EnvMapping::LatLong: {
      // u = 0.5 + atan2(d.x, -d.z)/(2 pi), v = acos(d.y)/pi.
      const double phi0 = (static_cast<double>(x) / width_ - 0.5) * 2.0 * kPi;
      const double dphi = 2.0 * kPi / width_;
      const double theta0 = kPi * y / height_, theta1 = kPi * (y + 1) / height_;
      const double phi = phi0 + 0.5 * dphi, theta = 0.5 * (theta0 + theta1);
      if (dir) {
        *dir = normalised(
            {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)});
      }
      if (solid_angle)
        *solid_angle = static_cast<float>(dphi * (std::cos(theta0) - std::cos(theta1)));
      return true;
    }
    case EnvMapping::VerticalCross: {
      const int f = face_size();
      const CubeFace face = cross_face_at(x / f, y / f);
      if (face == kNoFace) return false;
      if (!dir && !solid_angle) return true;
      const int i = x % f, j = y % f;
      const double u0 = 2.0 * i / f - 1.0, u1 = 2.0 * (i + 1) / f - 1.0;
      const double v0 = 1.0 - 2.0 * (j + 1) / f, v1 = 1.0 - 2.0 * j / f;
      if (dir) *dir = normalised(cross_face_direction(face, 0.5 * (u0 + u1), 0.5 * (v0 + v1)));
      if (solid_angle) *solid_angle = static_cast<float>(cube_texel_solid_angle(u0, v0, u1, v1));
      return true;
    }
    case EnvMapping::AngularProbe: {
      const double half = 0.5 * width_;
      const double u = (x + 0.5 - half) / half, v = (half - y - 0.5) / half;
      const double r = std::sqrt(u * u + v * v);
      if (r > 1.0) return false;
      if (!dir && !solid_angle) return true;
      const double theta = kPi * r, phi = std::atan2(v, u);
      // Probe frame d' = (sin t cos p, sin t sin p, cos t); world = (d'.x, d'.y, -d'.z).
      if (dir) {
        *dir = normalised(
            {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta)});
      }
      if (solid_angle) {
        const double texel = 2.0 * kPi / width_;
        const double sinc = theta > 1e-12 ? std::sin(theta) / theta : 1.0;
        *solid_angle = static_cast<float>(texel * texel * sinc);
      }
      return true;
    }
    case EnvMapping::Auto:
      break;
  }
  return false;
}

namespace {

// Continuous texel coordinates (texel centres at integers + 0.5 removed: centre of texel x is x).
struct LatLongCoord {
  double x, y;
};

// Float and double versions: radiance() runs per sample and needs no more than float.
template <typename T>
LatLongCoord latlong_coord(const glm::vec<3, T>& d, int width, int height) {
  const T pi = static_cast<T>(kPi);
  const T u = T(0.5) + std::atan2(d.x, -d.z) / (T(2) * pi);
  const T v = std::acos(std::clamp(d.y, T(-1), T(1))) / pi;
  return {double(u) * width - 0.5, double(v) * height - 0.5};
}

// Continuous texel coordinates of a direction in the probe image; no atan2/cos/sin: the
// azimuth's cosine and sine are d.x and d.y over their length.
template <typename T>
void probe_coord(const glm::vec<3, T>& d, int width, double* x, double* y) {
  const T r = std::acos(std::clamp(-d.z, T(-1), T(1))) / static_cast<T>(kPi);
  const T len = std::sqrt(d.x * d.x + d.y * d.y);
  const T cos_phi = len > T(0) ? d.x / len : T(1), sin_phi = len > T(0) ? d.y / len : T(0);
  const double half = 0.5 * width;
  *x = double(r * cos_phi) * half + half - 0.5;
  *y = half - double(r * sin_phi) * half - 0.5;
}

}  // namespace

void EnvMap::image_texel_of(const glm::vec3& dir_in, int* x, int* y) const {
  const glm::dvec3 d = glm::normalize(glm::dvec3(dir_in));
  int tx = 0, ty = 0;
  switch (mapping_) {
    case EnvMapping::LatLong: {
      const LatLongCoord c = latlong_coord(d, width_, height_);
      tx = static_cast<int>(std::floor(c.x + 0.5));
      ty = static_cast<int>(std::floor(c.y + 0.5));
      tx = ((tx % width_) + width_) % width_;
      break;
    }
    case EnvMapping::VerticalCross: {
      const int f = face_size();
      double u = 0.0, v = 0.0;
      const CubeFace face = cross_face_of(d, &u, &v);
      int col = 0, row = 0;
      cross_face_cell(face, &col, &row);
      const int i = std::clamp(static_cast<int>(std::floor((u + 1.0) * 0.5 * f)), 0, f - 1);
      const int j = std::clamp(static_cast<int>(std::floor((1.0 - v) * 0.5 * f)), 0, f - 1);
      tx = col * f + i;
      ty = row * f + j;
      break;
    }
    case EnvMapping::AngularProbe: {
      double cx = 0.0, cy = 0.0;
      probe_coord(d, width_, &cx, &cy);
      tx = static_cast<int>(std::floor(cx + 0.5));
      ty = static_cast<int>(std::floor(cy + 0.5));
      if (!image_texel(tx, ty, nullptr, nullptr)) {
        // Near the rim the nearest texel centre can lie just outside the disc: take the nearest
        // neighbour that is inside.
        double best = 1e300;
        const int cx0 = tx, cy0 = ty;
        for (int j = cy0 - 1; j <= cy0 + 1; ++j) {
          for (int i = cx0 - 1; i <= cx0 + 1; ++i) {
            const double dist = (i - cx) * (i - cx) + (j - cy) * (j - cy);
            if (dist < best && image_texel(i, j, nullptr, nullptr)) {
              best = dist;
              tx = i;
              ty = j;
            }
          }
        }
      }
      break;
    }
    case EnvMapping::Auto:
      break;
  }
  *x = std::clamp(tx, 0, width_ - 1);
  *y = std::clamp(ty, 0, height_ - 1);
}

namespace {

// The bilinear footprint of continuous texel coordinates: texels (x0|x1, y0|y1), weights from
// the fractions ax, ay.
EnvMap::Footprint bilinear_footprint(int width, int x0, int x1, int y0, int y1, float ax,
                                     float ay) {
  EnvMap::Footprint f;
  const auto index = [width](int x, int y) {
    return static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(width) +
           static_cast<std::uint32_t>(x);
  };
  f.texel[0] = index(x0, y0);
  f.texel[1] = index(x1, y0);
  f.texel[2] = index(x0, y1);
  f.texel[3] = index(x1, y1);
  f.weight[0] = (1.0f - ax) * (1.0f - ay);
  f.weight[1] = ax * (1.0f - ay);
  f.weight[2] = (1.0f - ax) * ay;
  f.weight[3] = ax * ay;
  return f;
}

}  // namespace

EnvMap::Footprint EnvMap::image_footprint(const glm::vec3& dir_in) const {
  const glm::vec3 d = glm::normalize(dir_in);
  switch (mapping_) {
    case EnvMapping::LatLong:
      return latlong_footprint(d);
    case EnvMapping::VerticalCross: {
      // Bilinear within the face, clamped at its edges (the padding is never read).
      const int f = face_size();
      double u = 0.0, v = 0.0;
      const CubeFace face = cross_face_of(glm::dvec3(d), &u, &v);
      int col = 0, row = 0;
      cross_face_cell(face, &col, &row);
      const double px = std::clamp((u + 1.0) * 0.5 * f - 0.5, 0.0, f - 1.0);
      const double py = std::clamp((1.0 - v) * 0.5 * f - 0.5, 0.0, f - 1.0);
      const int i0 = static_cast<int>(px), j0 = static_cast<int>(py);
      const int i1 = std::min(i0 + 1, f - 1), j1 = std::min(j0 + 1, f - 1);
      const int ox = col * f, oy = row * f;
      return bilinear_footprint(width_, ox + i0, ox + i1, oy + j0, oy + j1, float(px - i0),
                                float(py - j0));
    }
    case EnvMapping::AngularProbe: {
      // Bilinear over the texels inside the disc, weights renormalised at the rim.
      double cx = 0.0, cy = 0.0;
      probe_coord(d, width_, &cx, &cy);
      const double fx = std::floor(cx), fy = std::floor(cy);
      const double ax = cx - fx, ay = cy - fy;
      Footprint f{};
      double w[4] = {0.0, 0.0, 0.0, 0.0}, weight = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int x = static_cast<int>(fx) + (k & 1), y = static_cast<int>(fy) + (k >> 1);
        if (!image_texel(x, y, nullptr, nullptr)) continue;
        w[k] = ((k & 1) ? ax : 1.0 - ax) * ((k >> 1) ? ay : 1.0 - ay);
        f.texel[k] = static_cast<std::uint32_t>(y) * width_ + static_cast<std::uint32_t>(x);
        weight += w[k];
      }
      if (weight > 0.0) {
        for (int k = 0; k < 4; ++k) f.weight[k] = static_cast<float>(w[k] / weight);
        return f;
      }
      int x = 0, y = 0;
      image_texel_of(d, &x, &y);
      f = Footprint{};
      f.texel[0] = static_cast<std::uint32_t>(y) * width_ + static_cast<std::uint32_t>(x);
      f.weight[0] = 1.0f;
      return f;
    }
    case EnvMapping::Auto:
      break;
  }
  return Footprint{};
}

// Bilinear, wrapping around in longitude and clamped at the poles. All in float: this runs for
// every sample, and float texel coordinates (at most 2^15 wide) keep 8+ fractional bits, far
// finer than the bilinear weights need; the integer modulo is left to the rare out-of-range case.
EnvMap::Footprint EnvMap::latlong_footprint(const glm::vec3& d) const {
  constexpr float kInvPi = static_cast<float>(1.0 / kPi), kInvTwoPi = static_cast<float>(0.5 / kPi);
  const float u = 0.5f + atan2_float(d.x, -d.z) * kInvTwoPi;
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  const float cx = u * static_cast<float>(width_) - 0.5f;
  const float cy = v * static_cast<float>(height_) - 0.5f;
  const float fx = std::floor(cx), fy = std::floor(cy);
  int x0 = static_cast<int>(fx);
  if (x0 < 0 || x0 >= width_) x0 = ((x0 % width_) + width_) % width_;
  const int x1 = x0 + 1 == width_ ? 0 : x0 + 1;
  const int y0 = std::clamp(static_cast<int>(fy), 0, height_ - 1);
  const int y1 = std::clamp(static_cast<int>(fy) + 1, 0, height_ - 1);
  return bilinear_footprint(width_, x0, x1, y0, y1, cx - fx, cy - fy);
}

glm::vec3 EnvMap::footprint_radiance(const Footprint& footprint) const {
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 4; ++k) {
    const float* p = rgb_.data() + static_cast<std::size_t>(footprint.texel[k]) * 3;
    sum += footprint.weight[k] * glm::vec3(p[0], p[1], p[2]);
  }
  return sum;
}

void EnvMap::prefetch(const Footprint& footprint) const {
#if defined(__GNUC__) || defined(__clang__)
  for (int k = 0; k < 4; ++k) {
    __builtin_prefetch(rgb_.data() + static_cast<std::size_t>(footprint.texel[k]) * 3);
  }
#else
  (void)footprint;
#endif
}

// Rotation: the image describes the light in its own frame; world direction d sees the image at
// R^T d, and the image's texel direction e is seen from world R e.
void EnvMap::set_rotation(const glm::mat3& rotation) {
  const glm::mat3 should_be_identity = glm::transpose(rotation) * rotation;
  float off = 0.0f;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      const float v = rotation[c][r];
      if (!std::isfinite(v)) throw Error(source_ + ": environment rotation is not finite");
      off = std::max(off, std::abs(should_be_identity[c][r] - (c == r ? 1.0f : 0.0f)));
    }
  }
  if (off > 1e-4f || glm::determinant(rotation) < 0.0f) {
    throw Error(source_ + ": environment rotation is not a proper rotation matrix");
  }
  rotation_ = rotation;
  rotated_ = rotation != glm::mat3(1.0f);
}

glm::vec3 EnvMap::to_image_frame(const glm::vec3& dir) const {
  return rotated_ ? glm::transpose(rotation_) * dir : dir;
}

glm::vec3 EnvMap::radiance(const glm::vec3& dir) const {
  return footprint_radiance(footprint(dir));
}

EnvMap::Footprint EnvMap::footprint(const glm::vec3& dir) const {
  return image_footprint(to_image_frame(dir));
}

bool EnvMap::texel(int x, int y, glm::vec3* dir, float* solid_angle) const {
  if (!image_texel(x, y, dir, solid_angle)) return false;
  if (dir && rotated_) *dir = rotation_ * *dir;
  return true;
}

void EnvMap::texel_of(const glm::vec3& dir, int* x, int* y) const {
  image_texel_of(to_image_frame(dir), x, y);
}

glm::mat3 rotation_about_y(double degrees) {
  // Exact quarter turns keep a 90-degree shift of a lat-long map exact (cos(pi/2) != 0 in
  // floating point).
  const double turns = degrees / 90.0;
  double c = std::cos(degrees * kPi / 180.0), s = std::sin(degrees * kPi / 180.0);
  if (turns == std::floor(turns)) {
    static const double kCos[4] = {1.0, 0.0, -1.0, 0.0}, kSin[4] = {0.0, 1.0, 0.0, -1.0};
    const int k = ((static_cast<int>(std::fmod(turns, 4.0)) % 4) + 4) % 4;
    c = kCos[k];
    s = kSin[k];
  }
  // glm is column-major: m[column][row]. Rows: (c, 0, s), (0, 1, 0), (-s, 0, c).
  glm::mat3 m(1.0f);
  m[0][0] = float(c);
  m[2][0] = float(s);
  m[0][2] = float(-s);
  m[2][2] = float(c);
  return m;
}

void rotation_about_y_row_major(double degrees, float out[9]) {
  const glm::mat3 m = rotation_about_y(degrees);
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) out[3 * row + column] = m[column][row];
  }
}

namespace {

// Texels at RGBE's largest exponent decode to 2^119 .. 2^127 per channel: finite, but far above
// any real radiance, and a sum of two of them is already infinite in single precision.
std::string top_exponent_warning(const std::string& path, std::size_t texels, float largest) {
  char text[200];
  std::snprintf(
      text, sizeof text,
      ": %zu %s the largest RGBE exponent (255), values up to %.3g; no real scene is that "
      "bright, and sums over such texels overflow single precision",
      texels, texels == 1 ? "texel has" : "texels have", static_cast<double>(largest));
  return path + text;
}

}  // namespace

EnvMap load_envmap(const std::string& path, EnvMapping mapping, const MessageHook& messages) {
  const std::vector<unsigned char> bytes = read_file(path);
  if (!detail::has_radiance_signature(bytes) ||
      !stbi_is_hdr_from_memory(bytes.data(), static_cast<int>(bytes.size()))) {
    throw Error(path + ": not a Radiance .hdr image (no #?RADIANCE / #?RGBE signature)");
  }
  const detail::RadianceStreamSummary stream = detail::check_radiance_stream(path, bytes);
  int width = 0, height = 0, channels = 0;
  float* data = stbi_loadf_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width,
                                       &height, &channels, 3);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw Error(path + ": cannot decode the .hdr image (" + (reason ? reason : "unknown") + ")");
  }
  std::vector<float> rgb(data, data + static_cast<std::size_t>(width) * height * 3);
  stbi_image_free(data);
  const float largest = *std::max_element(rgb.begin(), rgb.end());
  EnvMap map(width, height, std::move(rgb), mapping, path);
  if (!messages) return map;
  if (stream.top_exponent_texels > 0) {
    messages(MessageLevel::Warning,
             top_exponent_warning(path, stream.top_exponent_texels, largest));
  }
  if (map.sanitized_texels() > 0) {
    messages(MessageLevel::Warning, path + ": replaced " + std::to_string(map.sanitized_texels()) +
                                        " texels holding NaN, infinite or negative values by 0");
  }
  messages(MessageLevel::Debug, path + ": " + std::to_string(width) + "x" + std::to_string(height) +
                                    " " + env_mapping_name(map.mapping()) + " environment map");
  return map;
}

EnvMap constant_envmap(const glm::vec3& radiance) {
  constexpr int kWidth = 8, kHeight = 4;
  std::vector<float> rgb(kWidth * kHeight * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = radiance.r;
    rgb[i + 1] = radiance.g;
    rgb[i + 2] = radiance.b;
  }
  return EnvMap(kWidth, kHeight, std::move(rgb), EnvMapping::LatLong, "constant environment");
}

namespace {

// Texel direction of face `face` at cube coordinates (s_c, t_c): prt_sh.h's table.
glm::vec3 cube_direction(int face, float s, float t) {
  switch (face) {
    case 0:
      return {1.0f, -t, -s};
    case 1:
      return {-1.0f, -t, s};
    case 2:
      return {s, 1.0f, t};
    case 3:
      return {s, -1.0f, -t};
    case 4:
      return {s, -t, 1.0f};
    default:
      return {-s, -t, -1.0f};
  }
}

}  // namespace

std::vector<std::vector<float>> resample_to_cube(const EnvMap& map, int face_size) {
  if (face_size < 1) throw Error(map.source() + ": cube face size must be >= 1");
  const std::size_t texels = std::size_t(face_size) * std::size_t(face_size);
  std::vector<std::vector<float>> faces(6, std::vector<float>(3 * texels));
  for (int face = 0; face < 6; ++face) {
    float* out = faces[face].data();
    for (int j = 0; j < face_size; ++j) {
      const float t = 2.0f * (static_cast<float>(j) + 0.5f) / static_cast<float>(face_size) - 1.0f;
      for (int i = 0; i < face_size; ++i) {
        const float s =
            2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(face_size) - 1.0f;
        const glm::vec3 value = map.radiance(glm::normalize(cube_direction(face, s, t)));
        for (int c = 0; c < 3; ++c) *out++ = value[c];
      }
    }
  }
  return faces;
}

}  // namespace prt::io
