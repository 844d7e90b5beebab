// SPDX-License-Identifier: MIT
// The runtime's private CLTH view (runtime/src/cloth/cloth_internal.h), which the shading reads
// and no public function exposes: on the section built by hand (cloth/clth_test_section.hpp),
// every record and every factorisation's ranks, scales and values are where SPEC §7.4 puts them.
#include <gtest/gtest.h>

#include <cstring>

#include "cloth/clth_test_section.hpp"
#include "support/mesh_blob.hpp"

extern "C" {
#include "cloth/cloth_internal.h"
#include "techniques.h"
}

namespace {

using namespace prt_test;

float f32_at(const uint8_t* p) {
  float f;
  const uint32_t bits = prt_le_load_u32(p);
  std::memcpy(&f, &bits, 4);
  return f;
}

int value_at(const void* block, size_t k, uint32_t bits) {
  const uint8_t* p = static_cast<const uint8_t*>(block);
  return bits == 8 ? int(int8_t(p[k])) : int(int16_t(prt_le_load_u16(p + 2 * k)));
}

TEST(ClothView, FactorisationsAreWhereTheSpecPutsThem) {
  for (uint32_t bits : {8u, 16u}) {
    const ClthTestSection s = small_clth(bits);
    Context ctx;
    const LoadedAsset a(ctx.ctx, clth_blob(s.bytes(), 2), PRT_VALIDATE_QUICK);
    ASSERT_EQ(a.result, PRT_OK);
    const auto* view =
        static_cast<const prt_cloth_view*>(prt_internal_view(a.asset, PRT_TECHNIQUE_CLOTH));
    ASSERT_NE(view, nullptr);
    for (uint32_t q = 0; q < 2; ++q)
      for (int cone = 0; cone < 2; ++cone) {
        prt_cloth_factor f;
        prt_cloth_read_factor(view, q, cone, &f);
        const uint32_t rank = s.rank_of(q, cone);
        ASSERT_EQ(f.rank, rank);
        EXPECT_EQ(f.bits, bits);
        for (uint32_t r = 0; r < rank; ++r) {
          EXPECT_EQ(f32_at(f.u_scale + 4 * r), ClthTestSection::scale(q, cone, r, false));
          EXPECT_EQ(f32_at(f.v_scale + 4 * r), ClthTestSection::scale(q, cone, r, true));
        }
        // The hand-built section's value k of a block is value(seed + k) (clth_test_section.hpp).
        const size_t seed = 100 * q + 50 * size_t(cone);
        for (size_t k = 0; k < s.columns() * rank; ++k)
          ASSERT_EQ(value_at(f.v_values, k, bits), s.value(seed + k)) << q << cone << k;
        for (size_t k = 0; k < s.rows() * rank; ++k)
          ASSERT_EQ(value_at(f.u_values, k, bits), s.value(seed + 7 + k)) << q << cone << k;
      }
  }
}

TEST(ClothView, RecordsAreWhatWasWritten) {
  const ClthTestSection s = small_clth();
  Context ctx;
  const LoadedAsset a(ctx.ctx, clth_blob(s.bytes(), 2), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  const auto* view =
      static_cast<const prt_cloth_view*>(prt_internal_view(a.asset, PRT_TECHNIQUE_CLOTH));
  ASSERT_NE(view, nullptr);
  for (uint32_t g = 0; g < 3; ++g) {
    prt_cloth_tangent_record t;
    prt_cloth_read_tangent(view, g, &t);
    EXPECT_EQ(t.offset, s.tangents[g].offset);
    EXPECT_EQ(t.multiplicity, s.tangents[g].multiplicity);
    EXPECT_EQ(t.table, s.tangents[g].table);
    EXPECT_EQ(t.mirror, s.tangents[g].mirror);
  }
  for (uint32_t f = 0; f < 2; ++f) {
    prt_cloth_fabric_record record;
    prt_cloth_read_fabric(view, f, &record);
    EXPECT_STREQ(record.name, s.fabrics[f].name.c_str());
    EXPECT_STREQ(view->names[f], s.fabrics[f].name.c_str());
    prt_cloth_weave weave;
    prt_cloth_fabric_weave(view, &record, &weave);
    EXPECT_EQ(weave.struct_size, sizeof weave);
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(record.first_tangent[j], s.fabrics[f].threads[j].first);
      EXPECT_EQ(record.tangent_count[j], s.fabrics[f].threads[j].count);
      EXPECT_EQ(record.params.threads[j].gamma_v, s.fabrics[f].threads[j].gamma_v);
      EXPECT_EQ(weave.tangent_count[j], s.fabrics[f].threads[j].count);
    }
  }
}

}  // namespace
