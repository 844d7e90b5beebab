// SPDX-License-Identifier: MIT
// Image and array files: per-vertex radiance as NumPy .npy, images as tone-mapped sRGB PNG or
// linear Radiance .hdr (the reference renderer's outputs and the viewers'), display-colour PNGs
// and montages.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/error.hpp"

namespace prt::io {

// Linear RGB radiance, row-major from the top row.
struct LinearImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;
  // Per pixel, the fraction of its samples that hit a surface (empty when not known).
  std::vector<float> coverage;
};

// Writes float32 little-endian, C order, shape [values.size(), 3] (.npy format 1.0).
// Throws Error naming the file if it cannot be written.
void write_npy_vec3(const std::string& path, const std::vector<glm::vec3>& values);
// Reads a float32 little-endian C-order array of shape [N, 3] (.npy 1.0/2.0), what
// write_npy_vec3 writes. Throws Error naming the file on anything else.
std::vector<glm::vec3> read_npy_vec3(const std::string& path);

// Exposure (in EV, a scale of 2^EV) for a tone-mapped image, metered on the subject: the
// log-average luminance of the pixels mostly covered by surfaces (coverage >= 0.5) maps to 0.35,
// so a white diffuse object comes out light grey with its shading intact, whatever the
// background. Without such pixels, the log-average of all pixels maps to middle grey 0.18
// (Reinhard et al. 2002's key value). Zero and non-finite luminances are ignored; 0 EV for an
// image that has none left.
float auto_exposure_ev(const LinearImage& image);

// Filmic tone map (the ACES fit of K. Narkowicz, 2015) of radiance x 2^exposure_ev, then sRGB
// encoding: RGB8, width*height*3 bytes.
std::vector<std::uint8_t> tone_map_srgb8(const LinearImage& image, float exposure_ev);

// Writes `image` by the file extension: .png -> tone-mapped sRGB (exposure_ev as above), .hdr ->
// linear radiance (no exposure). Throws Error naming the file on any other extension or failure.
void write_image(const std::string& path, const LinearImage& image, float exposure_ev);

// Writes `image` as an 8-bit RGB PNG, its values taken as display colours already: sRGB-encoded
// in [0,1] (clamped; non-finite values show as 1), as a heat map or false colours are. Throws
// Error naming the file on failure.
void write_display_png(const std::string& path, const LinearImage& image);

// Tiles `inputs` (PNG files of one size, row-major, `columns` per row) with `gap` black pixels
// between tiles into the PNG `output`. Throws Error naming the file that cannot be read or whose
// size differs from the first.
void write_montage(const std::string& output, const std::vector<std::string>& inputs, int columns,
                   int gap);

}  // namespace prt::io
