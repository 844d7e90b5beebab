// SPDX-License-Identifier: MIT
// The `wavelet` relight benchmarks' asset (wavelet_bench.cpp, wavelet_gl_bench.cpp): a WVLT
// transfer of the Stanford bunny's 35,947 vertices on the N = 64 cube, with rows shaped like a
// real bake keeping about 1000 coefficients per vertex (`--cube 64 --keep 1000`), built byte by
// byte by the test util so that the benchmark depends on neither the baker nor the envmaps.
//
// Row shape: a diffuse transfer lives on the hemisphere about the normal, so its energy sits on
// about three faces, and the kept coefficients concentrate in the coarse levels (Ng et al. 2003,
// §5): per face of three, every coefficient of levels -1..2 (64) and a share of levels 3, 4, 5
// (60 %, 15 %, 1.3 %), about 334 per face, 1000 per vertex. Level j's coefficients occupy
// max(x, y) in [2^j, 2^(j+1)) of the face (SPEC §14), so the pairs fall in the first blocks of
// each face, as in a bake.
#pragma once

#include <cstdint>
#include <vector>

#include "wavelet/wavelet_blob_test_util.hpp"

namespace prt_bench {

constexpr uint32_t kBunnyVertices = 35947, kWaveletSize = 64;
// The implementation report's figure: 3 frames/s for a 40,000-vertex mesh (about 1000 kept
// coefficients per vertex, 2003 hardware).
constexpr double kPaperFps = 3.0, kPaperVertices = 40000.0;

// A small, fast generator (SplitMix64): 12k draws per vertex, 36k vertices.
struct SplitMix {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double unit() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
};

// Share of each level's coefficients kept, by level + 1 (levels -1..6 for S up to 128), for
// `--keep 1000` rows.
constexpr double kKeep1000Share[8] = {1.0, 1.0, 1.0, 1.0, 0.6, 0.15, 0.013, 0.003};

inline prt_test::WvltTransfer bake_shaped_transfer(uint32_t vertices = kBunnyVertices,
                                                   uint32_t size = kWaveletSize, uint64_t seed = 1,
                                                   const double* kept_share = kKeep1000Share) {
  prt_test::WvltTransfer t = prt_test::wvlt_random(PRT_WAVELET_PARAM_CUBE, size, vertices, 0, 7);
  SplitMix rng{seed};
  uint32_t keep = 0;
  for (uint32_t v = 0; v < vertices; ++v) {
    std::vector<prt_test::WvltPair>& row = t.rows[v];
    // One face per axis, on the side the (random) normal faces: faces 2a and 2a + 1 are +a, -a.
    const uint64_t signs = rng.next();
    for (uint32_t axis = 0; axis < 3; ++axis) {
      const uint32_t face = 2 * axis + uint32_t((signs >> axis) & 1u);
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
          const uint32_t m = x > y ? x : y;
          int level = -1;
          for (uint32_t rest = m; rest != 0; rest >>= 1) ++level;
          const double share = kept_share[level + 1];
          if (share < 1.0 && rng.unit() >= share) continue;
          // Coarser levels carry larger values; never 0.
          const int magnitude = 1 + int(rng.next() % uint64_t(level < 3 ? 127 : 40));
          const int8_t q = int8_t(rng.next() & 1u ? magnitude : -magnitude);
          row.push_back({face * size * size + y * size + x, q});
        }
    }
    // Faces were visited in increasing order within each axis pair, and axes in order, so the
    // row is already sorted by j.
    keep = keep > row.size() ? keep : uint32_t(row.size());
  }
  t.keep = keep;
  return t;
}

// Bytes a shade streams per vertex on average: its pairs (2 B each), block counts (2 B per
// block), row start (4 B) and vertex scale (12 B); and the light it gathers: 16 B (RGBA float)
// per pair, mostly from cache (the N = 64 light is 384 KiB).
struct WaveletTraffic {
  double streamed_per_vertex = 0.0, gathered_per_vertex = 0.0, pairs_per_vertex = 0.0;
};
inline WaveletTraffic wavelet_traffic(const prt_test::WvltTransfer& t) {
  WaveletTraffic w;
  w.pairs_per_vertex = double(t.pair_count()) / double(t.vertices);
  w.streamed_per_vertex = 2.0 * w.pairs_per_vertex + 2.0 * t.blocks() + 4.0 + 12.0;
  w.gathered_per_vertex = 16.0 * w.pairs_per_vertex;
  return w;
}

}  // namespace prt_bench
