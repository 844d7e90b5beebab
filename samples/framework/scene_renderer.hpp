// SPDX-License-Identifier: MIT
// What every sample draws, once: meshes with per-vertex linear RGB radiance, the environment
// behind them, into a float (HDR) target of the frame's size times the supersampling factor;
// then one tone-map pass (exposure in EV, filmic or linear, sRGB encoding, the supersamples
// averaged in linear light as prt-view does) into an 8-bit target, the picture a screenshot
// takes.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl.hpp"
#include "orbit_camera.hpp"
#include "prt/io/image_io.hpp"

namespace prt::sample {

// A mesh on the GPU: positions and triangles, and a colour buffer of its own for colours the CPU
// computed. Its bounds are those of the vertices the triangles use.
class GpuMesh {
 public:
  GpuMesh(const float* positions, std::uint32_t vertex_count, const std::uint32_t* indices,
          std::uint32_t triangle_count);

  // Uploads vertex_count RGB float triples into the mesh's own colour buffer.
  void upload_colours(const float* rgb);
  // Replaces the positions (vertex_count triples: a skinned mesh's new pose); the bounds stay
  // those the mesh was made with, so framing does not follow the animation.
  void upload_positions(const float* positions);
  GLuint own_colours() const { return colours_.get(); }

  std::uint32_t vertex_count() const { return vertex_count_; }
  const glm::vec3& lo() const { return lo_; }
  const glm::vec3& hi() const { return hi_; }

  // Draws with `colour_buffer` (12-byte RGB float stride) as the colour attribute: the mesh's
  // own or a buffer the runtime's GL backend wrote.
  void draw(GLuint colour_buffer) const;

 private:
  GlVertexArray array_;
  GlBuffer positions_, indices_, colours_;
  std::uint32_t vertex_count_ = 0, index_count_ = 0;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
};

// A part of the frame, in fractions of its width and height from the top left.
struct FrameRect {
  float x0 = 0.0f, y0 = 0.0f, x1 = 1.0f, y1 = 1.0f;
};

// One picture of a mesh in the frame: the camera's view fills `viewport`; only `clip` of it is
// drawn (a split screen draws two views of the same viewport, each clipped to its side).
struct View {
  const GpuMesh* mesh = nullptr;
  GLuint colour_buffer = 0;
  // Colours that are display values already (sRGB, e.g. an error heat map): not tone mapped,
  // drawn over a mid-grey backdrop instead of the environment.
  bool display_colours = false;
  FrameRect viewport, clip;
};

enum class ToneMap { Filmic, Linear };
const char* tone_map_name(ToneMap tone_map);

struct RenderSettings {
  float exposure_ev = 0.0f;
  ToneMap tone_map = ToneMap::Filmic;
};

// The background: the current environment texture (lat-long) turned by `rotation` (world from
// image frame, as prt_io's EnvMap::set_rotation).
struct Background {
  GLuint latlong_texture = 0;
  glm::mat3 rotation{1.0f};
};

class SceneRenderer {
 public:
  SceneRenderer();

  // Draws the views into the HDR target, sized width x height times `supersample`.
  void render(int width, int height, int supersample, const std::vector<View>& views,
              const OrbitCamera& camera, const Background& background);
  // Tone maps the HDR target into the 8-bit target (same size as the frame).
  void tone_map(const RenderSettings& settings);

  // The HDR target as prt_io's LinearImage (supersampled size, top row first), coverage 1 where
  // a radiance surface was drawn: what auto-exposure meters.
  prt::io::LinearImage read_hdr() const;
  // The 8-bit target, RGB, top row first.
  std::vector<std::uint8_t> read_display(int* width, int* height) const;
  GLuint display_framebuffer() const { return display_fbo_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  GlProgram mesh_program_, background_program_, tone_program_;
  GlVertexArray empty_array_;
  GlFramebuffer hdr_fbo_, display_fbo_;
  GlTexture hdr_colour_, hdr_depth_, display_colour_;
  int width_ = 0, height_ = 0, supersample_ = 1;

  void resize(int width, int height, int supersample);
  void draw_view(const View& view, const OrbitCamera& camera, const Background& background);
};

}  // namespace prt::sample
