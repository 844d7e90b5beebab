// SPDX-License-Identifier: MIT
// What every sample draws, once: meshes with per-vertex linear RGB radiance, or meshes shaded per
// pixel by the app from a G-buffer (world normal, tangent, view direction), the environment
// behind them, into a float (HDR) target of the frame's size times the supersampling factor;
// then one tone-map pass (exposure in EV, filmic or linear, sRGB encoding, the supersamples
// averaged in linear light as prt-view does) into an 8-bit target, the picture a screenshot
// takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl.hpp"
#include "orbit_camera.hpp"
#include "prt/io/image_io.hpp"

namespace prt::sample {

// A mesh on the GPU: positions and triangles, and a colour buffer of its own for colours the CPU
// computed. Its bounds are those of the vertices the triangles use. A mesh made with normals and
// tangents (3 floats per vertex each: a surface frame, e.g. cloth's warp) can also be drawn into
// the G-buffer of a per-pixel view.
class GpuMesh {
 public:
  GpuMesh(const float* positions, std::uint32_t vertex_count, const std::uint32_t* indices,
          std::uint32_t triangle_count);
  GpuMesh(const float* positions, const float* normals, const float* tangents,
          std::uint32_t vertex_count, const std::uint32_t* indices, std::uint32_t triangle_count);

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
  // Whether the mesh has normals and tangents (attributes 2 and 3), and draws it with them.
  bool has_frames() const { return normals_.get() != 0; }
  void draw_frames() const;

 private:
  GlVertexArray array_;
  GlBuffer positions_, indices_, colours_, normals_, tangents_;
  std::uint32_t vertex_count_ = 0, index_count_ = 0;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
};

// A part of the frame, in fractions of its width and height from the top left.
struct FrameRect {
  float x0 = 0.0f, y0 = 0.0f, x1 = 1.0f, y1 = 1.0f;
};

// A rectangle of pixels, x0 <= x < x1, y0 <= y < y1, y from the top.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// What a per-pixel view's G-buffer holds, read back for shading on the CPU: every pixel of the
// view's viewport the mesh covers, in pixels of the HDR target (the frame times the
// supersampling). Inside the view's clip the mesh is depth-tested against what the earlier views
// drew there; outside it, it is the mesh drawn alone (what the other side of a split screen shows
// of it), so that two views of one viewport have the same samples.
struct PixelSamples {
  int width = 0, height = 0;         // the viewport, in target pixels
  PixelBox clip;                     // the view's clip within it
  std::vector<std::uint32_t> pixel;  // per sample: y * width + x, y from the viewport's top
  // Per sample, 3 floats each, world space, unit: the normal (turned towards the eye on the
  // mesh's back faces), the tangent made orthogonal to it (0 where the two are parallel) and
  // the direction from the surface to the eye.
  std::vector<float> normals, tangents, views;

  std::size_t size() const { return pixel.size(); }
  bool in_clip(std::size_t sample) const {
    return clip.contains(int(pixel[sample] % std::uint32_t(width)),
                         int(pixel[sample] / std::uint32_t(width)));
  }
};

// The G-buffer as GL textures (RGBA32F, the HDR target's size, one texel per pixel; the same
// vectors as PixelSamples, and (0, 0, 0) where the mesh is not drawn).
struct GlGBuffer {
  GLuint normal_texture = 0, tangent_texture = 0, view_texture = 0;
  int width = 0, height = 0;
};

// The app's shading of a per-pixel view. The framework draws the view's mesh into the G-buffer,
// then either the app draws radiance with GL (uses_gl) or the framework reads the G-buffer back,
// the app shades the samples on the CPU (shade) and the framework uploads the result. Exceptions
// thrown here end the run as the app's other failures do.
class PixelShader {
 public:
  virtual ~PixelShader() = default;
  // True: shade_gl draws this view's radiance.
  virtual bool uses_gl() const { return false; }
  // Draws radiance (RGB, alpha 1) into the bound draw framebuffer where the G-buffer's normal
  // is not 0: the HDR target itself, or (when the radiance is read back) a float target of the
  // same size. The viewport is the whole target, texel for pixel, and the scissor test keeps the
  // view's pixels; depth test and blending are off.
  virtual void shade_gl(const GlGBuffer&) {}
  // True: a GL view's radiance is drawn over its whole viewport into a float target, read back
  // and handed to gl_radiance (to compare it, say) before it is composited like a CPU view's.
  virtual bool reads_gl_radiance() const { return false; }
  virtual void gl_radiance(const PixelSamples&, const std::vector<float>& /*rgb*/) {}
  // CPU: 3 floats per sample into rgb (sized by the caller): linear radiance, or display colours
  // when the view says so. A sample whose red is NaN is not drawn (what is behind shows), nor
  // are samples outside the clip: they may be left at 0.
  virtual void shade(const PixelSamples&, std::vector<float>& /*rgb*/) {}
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
  // Per pixel: the mesh (made with normals and tangents) is drawn into the G-buffer and this
  // shades it; colour_buffer is not used then.
  PixelShader* pixel_shader = nullptr;
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
  GlProgram mesh_program_, background_program_, tone_program_, gbuffer_program_, composite_program_;
  GlVertexArray empty_array_;
  GlFramebuffer hdr_fbo_, display_fbo_, gbuffer_fbo_, radiance_fbo_;
  GlTexture hdr_colour_, hdr_depth_, display_colour_;
  // Made on the first per-pixel view: normal, tangent, view, depth; the radiance read back.
  GlTexture gbuffer_[4], radiance_;
  int width_ = 0, height_ = 0, supersample_ = 1;

  void resize(int width, int height, int supersample);
  void make_gbuffer();
  // A view's viewport and clip in target pixels (GL's, from the bottom left).
  struct ViewPixels {
    GLint port[4], clip[4];  // x, y, width, height; the clip within the viewport
  };
  void draw_view(const View& view, const OrbitCamera& camera, const Background& background);
  void draw_pixels(const View& view, const OrbitCamera& camera, const ViewPixels& at);
  void fill_gbuffer(const GpuMesh& mesh, const OrbitCamera& camera, const ViewPixels& at);
  PixelSamples read_samples(const ViewPixels& at) const;
  void upload_radiance(const PixelSamples& samples, const std::vector<float>& rgb,
                       const ViewPixels& at);
  std::vector<float> read_radiance(const PixelSamples& samples, const ViewPixels& at) const;
  void composite(const ViewPixels& at, float tag, bool colour);
};

}  // namespace prt::sample
