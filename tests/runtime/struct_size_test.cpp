// SPDX-License-Identifier: MIT
// struct_size, the first member of every struct that may grow (prt_types.h): a size below the
// struct's 1.0 size is rejected, the runtime writes an output struct only as far as its
// struct_size reaches (and leaves struct_size as the caller set it), and reads an input struct
// only that far. (prt_env_image: tests/runtime/env_test.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>

#include "sh/sh_blob_test_util.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace {

using namespace prt_test;

constexpr unsigned char kUntouched = 0xA5;

// Calls `query` on an output struct T three ways: struct_size 0 and 1.0's size minus one are
// rejected without a write; a struct from newer headers (larger struct_size) is filled as far as
// T reaches, and nothing after it is written.
template <typename T>
void expect_output_struct_rules(const char* what, size_t size_1_0,
                                const std::function<prt_result(T*)>& query) {
  struct Newer {
    T known;
    unsigned char future[32];
  } newer;
  for (size_t size : {size_t(0), size_1_0 - 1}) {
    std::memset(&newer, kUntouched, sizeof newer);
    newer.known.struct_size = size;
    EXPECT_EQ(query(&newer.known), PRT_ERROR_INVALID_ARGUMENT) << what << " struct_size " << size;
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(&newer);
    size_t written = 0;
    for (size_t i = sizeof(size_t); i < sizeof newer; ++i) written += bytes[i] != kUntouched;
    EXPECT_EQ(written, 0u) << what << ": a rejected call wrote";
  }
  std::memset(&newer, kUntouched, sizeof newer);
  newer.known.struct_size = sizeof newer;
  ASSERT_EQ(query(&newer.known), PRT_OK) << what;
  EXPECT_EQ(newer.known.struct_size, sizeof newer) << what << ": struct_size is the caller's";
  for (unsigned char b : newer.future) ASSERT_EQ(b, kUntouched) << what << ": wrote past T";
  // The same call with struct_size = sizeof(T) writes the same fields.
  T exact = prt::sized<T>();
  ASSERT_EQ(query(&exact), PRT_OK) << what;
  newer.known.struct_size = sizeof(T);
  EXPECT_EQ(std::memcmp(&newer.known, &exact, sizeof(T)), 0) << what;
}

// Every 1.0 struct ends with a member whose end is the 1.0 size; the test restates them here.
TEST(StructSize, OutputStructsFollowTheRule) {
  Context ctx;
  const Transfer sh = random_transfer(2, 5, 3, 8, 1);
  LoadedAsset sh_asset(ctx.ctx, make_blob(encode(sh), sh.vertices));
  ASSERT_EQ(sh_asset.result, PRT_OK);
  const WvltTransfer wavelet = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 5, 10, 2);
  LoadedAsset wavelet_asset(ctx.ctx, wvlt_make_blob(wvlt_encode(wavelet), wavelet.vertices));
  ASSERT_EQ(wavelet_asset.result, PRT_OK);

  expect_output_struct_rules<prt_backend_info>(
      "prt_backend_info", offsetof(prt_backend_info, note) + sizeof(const char*),
      [&](prt_backend_info* out) { return prt_backend_get_info(ctx.ctx, PRT_BACKEND_CPU, out); });
  expect_output_struct_rules<prt_asset_info>(
      "prt_asset_info", offsetof(prt_asset_info, borrowed) + sizeof(uint32_t),
      [&](prt_asset_info* out) { return prt_asset_get_info(sh_asset.asset, out); });
  expect_output_struct_rules<prt_section_info>(
      "prt_section_info", offsetof(prt_section_info, technique) + sizeof(prt_technique),
      [&](prt_section_info* out) { return prt_asset_get_section_info(sh_asset.asset, 2, out); });
  expect_output_struct_rules<prt_technique_info>(
      "prt_technique_info", offsetof(prt_technique_info, domain) + sizeof(prt_element_domain),
      [](prt_technique_info* out) { return prt_technique_get_info(PRT_TECHNIQUE_WAVELET, out); });
  expect_output_struct_rules<prt_sh_info>(
      "prt_sh_info", offsetof(prt_sh_info, bounces) + sizeof(uint32_t),
      [&](prt_sh_info* out) { return prt_sh_get_info(sh_asset.asset, out); });
  expect_output_struct_rules<prt_wavelet_info>(
      "prt_wavelet_info", offsetof(prt_wavelet_info, pair_count) + sizeof(uint32_t),
      [&](prt_wavelet_info* out) { return prt_wavelet_get_info(wavelet_asset.asset, out); });
}

TEST(StructSize, ContextDescFollowsTheRule) {
  prt_context* ctx = nullptr;
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.struct_size = 0;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_INVALID_ARGUMENT);
  desc.struct_size = offsetof(prt_context_desc, flags) + sizeof(uint32_t) - 1;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(ctx, nullptr);
  // A description from newer headers: its fields past this runtime's are not read.
  struct Newer {
    prt_context_desc known;
    uint32_t future_flags;
  } newer;
  std::memset(&newer, 0, sizeof newer);
  newer.known.struct_size = sizeof newer;
  newer.known.backend_limit = PRT_BACKEND_CPU;
  newer.future_flags = 0xFFFFFFFFu;
  ASSERT_EQ(prt_context_create(&newer.known, &ctx), PRT_OK);
  EXPECT_EQ(prt_context_backend(ctx), PRT_BACKEND_CPU) << "the known fields are read";
  prt_context_destroy(ctx);
  // NULL still means the defaults.
  ASSERT_EQ(prt_context_create(nullptr, &ctx), PRT_OK);
  prt_context_destroy(ctx);
}

}  // namespace
