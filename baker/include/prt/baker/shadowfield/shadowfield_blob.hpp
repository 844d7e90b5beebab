// SPDX-License-Identifier: MIT
// The `shadowfield` blob: a baked ShadowfieldObject quantised and written as sections VPOS, VNRM,
// TRIS (the object's mesh, its own frame) and SFLD (formats/SPEC.md §7.5).
//
// The four big arrays are quantised to 8 or 16 bits with an (offset, scale) pair per row, as
// sh_blob.hpp does per column: offset = min, scale = (max - min) / (2^bits - 1),
// q = round((t - min) / scale) rounded half away from zero and clamped to [0, 2^bits - 1]; a
// constant row gets scale 0 and q = 0 (exact). Rows: the transfer per (term, coefficient), the
// OOF per coefficient, the basis per basis function, the SRF per (field, coefficient). The other
// arrays are stored as f32.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/shadowfield/shadowfield_object.hpp"

namespace prt::bake {

// One quantised array: rows (offset, scale) pairs and one q per value, in the array's order.
struct QuantizedShadowfieldBlock {
  std::vector<float> offsets, scales;  // per row
  std::vector<std::uint16_t> q;
  // Of offset + scale * q (in float, as a reader computes it) against the float array.
  double max_abs_error = 0.0;
  double max_abs_value = 0.0;  // max |t|, the scale the error can be read against
};

struct QuantizedShadowfield {
  std::uint32_t bits = 16;  // 8 or 16
  QuantizedShadowfieldBlock transfer, oof, basis, srf;
};

// Throws Error naming the first field of `object` that the SFLD layout cannot hold: an order,
// term count, BRDF grid, basis size or shell grid out of range, an array of the wrong size, a
// non-finite float, albedo outside [0, 1], a negative vertex weight, an index past the vertices.
void check_shadowfield_object(const ShadowfieldObject& object);

// Quantises the object's transfer, OOF, basis and SRF to `bits` (8 or 16; Error otherwise),
// after check_shadowfield_object.
QuantizedShadowfield quantize_shadowfield(const ShadowfieldObject& object, int bits);

// The raw bytes of the SFLD section (little-endian, zero padding).
std::vector<std::uint8_t> encode_sfld_section(const ShadowfieldObject& object,
                                              const QuantizedShadowfield& quantized);

// The complete blob: INFO (`info`, skipped when empty), VPOS, VNRM, TRIS and SFLD, each zstd
// where that makes it smaller; producer "prtkit <version>". The same inputs give the same bytes.
// Throws Error when `quantized` is not `object`'s (sizes).
std::vector<std::uint8_t> build_shadowfield_blob(const ShadowfieldObject& object,
                                                 const QuantizedShadowfield& quantized,
                                                 const std::string& info);

}  // namespace prt::bake
