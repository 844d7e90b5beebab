// SPDX-License-Identifier: MIT
// Which tables fabrics need and how their tangents share them (plan_cloth_tables), and the
// symmetries of the model that make the sharing exact: W of offset -tau of a multiset S is W of
// tau of -S mirrored x -> -x (so, for S symmetric about 0, of tau of S), and W is unchanged by
// y -> -y (so the view grid needs y >= 0 only).
#include <gtest/gtest.h>
#include <prt/prt_cloth.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The mirrors are exact in float (a sign flip) and the model evaluates them exactly alike: W
// agrees to within a unit of float at 1, which leaves room for another order of operations.
constexpr double kFloatUlp = 1.2e-7;

float degrees(double d) {
  return float(d * kPi / 180.0);
}

prt_cloth_weave weave_of(std::vector<double> offsets_deg, std::vector<std::uint32_t> counts) {
  prt_cloth_weave w{};
  w.struct_size = sizeof(prt_cloth_weave);
  for (int j = 0; j < 2; ++j) {
    w.tangent_count[j] = std::uint32_t(offsets_deg.size());
    for (std::size_t k = 0; k < offsets_deg.size(); ++k) {
      w.offsets[j][k] = degrees(offsets_deg[k]);
      w.multiplicity[j][k] = counts[k];
    }
  }
  return w;
}

double uniform(std::uint64_t& state) {  // [0, 1), splitmix64
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

// A direction above the cloth (z > 0), as floats.
std::array<float, 3> upper_direction(std::uint64_t& state) {
  const double z = 0.02 + 0.98 * uniform(state), phi = 2.0 * kPi * uniform(state);
  const double r = std::sqrt(1.0 - z * z);
  return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
}

// W of every offset of thread 0 of `weave`, frame normal +z, warp +x (the canonical frame).
std::vector<float> weights(const prt_cloth_weave& weave, const std::array<float, 3>& light,
                           const std::array<float, 3>& view) {
  static const float normal[3] = {0.0f, 0.0f, 1.0f}, warp[3] = {1.0f, 0.0f, 0.0f};
  std::vector<float> out(weave.tangent_count[0]);
  EXPECT_EQ(
      prt_cloth_thread_weights(&weave, 0, normal, warp, light.data(), view.data(), out.data()),
      PRT_OK);
  return out;
}

std::array<float, 3> mirror_x(std::array<float, 3> w) {
  w[0] = -w[0];
  return w;
}

std::array<float, 3> mirror_y(std::array<float, 3> w) {
  w[1] = -w[1];
  return w;
}

// The index of `offset` in thread 0 of `weave`.
std::uint32_t index_of(const prt_cloth_weave& weave, float offset) {
  for (std::uint32_t k = 0; k < weave.tangent_count[0]; ++k)
    if (weave.offsets[0][k] == offset) return k;
  ADD_FAILURE() << "no offset " << offset;
  return 0;
}

// The largest |W - W'| over random pairs of directions, W' read at the mirrored directions in
// `other` at offset -tau (mirror x) or tau (mirror y).
double largest_mirror_difference(const prt_cloth_weave& weave, const prt_cloth_weave& other,
                                 bool mirror_in_x) {
  std::uint64_t state = 7;
  double largest = 0.0;
  for (int n = 0; n < 2000; ++n) {
    const std::array<float, 3> light = upper_direction(state), view = upper_direction(state);
    const std::vector<float> w = weights(weave, light, view);
    const std::vector<float> m = mirror_in_x ? weights(other, mirror_x(light), mirror_x(view))
                                             : weights(other, mirror_y(light), mirror_y(view));
    for (std::uint32_t k = 0; k < weave.tangent_count[0]; ++k) {
      const float tau = weave.offsets[0][k];
      const std::uint32_t k_other = index_of(other, mirror_in_x ? -tau : tau);
      largest = std::max(largest, double(std::fabs(w[k] - m[k_other])));
    }
  }
  return largest;
}

TEST(ClothTablePlan, WOfMinusTauIsWOfTauMirroredInX) {
  // Satin's warp: symmetric about 0, with multiplicities.
  const prt_cloth_weave satin = weave_of({-32, -18, 0, 18, 32}, {2, 1, 2, 1, 2});
  EXPECT_LE(largest_mirror_difference(satin, satin, true), kFloatUlp);
  // Velvet's warp is not symmetric: -tau of S reads tau of -S.
  const prt_cloth_weave velvet = weave_of({-90, -50}, {1, 1});
  const prt_cloth_weave reversed = weave_of({50, 90}, {1, 1});
  EXPECT_LE(largest_mirror_difference(velvet, reversed, true), kFloatUlp);
  // It holds for -S only: other multiplicities weigh the offsets otherwise.
  const prt_cloth_weave other = weave_of({50, 90}, {2, 1});
  EXPECT_GT(largest_mirror_difference(velvet, other, true), 0.1);
}

TEST(ClothTablePlan, WIsUnchangedByMirrorInY) {
  EXPECT_LE(
      largest_mirror_difference(weave_of({-90, -50}, {1, 1}), weave_of({-90, -50}, {1, 1}), false),
      1e-6);
  const prt_cloth_weave satin = weave_of({-32, -18, 0, 18, 32}, {2, 1, 2, 1, 2});
  EXPECT_LE(largest_mirror_difference(satin, satin, false), kFloatUlp);
}

std::vector<prt_cloth_weave> preset_weaves() {
  std::vector<prt_cloth_weave> weaves;
  for (const prt::bake::ClothPreset& p : prt::bake::cloth_fabrics()) weaves.push_back(p.weave);
  return weaves;
}

TEST(ClothTablePlan, LinensThreadsShareOneTable) {
  const ClothTablePlan plan = plan_cloth_tables({prt::bake::cloth_fabric("linen_plain").weave});
  ASSERT_EQ(plan.tables.size(), 1u);
  EXPECT_EQ(plan.tables[0].offsets, (std::vector<float>{degrees(-25), degrees(25)}));
  EXPECT_EQ(plan.tables[0].offset(), degrees(25));
  for (int j = 0; j < 2; ++j) {
    const std::vector<ClothTangent>& records = plan.threads[0][j];
    ASSERT_EQ(records.size(), 2u);
    for (const ClothTangent& t : records) {
      EXPECT_EQ(t.table, 0u);
      EXPECT_EQ(t.multiplicity, 1u);
      EXPECT_EQ(t.mirror, t.offset < 0.0f);
    }
  }
}

TEST(ClothTablePlan, SatinsWarpHasThreeTablesForFiveOffsets) {
  const ClothTablePlan plan =
      plan_cloth_tables({prt::bake::cloth_fabric("polyester_satin_charmeuse").weave});
  ASSERT_EQ(plan.tables.size(), 4u);  // 0, 18, 32 degrees of the warp; the weft's 0
  const std::vector<ClothTangent>& warp = plan.threads[0][0];
  ASSERT_EQ(warp.size(), 5u);
  std::set<std::uint32_t> tables;
  for (const ClothTangent& t : warp) {
    tables.insert(t.table);
    const ClothTableKey& key = plan.tables[t.table];
    EXPECT_EQ(key.offset(), t.mirror ? -t.offset : t.offset);
    EXPECT_GE(key.offset(), 0.0f);
    EXPECT_EQ(t.mirror, t.offset < 0.0f);
    EXPECT_EQ(key.multiplicities, (std::vector<std::uint32_t>{2, 1, 2, 1, 2}));
  }
  EXPECT_EQ(tables.size(), 3u);
  ASSERT_EQ(plan.threads[0][1].size(), 1u);
  EXPECT_EQ(plan.threads[0][1][0].table, 3u);
  EXPECT_FALSE(plan.threads[0][1][0].mirror);
}

TEST(ClothTablePlan, PresetsShareTablesAcrossFabrics) {
  const ClothTablePlan plan = plan_cloth_tables(preset_weaves());
  // linen 1; crepe 1 + the weft's {0}; satin 3 (+ {0}); satin back 2 (+ {0}); shot 1 (+ {0});
  // velvet 2 + 2.
  EXPECT_EQ(plan.tables.size(), 13u);
  // Every weft of a single 0 (crepe, both satins, shot) reads one table.
  std::set<std::uint32_t> zero_tables;
  for (const auto& threads : plan.threads)
    if (threads[1].size() == 1) zero_tables.insert(threads[1][0].table);
  EXPECT_EQ(zero_tables.size(), 1u);
  // Velvet's warp {-90, -50} is stored as it is (it sorts before {50, 90}), unmirrored.
  for (const ClothTangent& t : plan.threads[5][0]) EXPECT_FALSE(t.mirror);
  // The same weaves in another order need the same tables.
  std::vector<prt_cloth_weave> reversed = preset_weaves();
  std::reverse(reversed.begin(), reversed.end());
  const ClothTablePlan other = plan_cloth_tables(reversed);
  ASSERT_EQ(other.tables.size(), plan.tables.size());
  for (const ClothTableKey& key : plan.tables)
    EXPECT_NE(std::find(other.tables.begin(), other.tables.end(), key), other.tables.end());
}

TEST(ClothTablePlan, AReversedMultisetReadsTheSameTablesMirrored) {
  const ClothTablePlan plan =
      plan_cloth_tables({weave_of({-90, -50}, {1, 1}), weave_of({50, 90}, {1, 1})});
  ASSERT_EQ(plan.tables.size(), 2u);
  for (int j = 0; j < 2; ++j)
    for (std::size_t k = 0; k < 2; ++k) {
      const ClothTangent& a = plan.threads[0][j][k];
      const ClothTangent& b = plan.threads[1][j][1 - k];  // -tau of the reversed multiset
      EXPECT_EQ(a.offset, -b.offset);
      EXPECT_EQ(a.table, b.table);
      EXPECT_FALSE(a.mirror);
      EXPECT_TRUE(b.mirror);
    }
}

TEST(ClothTablePlan, RejectsAnInvalidWeave) {
  prt_cloth_weave bad = weave_of({0, 0}, {1, 1});  // repeated offset
  EXPECT_THROW(plan_cloth_tables({bad}), Error);
}

}  // namespace
}  // namespace prt::bake
