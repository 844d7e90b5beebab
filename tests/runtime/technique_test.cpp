// SPDX-License-Identifier: MIT
// The technique registry of the C API (prt_technique.h): what each technique says about itself,
// checked against names, tags and domains typed here from formats/SPEC.md; which techniques a blob
// holds; the domain and technique of each section; and allocation failures while a load decodes
// the technique sections' headers.
#include <gtest/gtest.h>

#include <prt/format/blob_writer.hpp>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/counting_allocator.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace {

using namespace prt_test;

TEST(Technique, EachTechniqueDescribesItself) {
  struct Expected {
    prt_technique technique;
    const char* name;
    uint32_t tag;
    prt_element_domain domain;
  };
  const Expected expected[] = {
      {PRT_TECHNIQUE_SH, "sh", PRT_BLOB_TAG('S', 'H', 'T', 'R'), PRT_ELEMENT_DOMAIN_VERTEX},
      {PRT_TECHNIQUE_WAVELET, "wavelet", PRT_BLOB_TAG('W', 'V', 'L', 'T'),
       PRT_ELEMENT_DOMAIN_VERTEX},
      {PRT_TECHNIQUE_POSE, "pose", PRT_BLOB_TAG('P', 'S', 'T', 'R'), PRT_ELEMENT_DOMAIN_VERTEX},
      {PRT_TECHNIQUE_CLOTH, "cloth", PRT_BLOB_TAG('C', 'L', 'T', 'H'), PRT_ELEMENT_DOMAIN_MATERIAL},
      {PRT_TECHNIQUE_SHADOWFIELD, "shadowfield", PRT_BLOB_TAG('S', 'F', 'L', 'D'),
       PRT_ELEMENT_DOMAIN_OBJECT},
  };
  for (const Expected& e : expected) {
    prt_technique_info info = prt::sized<prt_technique_info>();
    ASSERT_EQ(prt_technique_get_info(e.technique, &info), PRT_OK) << e.name;
    EXPECT_EQ(info.technique, e.technique);
    EXPECT_STREQ(info.name, e.name);
    EXPECT_EQ(info.section_tag, e.tag) << e.name;
    EXPECT_EQ(info.domain, e.domain) << e.name;
  }
  EXPECT_EQ(PRT_SECTION_SHTR, expected[0].tag);
  EXPECT_EQ(PRT_SECTION_WVLT, expected[1].tag);
  EXPECT_EQ(PRT_SECTION_PSTR, expected[2].tag);
  EXPECT_EQ(PRT_SECTION_CLTH, expected[3].tag);
  EXPECT_EQ(PRT_SECTION_SFLD, expected[4].tag);
  // Every other value is not a technique of this runtime.
  int known = 0;
  for (uint32_t t = 0; t < 32; ++t) {
    prt_technique_info info = prt::sized<prt_technique_info>();
    const prt_result r = prt_technique_get_info(static_cast<prt_technique>(t), &info);
    EXPECT_TRUE(r == PRT_OK || r == PRT_ERROR_NOT_FOUND) << t;
    known += r == PRT_OK;
  }
  EXPECT_EQ(known, 5);
  prt_technique_info info = prt::sized<prt_technique_info>();
  EXPECT_EQ(prt_technique_get_info(PRT_TECHNIQUE_NONE, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_technique_get_info(PRT_TECHNIQUE_SH, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  info.struct_size = 0;
  EXPECT_EQ(prt_technique_get_info(PRT_TECHNIQUE_SH, &info), PRT_ERROR_INVALID_ARGUMENT);
}

// VPOS, TRIS, SHTR and WVLT in one blob (a blob may hold several techniques).
Bytes both_techniques_blob(uint32_t vertices) {
  const Transfer sh = random_transfer(2, vertices, 3, 8, 5);
  const WvltTransfer wavelet = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, vertices, 20, 6);
  const Bytes shtr = encode(sh), wvlt = wvlt_encode(wavelet);
  std::vector<float> positions(3 * size_t(vertices), 0.5f);
  const uint32_t tri[3] = {0, 1, 2};
  prt::format::BlobWriter w;
  prt::format::SectionOptions required;
  required.required = true;
  w.add_section(kVPOS, positions.data(), positions.size() * 4, vertices, required);
  w.add_section(kTRIS, tri, sizeof tri, 1, required);
  w.add_section(kSHTR, shtr.data(), shtr.size(), vertices, required);
  w.add_section(kWvltWVLT, wvlt.data(), wvlt.size(), vertices, required);
  return w.finish();
}

TEST(Technique, AssetTechniquesAreTheSectionsItHolds) {
  Context ctx;
  EXPECT_EQ(prt_asset_techniques(nullptr), 0u);
  {
    LoadedAsset mesh_only(ctx.ctx, read_file(golden_path()));
    ASSERT_EQ(mesh_only.result, PRT_OK);
    EXPECT_EQ(prt_asset_techniques(mesh_only.asset), 0u);
  }
  {
    const Transfer t = random_transfer(3, 10, 1, 16, 1);
    LoadedAsset sh(ctx.ctx, make_blob(encode(t), t.vertices));
    ASSERT_EQ(sh.result, PRT_OK);
    EXPECT_EQ(prt_asset_techniques(sh.asset), 1u << PRT_TECHNIQUE_SH);
  }
  {
    const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 16, 10, 30, 2);
    LoadedAsset wavelet(ctx.ctx, wvlt_make_blob(wvlt_encode(t), t.vertices, true));
    ASSERT_EQ(wavelet.result, PRT_OK);
    EXPECT_EQ(prt_asset_techniques(wavelet.asset), 1u << PRT_TECHNIQUE_WAVELET);
  }
  for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    LoadedAsset both(ctx.ctx, both_techniques_blob(12), level);
    ASSERT_EQ(both.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(prt_asset_techniques(both.asset),
              (1u << PRT_TECHNIQUE_SH) | (1u << PRT_TECHNIQUE_WAVELET));
    prt_sh_info sh = prt::sized<prt_sh_info>();
    prt_wavelet_info wavelet = prt::sized<prt_wavelet_info>();
    EXPECT_EQ(prt_sh_get_info(both.asset, &sh), PRT_OK);
    EXPECT_EQ(prt_wavelet_get_info(both.asset, &wavelet), PRT_OK);
    EXPECT_EQ(sh.vertex_count, 12u);
    EXPECT_EQ(wavelet.vertex_count, 12u);
  }
}

// A technique section of a layout version this runtime does not know, marked optional, passes
// validation unchecked; the technique then counts as absent instead of reading it.
TEST(Technique, SectionOfAnUnknownLayoutVersionIsAbsent) {
  const uint32_t vertices = 6;
  const Transfer sh = random_transfer(2, vertices, 3, 8, 7);
  const Bytes shtr = encode(sh);
  std::vector<float> positions(3 * size_t(vertices), 0.25f);
  prt::format::BlobWriter w;
  prt::format::SectionOptions required, unknown;
  required.required = true;
  unknown.layout_version = 2;
  w.add_section(kVPOS, positions.data(), positions.size() * 4, vertices, required);
  w.add_section(kSHTR, shtr.data(), shtr.size(), vertices, unknown);
  Context ctx;
  for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    LoadedAsset asset(ctx.ctx, w.finish(), level);
    ASSERT_EQ(asset.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(prt_asset_techniques(asset.asset), 0u);
    prt_sh_info info = prt::sized<prt_sh_info>();
    EXPECT_EQ(prt_sh_get_info(asset.asset, &info), PRT_ERROR_NOT_FOUND);
    float light[12] = {1.0f}, out[3];
    EXPECT_EQ(prt_sh_shade(asset.asset, PRT_BACKEND_CPU, light, 0, 1, out), PRT_ERROR_NOT_FOUND);
    prt_section_info section = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(asset.asset, 1, &section), PRT_OK);
    EXPECT_EQ(section.technique, PRT_TECHNIQUE_NONE);
  }
}

TEST(Technique, SectionInfoSaysDomainAndTechnique) {
  Context ctx;
  LoadedAsset both(ctx.ctx, both_techniques_blob(4));
  ASSERT_EQ(both.result, PRT_OK);
  struct Expected {
    uint32_t tag;
    prt_element_domain domain;
    prt_technique technique;
  };
  const Expected expected[] = {
      {PRT_BLOB_TAG('V', 'P', 'O', 'S'), PRT_ELEMENT_DOMAIN_VERTEX, PRT_TECHNIQUE_NONE},
      {PRT_BLOB_TAG('T', 'R', 'I', 'S'), PRT_ELEMENT_DOMAIN_TRIANGLE, PRT_TECHNIQUE_NONE},
      {PRT_BLOB_TAG('S', 'H', 'T', 'R'), PRT_ELEMENT_DOMAIN_VERTEX, PRT_TECHNIQUE_SH},
      {PRT_BLOB_TAG('W', 'V', 'L', 'T'), PRT_ELEMENT_DOMAIN_VERTEX, PRT_TECHNIQUE_WAVELET},
  };
  ASSERT_EQ(prt_asset_section_count(both.asset), 4u);
  for (uint32_t i = 0; i < 4; ++i) {
    prt_section_info info = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(both.asset, i, &info), PRT_OK);
    EXPECT_EQ(info.tag, expected[i].tag) << i;
    EXPECT_EQ(info.domain, expected[i].domain) << i;
    EXPECT_EQ(info.technique, expected[i].technique) << i;
  }
  // The INFO text of the golden blob: element = byte.
  LoadedAsset golden(ctx.ctx, read_file(golden_path()));
  ASSERT_EQ(golden.result, PRT_OK);
  uint32_t index = 0;
  ASSERT_EQ(prt_asset_find_section(golden.asset, PRT_SECTION_INFO, &index), PRT_OK);
  prt_section_info info = prt::sized<prt_section_info>();
  ASSERT_EQ(prt_asset_get_section_info(golden.asset, index, &info), PRT_OK);
  EXPECT_EQ(info.domain, PRT_ELEMENT_DOMAIN_NONE);
  EXPECT_EQ(info.technique, PRT_TECHNIQUE_NONE);
}

// Every allocation of a load or a validation of a blob with both techniques failing in turn
// (the technique views included) gives OUT_OF_MEMORY and leaks nothing.
TEST(Technique, EveryAllocationFailureWhileOpeningViewsIsReported) {
  const Bytes blob = both_techniques_blob(9);
  for (const prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    expect_every_allocation_failure_reported(
        [&](prt_context* c) {
          prt_asset* asset = nullptr;
          const prt_result r = prt_asset_load_memory(c, blob.data(), blob.size(), level, &asset);
          if (r == PRT_OK && asset) {
            EXPECT_EQ(prt_asset_techniques(asset),
                      (1u << PRT_TECHNIQUE_SH) | (1u << PRT_TECHNIQUE_WAVELET));
          }
          prt_asset_destroy(asset);
          return r;
        },
        level == PRT_VALIDATE_QUICK ? "load at quick validation" : "load at full validation");
  }
  expect_every_allocation_failure_reported(
      [&](prt_context* c) {
        return prt_asset_validate(c, blob.data(), blob.size(), PRT_VALIDATE_QUICK, nullptr, 0);
      },
      "quick validation");
}

}  // namespace
