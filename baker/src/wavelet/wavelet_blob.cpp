// SPDX-License-Identifier: MIT
// The WVLT section encoder and the `wavelet` blob (formats/SPEC.md §7.2).
#include "prt/baker/wavelet/wavelet_blob.hpp"

#include "../common/technique_blob.hpp"

#include <prt/prt.h>
#include <prt/prt_wavelet.h>

#include <cmath>
#include <cstring>

#include <prt/format/blob_writer.hpp>

namespace prt::bake {
namespace {

constexpr std::size_t kWvltHeaderBytes = 32;
constexpr std::uint32_t kBlockSize = 256;

class ByteWriter {
 public:
  explicit ByteWriter(std::size_t size) : bytes_(size, 0) {}
  void u8(std::uint8_t v) { bytes_[at_++] = v; }
  void u16(std::uint16_t v) {
    u8(static_cast<std::uint8_t>(v));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  std::size_t position() const { return at_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<std::uint8_t> encode_wvlt_section(const QuantizedWavelet& qw) {
  const std::size_t vertices = qw.vertex_count, blocks = qw.block_count();
  const std::size_t pairs = qw.pair_count();
  std::size_t size = kWvltHeaderBytes + 4 * qw.band_scale.size() + 12 * vertices +
                     4 * (vertices + 1) + 2 * vertices * blocks + 2 * pairs;
  size = (size + 3) / 4 * 4;
  ByteWriter out(size);
  const std::uint32_t header[8] = {qw.param,
                                   qw.size,
                                   static_cast<std::uint32_t>(vertices),
                                   static_cast<std::uint32_t>(qw.quantizer),
                                   qw.keep,
                                   qw.bounces,
                                   static_cast<std::uint32_t>(pairs),
                                   0};
  for (std::uint32_t h : header) out.u32(h);
  for (float b : qw.band_scale) out.f32(b);
  for (float s : qw.vertex_scale) out.f32(s);
  for (std::uint32_t r : qw.row_start) out.u32(r);
  for (std::size_t v = 0; v < vertices; ++v) {  // block counts
    std::vector<std::uint16_t> count(blocks, 0);
    for (std::uint32_t p = qw.row_start[v]; p < qw.row_start[v + 1]; ++p) {
      ++count[qw.index[p] / kBlockSize];
    }
    for (std::uint16_t c : count) out.u16(c);
  }
  // Pairs: row by row, and within a row ascending index is block by block, ascending in block.
  for (std::size_t p = 0; p < pairs; ++p) {
    out.u8(static_cast<std::uint8_t>(qw.index[p] % kBlockSize));
    out.u8(static_cast<std::uint8_t>(qw.q[p]));
  }
  return out.take();
}

std::vector<std::uint8_t> build_wavelet_blob(const Scene& scene, const QuantizedWavelet& quantized,
                                             const std::string& info) {
  if (scene.vertex_count() != quantized.vertex_count) {
    throw Error("wavelet blob: the transfer has " + std::to_string(quantized.vertex_count) +
                " vertices, the scene " + std::to_string(scene.vertex_count()));
  }
  prt::format::BlobWriter writer = start_technique_blob(scene, info);
  const std::vector<std::uint8_t> wvlt = encode_wvlt_section(quantized);
  writer.add_section(PRT_SECTION_WVLT, wvlt.data(), wvlt.size(), scene.vertex_count(),
                     required_section());
  return writer.finish();
}

}  // namespace prt::bake
