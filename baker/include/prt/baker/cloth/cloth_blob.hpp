// SPDX-License-Identifier: MIT
// The CLTH section of technique `cloth` (formats/SPEC.md §7.4) from a description of its fabrics
// and factored tables, the description back from the bytes (dequantised: the bake's self-check and
// the tests), and a whole cloth blob with the mesh to draw it on.
#pragma once

#include <prt/prt_cloth.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prt::bake {

// One distinct offset of a thread's tangent multiset (a tangent record).
struct ClothTangent {
  float offset = 0.0f;             // tau, radians, |tau| <= pi/2
  std::uint32_t multiplicity = 1;  // copies of tau in the multiset, 1..64
  std::uint32_t table = 0;         // index into ClothSection::tables
  bool mirror = false;             // read the table with x -> -x (view and lobe)
};

// A fabric: its name, default live parameters and each thread's distinct offsets.
struct ClothFabric {
  std::string name;                                  // UTF-8, 1..32 bytes, no NUL
  prt_cloth_params params{};                         // struct_size is not stored
  std::array<std::vector<ClothTangent>, 2> threads;  // [0] warp, [1] weft: 1..16 offsets each
};

// The grids every table is sampled on (SPEC §7.4: octahedral lobe nodes, log-uniform sharpness
// levels, view nodes over theta in [0, pi/2] and phi in [0, pi]).
struct ClothGrid {
  std::uint32_t xi_size = 0;        // N_xi, 2..256
  std::uint32_t lambda_levels = 0;  // L, 1..64
  float lambda_min = 0.0f;          // > 0
  float lambda_max = 0.0f;          // >= lambda_min (= it when L = 1)
  std::uint32_t view_theta = 0;     // N_theta, 2..256
  std::uint32_t view_phi = 0;       // N_phi, 2..256

  std::uint64_t rows() const { return std::uint64_t(lambda_levels) * xi_size * xi_size; }
  std::uint64_t columns() const { return std::uint64_t(view_theta) * view_phi; }
};

// A factorisation table ~ U V^T of rank R: u is rows x R (row-major, row = level N_xi^2 +
// j N_xi + i, singular values folded in), v is columns x R (column = a N_phi + b).
struct ClothFactor {
  std::uint32_t rank = 0;  // 1..64
  std::vector<float> u;
  std::vector<float> v;
};

// One table record: the lobe-weighted convolution T and its cone restriction T_c.
struct ClothTable {
  ClothFactor full;
  ClothFactor cone;
};

struct ClothSection {
  ClothGrid grid;
  std::vector<ClothFabric> fabrics;  // 1..64
  std::vector<ClothTable> tables;    // 1..1024
};

// The section's bytes (little-endian, zero-padded, deterministic), with 8 or 16 bits per factor
// value: each column r of U and of V is quantised with its own scale, max |value| / qmax (qmax =
// 127 or 32767; 0 for a column of zeros), q = round(value / scale) half away from zero. The
// tangent records are written thread after thread, fabric after fabric. Throws
// std::invalid_argument naming what breaks SPEC §7.4 (a count, a size, a non-finite value, or a
// rule the formats checker reports on the bytes).
std::vector<std::uint8_t> encode_clth_section(const ClothSection& section, int bits);

// What a CLTH section's bytes describe: every factor value dequantised (scale x q, rounded once to
// f32), params.struct_size set. Throws std::invalid_argument, with the formats checker's message,
// when the bytes fail full validation of the section.
struct DecodedClothSection {
  ClothSection section;
  int bits = 0;
};
DecodedClothSection decode_clth_section(const std::uint8_t* bytes, std::size_t size);

// A mesh to draw the cloth on: positions, and optionally normals and thread 1's direction.
struct ClothMesh {
  std::vector<float> positions;          // x, y, z per vertex (at least one vertex)
  std::vector<float> normals;            // x, y, z per vertex, or empty
  std::vector<float> tangents;           // x, y, z per vertex (the warp), or empty
  std::vector<std::uint32_t> triangles;  // i0, i1, i2 per triangle, each < the vertex count
};

// A whole blob, deterministic: INFO (when `info` is not empty); with a mesh, VPOS (required),
// VNRM and VTAN (optional sections, each when given) and TRIS (required); then CLTH (required).
// Every section is zstd where that is smaller; producer "prtkit <version>". Throws
// std::invalid_argument for a mesh whose arrays disagree, hold a non-finite float or an index out
// of range, and as encode_clth_section.
std::vector<std::uint8_t> write_cloth_blob(const ClothSection& section, int bits,
                                           const ClothMesh* mesh, const std::string& info);

}  // namespace prt::bake
