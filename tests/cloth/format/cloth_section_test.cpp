// SPDX-License-Identifier: MIT
// The CLTH section through the formats checker and the runtime (formats/SPEC.md §7.4), on a small
// section written byte by byte (cloth/clth_test_section.hpp): it loads and the fabric queries
// answer what was written; every rule is rejected, the header, record and size ones at both
// validation levels (the open hook and the checker say the same words), the contents at full
// validation only; truncated blobs and sections fail cleanly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "cloth/clth_test_section.hpp"
#include "support/mesh_blob.hpp"

namespace {

using namespace prt_test;

struct Outcome {
  prt_result result;
  std::string message;
};

Outcome validate_with_message(const Bytes& blob, prt_validation level) {
  Context ctx;
  auto copy = exact_copy(blob);
  char msg[256] = "";
  const prt_result r = prt_asset_validate(ctx.ctx, copy.get(), blob.size(), level, msg, sizeof msg);
  return {r, msg};
}

Bytes small_blob(uint32_t bits = 8, bool zstd = false) {
  const ClthTestSection s = small_clth(bits);
  return clth_blob(s.bytes(), s.fabrics.size(), zstd);
}

// The sizes of the small section, by hand: 64 + 2 x 160 + 3 x 16 + 2 x 16 = 464 bytes of header
// and records; a factorisation of rank R over 9 columns and 18 rows takes 8 R + align4(9 R b/8) +
// align4(18 R b/8) bytes: 8 bits 8 + 12 + 20 = 40, 16 + 20 + 36 = 72, 24 + 28 + 56 = 108 for
// R = 1, 2, 3; 16 bits 8 + 20 + 36 = 64, 16 + 36 + 72 = 124, 24 + 56 + 108 = 188. Tables 0 and 1
// have ranks (2, 1) and (1, 3).
constexpr size_t kRecords = 464;
constexpr size_t kTables8 = 72 + 40 + 40 + 108, kTables16 = 124 + 64 + 64 + 188;

TEST(ClothSection, TheTestSectionHasItsSizeByHand) {
  EXPECT_EQ(small_clth(8).size(), kRecords + kTables8);
  EXPECT_EQ(small_clth(16).size(), kRecords + kTables16);
}

TEST(ClothSection, ValidSectionLoadsAtBothLevelsAndCompressed) {
  for (uint32_t bits : {8u, 16u})
    for (bool zstd : {false, true})
      for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
        const Outcome o = validate_with_message(small_blob(bits, zstd), level);
        EXPECT_EQ(o.result, PRT_OK) << bits << " bits, zstd " << zstd << ": " << o.message;
        Context ctx;
        const LoadedAsset a(ctx.ctx, small_blob(bits, zstd), level);
        ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
        EXPECT_EQ(prt_asset_techniques(a.asset), 1u << PRT_TECHNIQUE_CLOTH);
        prt_section_info info = prt::sized<prt_section_info>();
        ASSERT_EQ(prt_asset_get_section_info(a.asset, 0, &info), PRT_OK);
        EXPECT_EQ(info.domain, PRT_ELEMENT_DOMAIN_MATERIAL);
        EXPECT_EQ(info.technique, PRT_TECHNIQUE_CLOTH);
      }
}

TEST(ClothSection, InfoIsTheHeader) {
  for (uint32_t bits : {8u, 16u}) {
    Context ctx;
    const LoadedAsset a(ctx.ctx, small_blob(bits));
    ASSERT_EQ(a.result, PRT_OK);
    prt_cloth_info info = prt::sized<prt_cloth_info>();
    ASSERT_EQ(prt_cloth_get_info(a.asset, &info), PRT_OK);
    EXPECT_EQ(info.struct_size, sizeof info);
    EXPECT_EQ(info.fabric_count, 2u);
    EXPECT_EQ(info.table_count, 2u);
    EXPECT_EQ(info.xi_size, 3u);
    EXPECT_EQ(info.lambda_levels, 2u);
    EXPECT_EQ(info.lambda_min, 1.0f);
    EXPECT_EQ(info.lambda_max, 8.0f);
    EXPECT_EQ(info.view_theta, 3u);
    EXPECT_EQ(info.view_phi, 3u);
    EXPECT_EQ(info.bits, bits);
    EXPECT_EQ(info.table_bytes, bits == 8 ? kTables8 : kTables16);
  }
}

void expect_thread(const prt_cloth_thread& got, const ClthThread& want, const std::string& what) {
  EXPECT_EQ(got.eta, want.eta) << what;
  for (int c = 0; c < 3; ++c) EXPECT_EQ(got.albedo[c], want.albedo[c]) << what << " " << c;
  EXPECT_EQ(got.kd, want.kd) << what;
  EXPECT_EQ(got.gamma_s, want.gamma_s) << what;
  EXPECT_EQ(got.gamma_v, want.gamma_v) << what;
  EXPECT_EQ(got.coverage, want.coverage) << what;
}

TEST(ClothSection, FabricsAreWhatWasWritten) {
  const ClthTestSection s = small_clth();
  Context ctx;
  const LoadedAsset a(ctx.ctx, small_blob(), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  // Each fabric's table bytes: fabric 0 reads tables 0 and 1 (table 1 through two records),
  // fabric 1 table 0 only (through one record shared by both threads).
  const size_t table_bytes[2] = {kTables8, 72 + 40};
  for (uint32_t f = 0; f < 2; ++f) {
    const char* name = nullptr;
    prt_cloth_params params = prt::sized<prt_cloth_params>();
    prt_cloth_weave weave = prt::sized<prt_cloth_weave>();
    size_t bytes = 0;
    ASSERT_EQ(prt_cloth_get_fabric(a.asset, f, &name, &params, &weave, &bytes), PRT_OK);
    EXPECT_STREQ(name, s.fabrics[f].name.c_str());
    EXPECT_EQ(bytes, table_bytes[f]) << f;
    for (uint32_t j = 0; j < 2; ++j) {
      const ClthThread& t = s.fabrics[f].threads[j];
      expect_thread(params.threads[j], t, "fabric " + std::to_string(f));
      ASSERT_EQ(weave.tangent_count[j], t.count);
      for (uint32_t k = 0; k < t.count; ++k) {
        EXPECT_EQ(weave.offsets[j][k], s.tangents[t.first + k].offset);
        EXPECT_EQ(weave.multiplicity[j][k], s.tangents[t.first + k].multiplicity);
      }
    }
  }
  // Every output may be NULL.
  EXPECT_EQ(prt_cloth_get_fabric(a.asset, 1, nullptr, nullptr, nullptr, nullptr), PRT_OK);
}

TEST(ClothSection, FindFabricByName) {
  Context ctx;
  const LoadedAsset a(ctx.ctx, small_blob());
  ASSERT_EQ(a.result, PRT_OK);
  uint32_t f = 99;
  ASSERT_EQ(prt_cloth_find_fabric(a.asset, "linen_plain", &f), PRT_OK);
  EXPECT_EQ(f, 0u);
  ASSERT_EQ(prt_cloth_find_fabric(a.asset, "abcdefghijklmnopqrstuvwxyz012345", &f), PRT_OK);
  EXPECT_EQ(f, 1u);
  for (const char* missing : {"linen", "linen_plain ", "", "abcdefghijklmnopqrstuvwxyz0123456"})
    EXPECT_EQ(prt_cloth_find_fabric(a.asset, missing, &f), PRT_ERROR_NOT_FOUND) << missing;
}

TEST(ClothSection, QueriesRejectBadArgumentsAndMissingSections) {
  Context ctx;
  const LoadedAsset a(ctx.ctx, small_blob());
  const LoadedAsset mesh(ctx.ctx, mesh_only_blob());
  ASSERT_EQ(a.result, PRT_OK);
  ASSERT_EQ(mesh.result, PRT_OK);
  prt_cloth_info info = prt::sized<prt_cloth_info>();
  prt_cloth_params params = prt::sized<prt_cloth_params>();
  prt_cloth_weave weave = prt::sized<prt_cloth_weave>();
  uint32_t f = 0;
  EXPECT_EQ(prt_cloth_get_info(nullptr, &info), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_get_info(a.asset, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_get_info(mesh.asset, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_cloth_get_fabric(nullptr, 0, nullptr, nullptr, nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_get_fabric(a.asset, 2, nullptr, nullptr, nullptr, nullptr),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_cloth_get_fabric(mesh.asset, 0, nullptr, nullptr, nullptr, nullptr),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_cloth_find_fabric(nullptr, "linen_plain", &f), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_find_fabric(a.asset, nullptr, &f), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_find_fabric(a.asset, "linen_plain", nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_find_fabric(mesh.asset, "linen_plain", &f), PRT_ERROR_NOT_FOUND);
  // A struct_size below 1.0's is refused; a larger one gets the 1.0 fields and keeps its size.
  info.struct_size = offsetof(prt_cloth_info, table_bytes);
  EXPECT_EQ(prt_cloth_get_info(a.asset, &info), PRT_ERROR_INVALID_ARGUMENT);
  params.struct_size = sizeof params - 1;
  EXPECT_EQ(prt_cloth_get_fabric(a.asset, 0, nullptr, &params, nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  weave.struct_size = sizeof weave - 4;
  EXPECT_EQ(prt_cloth_get_fabric(a.asset, 0, nullptr, nullptr, &weave, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  struct {
    prt_cloth_info info;
    uint32_t canary;
  } grown{};
  grown.info.struct_size = sizeof grown;
  grown.canary = 0xC0FFEEu;
  ASSERT_EQ(prt_cloth_get_info(a.asset, &grown.info), PRT_OK);
  EXPECT_EQ(grown.info.struct_size, sizeof grown);
  EXPECT_EQ(grown.info.fabric_count, 2u);
  EXPECT_EQ(grown.canary, 0xC0FFEEu);
}

// ---- rejections ----------------------------------------------------------------------------

using Edit = std::function<void(Bytes& section, const ClthTestSection& s)>;

struct Case {
  const char* name;
  Edit edit;
  prt_result full;  // what full validation says (quick validation: CORRUPT for every load case)
  const char* words;
};

Bytes edited_blob(const ClthTestSection& s, const Edit& edit, uint64_t element_count = 2) {
  Bytes section = s.bytes();
  edit(section, s);
  return clth_blob(section, element_count);
}

const float kNan = std::nanf("");

// Header fields, records and the size: the open hook rejects them at quick validation as the
// checker does at full, in the same words.
std::vector<Case> load_cases() {
  using S = const ClthTestSection&;
  const prt_result C = PRT_ERROR_CORRUPT, N = PRT_ERROR_NON_FINITE;
  return {
      {"no fabric", [](Bytes& b, S) { put_u32(b, 0, 0); }, C, "0 fabrics (must be 1..64)"},
      {"65 fabrics", [](Bytes& b, S) { put_u32(b, 0, 65); }, C, "65 fabrics"},
      {"no tangent", [](Bytes& b, S) { put_u32(b, 4, 0); }, C, "0 tangent records (must be"},
      {"1025 tangents", [](Bytes& b, S) { put_u32(b, 4, 1025); }, C, "1025 tangent records"},
      {"no table", [](Bytes& b, S) { put_u32(b, 8, 0); }, C, "0 table records (must be 1..1024)"},
      {"1025 tables", [](Bytes& b, S) { put_u32(b, 8, 1025); }, C, "1025 table records"},
      {"xi 1", [](Bytes& b, S) { put_u32(b, 12, 1); }, C, "1 lobe nodes per side (must be 2..256)"},
      {"xi 257", [](Bytes& b, S) { put_u32(b, 12, 257); }, C, "257 lobe nodes per side"},
      {"no level", [](Bytes& b, S) { put_u32(b, 16, 0); }, C, "0 sharpness levels (must be 1..64)"},
      {"65 levels", [](Bytes& b, S) { put_u32(b, 16, 65); }, C, "65 sharpness levels"},
      {"lambda_min NaN", [](Bytes& b, S) { put_f32_at(b, 20, kNan); }, N,
       "lambda_min is not finite"},
      {"lambda_min 0", [](Bytes& b, S) { put_f32_at(b, 20, 0.0f); }, C,
       "lambda_min 0 is not positive"},
      {"lambda_min -1", [](Bytes& b, S) { put_f32_at(b, 20, -1.0f); }, C, "lambda_min -1 is not"},
      {"lambda_max inf", [](Bytes& b, S) { put_f32_at(b, 24, INFINITY); }, N,
       "lambda_max is not finite"},
      {"lambda_max below min", [](Bytes& b, S) { put_f32_at(b, 24, 0.5f); }, C,
       "lambda_max 0.5 is below lambda_min 1"},
      {"one level, two sharpnesses", [](Bytes& b, S) { put_u32(b, 16, 1); }, C,
       "lambda_max 8 differs from lambda_min 1 with one level"},
      {"theta 1", [](Bytes& b, S) { put_u32(b, 28, 1); }, C, "1 view theta nodes (must be 2..256)"},
      {"theta 257", [](Bytes& b, S) { put_u32(b, 28, 257); }, C, "257 view theta nodes"},
      {"phi 1", [](Bytes& b, S) { put_u32(b, 32, 1); }, C, "1 view phi nodes (must be 2..256)"},
      {"phi 257", [](Bytes& b, S) { put_u32(b, 32, 257); }, C, "257 view phi nodes"},
      {"12 bits", [](Bytes& b, S) { put_u32(b, 36, 12); }, C, "12 bits (must be 8 or 16)"},
      {"flag", [](Bytes& b, S) { put_u32(b, 40, 4); }, C, "unknown flags 0x4"},
      {"reserved first", [](Bytes& b, S) { put_u32(b, 44, 1); }, C, "reserved header fields"},
      {"reserved last", [](Bytes& b, S) { b[63] = 1; }, C, "reserved header fields"},
      {"one byte more", [](Bytes& b, S) { b.push_back(0); }, C,
       "725 raw bytes, the header and ranks imply 724"},
      {"one byte less", [](Bytes& b, S) { b.pop_back(); }, C,
       "723 raw bytes, the header and ranks imply 724"},
      {"no room for the records", [](Bytes& b, S) { b.resize(463); }, C,
       "463 raw bytes cannot hold the header and records (464 bytes)"},
      {"no room for the header", [](Bytes& b, S) { b.resize(63); }, C,
       "63 bytes cannot hold the 64-byte header"},
      {"empty name", [](Bytes& b, S s) { std::memset(&b[s.fabric_at(0)], 0, 32); }, C,
       "fabric 0 has an empty name"},
      {"byte after the NUL", [](Bytes& b, S s) { b[s.fabric_at(0) + 20] = 'x'; }, C,
       "fabric 0: name is not NUL-padded"},
      {"NaN eta", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(1, 0), kNan); }, N,
       "fabric 1 thread 1: eta is not finite"},
      {"eta 0.5", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 1), 0.5f); }, C,
       "fabric 0 thread 2: eta 0.5 is not in [1, 4]"},
      {"eta 4.5", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 0), 4.5f); }, C,
       "eta 4.5 is not in [1, 4]"},
      {"inf albedo", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 0) + 8, -INFINITY); }, N,
       "fabric 0 thread 1: albedo green is not finite"},
      {"albedo 1.5", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(1, 1) + 12, 1.5f); }, C,
       "fabric 1 thread 2: albedo blue 1.5 is not in [0, 1]"},
      {"albedo -0.1", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 0) + 4, -0.1f); }, C,
       "albedo red -0.1 is not in [0, 1]"},
      {"k_d 2", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 0) + 16, 2.0f); }, C,
       "k_d 2 is not in [0, 1]"},
      {"gamma_s 0", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 0) + 20, 0.0f); }, C,
       "gamma_s 0 is not in (0, pi]"},
      {"gamma_v above pi",
       [](Bytes& b, S s) {
         put_f32_at(b, s.thread_at(0, 0) + 24, std::nextafter(3.14159274f, 4.0f));
       },
       C, "gamma_v 3.14159 is not in (0, pi]"},
      {"NaN coverage", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 1) + 28, kNan); }, N,
       "fabric 0 thread 2: coverage is not finite"},
      {"coverage -0.1", [](Bytes& b, S s) { put_f32_at(b, s.thread_at(0, 1) + 28, -0.1f); }, C,
       "coverage -0.1 is not in [0, 1]"},
      {"no tangent in a thread", [](Bytes& b, S s) { put_u32(b, s.thread_at(0, 1) + 36, 0); }, C,
       "fabric 0 thread 2 has 0 tangent records (must be 1..16)"},
      {"17 tangents in a thread", [](Bytes& b, S s) { put_u32(b, s.thread_at(0, 1) + 36, 17); }, C,
       "has 17 tangent records"},
      {"range past G",
       [](Bytes& b, S s) {
         put_u32(b, s.thread_at(1, 1) + 32, 2);
         put_u32(b, s.thread_at(1, 1) + 36, 2);
       },
       C, "fabric 1 thread 2: tangent records 2..3 are not below 3"},
      {"range start past G", [](Bytes& b, S s) { put_u32(b, s.thread_at(1, 0) + 32, 0xFFFFFFFFu); },
       C, "tangent records 4294967295..4294967295 are not below 3"},
      {"thread reserved", [](Bytes& b, S s) { b[s.thread_at(1, 0) + 63] = 1; }, C,
       "fabric 1 thread 1: reserved fields are not zero"},
      {"coverages above 1",
       [](Bytes& b, S s) { put_f32_at(b, s.thread_at(1, 1) + 28, 0.2501f); }, C,
       "fabric 1: coverages 0.75 and 0.2501 add up to more than 1"},
      {"NaN offset", [](Bytes& b, S s) { put_f32_at(b, s.tangent_at(2), kNan); }, N,
       "tangent 2: offset is not finite"},
      {"offset above pi/2",
       [](Bytes& b, S s) { put_f32_at(b, s.tangent_at(1), std::nextafter(1.57079637f, 2.0f)); }, C,
       "tangent 1: offset 1.5708 is not in [-pi/2, pi/2]"},
      {"offset -1.6", [](Bytes& b, S s) { put_f32_at(b, s.tangent_at(0), -1.6f); }, C,
       "tangent 0: offset -1.6 is not in"},
      {"multiplicity 0", [](Bytes& b, S s) { put_u32(b, s.tangent_at(0) + 4, 0); }, C,
       "tangent 0: multiplicity 0 (must be 1..64)"},
      {"multiplicity 65", [](Bytes& b, S s) { put_u32(b, s.tangent_at(2) + 4, 65); }, C,
       "tangent 2: multiplicity 65"},
      {"table Q", [](Bytes& b, S s) { put_u32(b, s.tangent_at(1) + 8, 2); }, C,
       "tangent 1: table 2 is not below 2 tables"},
      {"mirror 2", [](Bytes& b, S s) { put_u32(b, s.tangent_at(2) + 12, 2); }, C,
       "tangent 2: mirror 2 is not 0 or 1"},
      {"rank 0", [](Bytes& b, S s) { put_u32(b, s.table_at(1), 0); }, C,
       "table 1: rank 0 (must be 1..64)"},
      {"rank 65", [](Bytes& b, S s) { put_u32(b, s.table_at(0), 65); }, C, "table 0: rank 65"},
      {"cone rank 0", [](Bytes& b, S s) { put_u32(b, s.table_at(0) + 4, 0); }, C,
       "table 0: cone rank 0 (must be 1..64)"},
      {"cone rank 65", [](Bytes& b, S s) { put_u32(b, s.table_at(1) + 4, 65); }, C,
       "table 1: cone rank 65"},
      {"table reserved", [](Bytes& b, S s) { b[s.table_at(1) + 15] = 1; }, C,
       "table 1: reserved fields are not zero"},
      {"a rank the size does not hold", [](Bytes& b, S s) { put_u32(b, s.table_at(1) + 4, 4); }, C,
       "724 raw bytes, the header and ranks imply 756"},
  };
}

TEST(ClothSection, LoadRejectsHeaderRecordsAndSizeAtBothLevels) {
  const ClthTestSection s = small_clth();
  for (const Case& c : load_cases()) {
    const Bytes blob = edited_blob(s, c.edit);
    for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
      const Outcome o = validate_with_message(blob, level);
      const prt_result expected = level == PRT_VALIDATE_FULL ? c.full : PRT_ERROR_CORRUPT;
      EXPECT_EQ(o.result, expected) << c.name << " at level " << level << ": " << o.message;
      EXPECT_NE(o.message.find(c.words), std::string::npos) << c.name << ": " << o.message;
      EXPECT_NE(o.message.find("'CLTH': "), std::string::npos) << c.name << ": " << o.message;
      Context ctx;
      EXPECT_EQ(load(ctx.ctx, blob, level), expected) << c.name;
    }
  }
}

// The element count is the fabric count (the section counts the material domain).
TEST(ClothSection, ElementCountIsTheFabricCount) {
  const ClthTestSection s = small_clth();
  for (uint64_t count : {1u, 3u}) {
    const Bytes blob = clth_blob(s.bytes(), count);
    for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
      const Outcome o = validate_with_message(blob, level);
      EXPECT_EQ(o.result, PRT_ERROR_CORRUPT) << count;
      EXPECT_NE(o.message.find("header says 2 fabrics, element count " + std::to_string(count)),
                std::string::npos)
          << o.message;
    }
  }
}

// The edges of each range are inside it.
TEST(ClothSection, RangeEdgesAreAccepted) {
  const ClthTestSection s = small_clth();
  const Edit edges[] = {
      [](Bytes& b, const ClthTestSection& s) { put_f32_at(b, s.tangent_at(1), 1.57079637f); },
      [](Bytes& b, const ClthTestSection& s) { put_f32_at(b, s.tangent_at(2), -1.57079637f); },
      [](Bytes& b, const ClthTestSection& s) { put_f32_at(b, s.thread_at(0, 0) + 28, 0.0f); },
      [](Bytes& b, const ClthTestSection&) { put_f32_at(b, 24, 1.0f); },  // lambda_max = min
      [](Bytes& b, const ClthTestSection& s) { put_u32(b, s.tangent_at(0) + 4, 64); },
      [](Bytes& b, const ClthTestSection& s) { put_f32_at(b, s.thread_at(1, 0) + 20, 1e-30f); },
  };
  for (size_t i = 0; i < sizeof edges / sizeof edges[0]; ++i)
    for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
      const Outcome o = validate_with_message(edited_blob(s, edges[i]), level);
      EXPECT_EQ(o.result, PRT_OK) << "edge " << i << ": " << o.message;
    }
}

// The contents: rejected by full validation only; a quick load still answers every query.
std::vector<Case> content_cases(uint32_t bits) {
  using S = const ClthTestSection&;
  const prt_result C = PRT_ERROR_CORRUPT, N = PRT_ERROR_NON_FINITE;
  std::vector<Case> cases = {
      {"name not UTF-8", [](Bytes& b, S s) { b[s.fabric_at(0) + 3] = 0xFF; }, C,
       "fabric 0: name is not UTF-8"},
      {"same names",
       [](Bytes& b, S s) {
         std::memset(&b[s.fabric_at(1)], 0, 32);
         std::memcpy(&b[s.fabric_at(1)], "linen_plain", 11);
       },
       C, "fabrics 0 and 1 have the same name"},
      {"offset twice", [](Bytes& b, S s) { put_f32_at(b, s.tangent_at(2), 0.3f); }, C,
       "fabric 0 thread 2: offset 0.3 appears twice"},
      {"NaN u_scale", [](Bytes& b, S s) { put_f32_at(b, s.factor_at(1, 1) + 8, kNan); }, N,
       "table 1 T_c: u_scale[2] is not finite"},
      {"inf v_scale", [](Bytes& b, S s) { put_f32_at(b, s.factor_at(0, 0) + 12, INFINITY); }, N,
       "table 0 T: v_scale[1] is not finite"},
      {"negative scale", [](Bytes& b, S s) { put_f32_at(b, s.factor_at(1, 0) + 4, -0.5f); }, C,
       "table 1 T: v_scale[0] is negative"},
      {"V padding", [](Bytes& b, S s) { b[s.u_values_at(1, 1) - 1] = 1; }, C,
       "table 1 T_c: padding after the V values is not zero"},
  };
  if (bits == 8) {
    cases.push_back({"U padding", [](Bytes& b, S s) { b[s.factor_at(1, 0) - 1] = 1; }, C,
                     "table 0 T_c: padding after the U values is not zero"});
    cases.push_back({"V value -128", [](Bytes& b, S s) { b[s.v_values_at(0, 1) + 5] = 0x80; }, C,
                     "table 0 T_c: V value 5 is -128"});
    cases.push_back({"U value -128", [](Bytes& b, S s) { b[s.u_values_at(1, 0) + 7] = 0x80; }, C,
                     "table 1 T: U value 7 is -128"});
  } else {
    cases.push_back({"U value -32768",
                     [](Bytes& b, S s) { put_u16(b, s.u_values_at(0, 0) + 2 * 15, 0x8000); }, C,
                     "table 0 T: U value 15 is -32768"});
  }
  return cases;
}

TEST(ClothSection, FullValidationRejectsTheContents) {
  for (uint32_t bits : {8u, 16u}) {
    const ClthTestSection s = small_clth(bits);
    for (const Case& c : content_cases(bits)) {
      const Bytes blob = edited_blob(s, c.edit);
      const Outcome full = validate_with_message(blob, PRT_VALIDATE_FULL);
      EXPECT_EQ(full.result, c.full) << c.name << ": " << full.message;
      EXPECT_NE(full.message.find(c.words), std::string::npos) << c.name << ": " << full.message;
      Context ctx;
      const LoadedAsset quick(ctx.ctx, blob, PRT_VALIDATE_QUICK);
      ASSERT_EQ(quick.result, PRT_OK) << c.name;
      prt_cloth_info info = prt::sized<prt_cloth_info>();
      prt_cloth_params params = prt::sized<prt_cloth_params>();
      prt_cloth_weave weave = prt::sized<prt_cloth_weave>();
      const char* name = nullptr;
      size_t bytes = 0;
      uint32_t f = 0;
      EXPECT_EQ(prt_cloth_get_info(quick.asset, &info), PRT_OK);
      for (uint32_t i = 0; i < 2; ++i)
        EXPECT_EQ(prt_cloth_get_fabric(quick.asset, i, &name, &params, &weave, &bytes), PRT_OK);
      EXPECT_EQ(prt_cloth_find_fabric(quick.asset, name, &f), PRT_OK) << c.name;
    }
  }
}

// ---- truncation ----------------------------------------------------------------------------

TEST(ClothSection, EveryPrefixOfTheBlobIsTruncated) {
  const Bytes blob = small_blob();
  Context ctx;
  for (size_t n = 0; n < blob.size(); ++n) {
    const Bytes prefix(blob.begin(), blob.begin() + std::ptrdiff_t(n));
    ASSERT_EQ(validate(ctx.ctx, prefix, PRT_VALIDATE_QUICK), PRT_ERROR_TRUNCATED) << n;
    ASSERT_EQ(validate(ctx.ctx, prefix, PRT_VALIDATE_FULL), PRT_ERROR_TRUNCATED) << n;
    ASSERT_EQ(load(ctx.ctx, prefix, PRT_VALIDATE_QUICK), PRT_ERROR_TRUNCATED) << n;
  }
}

// Every prefix of the section, in a container that is otherwise valid: CORRUPT at both levels.
TEST(ClothSection, EveryPrefixOfTheSectionIsCorrupt) {
  for (uint32_t bits : {8u, 16u}) {
    const Bytes section = small_clth(bits).bytes();
    Context ctx;
    for (size_t n = 0; n < section.size(); ++n) {
      const Bytes prefix(section.begin(), section.begin() + std::ptrdiff_t(n));
      const Bytes blob = clth_blob(prefix, std::min<uint64_t>(2, n));
      ASSERT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT) << n;
      ASSERT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT) << n;
      ASSERT_EQ(load(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT) << n;
    }
  }
}

// ---- VTAN: per-vertex tangents, checked like VNRM ------------------------------------------

Bytes tangent_blob(const std::vector<float>& tangents, uint64_t tangent_count) {
  prt::format::BlobWriter w;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t tri[3] = {0, 1, 2};
  prt::format::SectionOptions required, optional;
  required.required = true;
  w.add_section(PRT_BLOB_TAG_VPOS, positions, sizeof positions, 3, required);
  w.add_section(PRT_BLOB_TAG_TRIS, tri, sizeof tri, 1, required);
  // Under a stand-in tag, so that the writer's own size check lets a wrong count through.
  w.add_section(PRT_BLOB_TAG('t', 'm', 'p', '0'), tangents.data(), tangents.size() * 4,
                tangent_count, optional);
  Bytes b = w.finish();
  put_u32(b, entry(2) + PRT_BLOB_SEC_OFF_TAG, PRT_BLOB_TAG('V', 'T', 'A', 'N'));
  fix_header_checksum(b);
  return b;
}

TEST(ClothVtan, TangentsLoadAndAreCheckedLikeNormals) {
  const std::vector<float> tangents = {1, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0};
  Context ctx;
  for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    const LoadedAsset a(ctx.ctx, tangent_blob(tangents, 3), level);
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    const void* data = nullptr;
    size_t size = 0;
    ASSERT_EQ(prt_asset_section_data(a.asset, PRT_SECTION_VTAN, &data, &size), PRT_OK);
    ASSERT_EQ(size, tangents.size() * 4);
    EXPECT_EQ(std::memcmp(data, tangents.data(), size), 0);
    prt_section_info info = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(a.asset, 2, &info), PRT_OK);
    EXPECT_EQ(info.domain, PRT_ELEMENT_DOMAIN_VERTEX);
    EXPECT_EQ(info.technique, PRT_TECHNIQUE_NONE);
  }
  // Non-finite floats: full validation only, naming the float and the element.
  for (float bad : {kNan, INFINITY, -INFINITY}) {
    std::vector<float> t = tangents;
    t[7] = bad;
    const Bytes blob = tangent_blob(t, 3);
    EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_OK);
    const Outcome o = validate_with_message(blob, PRT_VALIDATE_FULL);
    EXPECT_EQ(o.result, PRT_ERROR_NON_FINITE);
    EXPECT_NE(o.message.find("'VTAN': float 7 (element 2) is not finite"), std::string::npos)
        << o.message;
  }
  // One tangent per vertex, 12 bytes each (quick validation).
  const Outcome fewer =
      validate_with_message(tangent_blob({1, 0, 0, 0, 1, 0}, 2), PRT_VALIDATE_QUICK);
  EXPECT_EQ(fewer.result, PRT_ERROR_CORRUPT);
  EXPECT_EQ(fewer.message, "'VTAN' has 2 tangents for 3 vertices");
  const Outcome ragged = validate_with_message(tangent_blob(tangents, 2), PRT_VALIDATE_QUICK);
  EXPECT_EQ(ragged.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(ragged.message.find("2 elements of 12 bytes do not make 36 raw bytes"),
            std::string::npos)
      << ragged.message;
}

}  // namespace
