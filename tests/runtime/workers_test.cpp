// Runtime-owned worker threads (prt_workers.h): the split shade calls give bitwise the one-range
// calls' results for every thread and vertex count, and the pool's errors and lifetime.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/blob_test_util.hpp"
#include "support/mesh_blob.hpp"

#include <prt/prt.h>

namespace {

using namespace prt_test;

const uint32_t kThreadCounts[] = {1u, 2u, 3u, 7u};

struct Pool {
  prt_workers* workers = nullptr;
  Pool(prt_context* ctx, uint32_t threads) {
    prt_workers_desc desc{};
    desc.struct_size = sizeof desc;
    desc.thread_count = threads;
    EXPECT_EQ(prt_workers_create(ctx, &desc, &workers), PRT_OK) << prt_context_last_message(ctx);
  }
  ~Pool() { prt_workers_destroy(workers); }
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;
};

std::vector<float> random_floats(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-2.0f, 2.0f);
  std::vector<float> v(n);
  for (float& x : v) x = unit(rng);
  return v;
}

bool bitwise_equal(const std::vector<float>& a, const std::vector<float>& b) {
  // memcmp may not be given the null data() of an empty vector.
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(Workers, ShMatchesTheOneRangeCallBitwise) {
  Context c;
  const uint32_t vertices = 2000;
  const Transfer t = random_transfer(3, vertices, 3, 8, 7);
  LoadedAsset a(c.ctx, make_blob(encode(t), vertices));
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(c.ctx);
  const std::vector<float> light = random_floats(size_t(t.order) * t.order * 3, 11);
  for (prt_backend backend : {PRT_BACKEND_AUTO, PRT_BACKEND_CPU})
    for (uint32_t threads : kThreadCounts) {
      Pool pool(c.ctx, threads);
      ASSERT_NE(pool.workers, nullptr);
      EXPECT_EQ(prt_workers_thread_count(pool.workers), threads);
      // Ranges of 0, 1, fewer than the threads and many vertices, from 0 and from inside.
      for (uint32_t first : {0u, 5u})
        for (uint32_t count : {0u, 1u, 2u, 6u, vertices - first}) {
          SCOPED_TRACE(testing::Message() << "threads " << threads << ", first " << first
                                          << ", count " << count << ", backend " << backend);
          std::vector<float> one(size_t(count) * 3, -1.0f), split(size_t(count) * 3, -2.0f);
          ASSERT_EQ(prt_sh_shade(a.asset, backend, light.data(), first, count, one.data()), PRT_OK);
          ASSERT_EQ(prt_sh_shade_workers(pool.workers, a.asset, backend, light.data(), first, count,
                                         split.data()),
                    PRT_OK);
          EXPECT_TRUE(bitwise_equal(one, split));
        }
    }
}

TEST(Workers, WaveletMatchesTheOneRangeCallBitwise) {
  Context c;
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_file(c.ctx, PRT_GOLDEN_DIR "/1.0/wavelet_quad.prtk", PRT_VALIDATE_FULL,
                                &asset),
            PRT_OK)
      << prt_context_last_message(c.ctx);
  prt_wavelet_info info{};
  info.struct_size = sizeof info;
  ASSERT_EQ(prt_wavelet_get_info(asset, &info), PRT_OK);
  std::vector<float> prepared = random_floats(size_t(info.coefficient_count) * 4, 3);
  ASSERT_EQ(prt_wavelet_prepare_light(asset, prepared.data(), prepared.data(), nullptr), PRT_OK);
  const uint32_t vertices = info.vertex_count;
  for (uint32_t threads : kThreadCounts) {
    Pool pool(c.ctx, threads);
    ASSERT_NE(pool.workers, nullptr);
    for (uint32_t count : {0u, 1u, 2u, vertices}) {
      SCOPED_TRACE(testing::Message() << "threads " << threads << ", count " << count);
      std::vector<float> one(size_t(count) * 3, -1.0f), split(size_t(count) * 3, -2.0f);
      ASSERT_EQ(prt_wavelet_shade(asset, PRT_BACKEND_AUTO, prepared.data(), nullptr, 0, count,
                                  one.data()),
                PRT_OK);
      ASSERT_EQ(prt_wavelet_shade_workers(pool.workers, asset, PRT_BACKEND_AUTO, prepared.data(),
                                          nullptr, 0, count, split.data()),
                PRT_OK);
      EXPECT_TRUE(bitwise_equal(one, split));
    }
  }
  prt_asset_destroy(asset);
}

TEST(Workers, ReportsTheOneRangeCallsErrors) {
  Context c;
  const Transfer t = random_transfer(2, 10, 3, 8, 5);
  LoadedAsset a(c.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = random_floats(4 * 3, 1);
  std::vector<float> out(30);
  Pool pool(c.ctx, 3);
  ASSERT_NE(pool.workers, nullptr);
  EXPECT_EQ(
      prt_sh_shade_workers(nullptr, a.asset, PRT_BACKEND_CPU, light.data(), 0, 10, out.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_sh_shade_workers(pool.workers, nullptr, PRT_BACKEND_CPU, light.data(), 0, 10, out.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, nullptr, 0, 10, out.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, light.data(), 0, 10, nullptr),
      PRT_ERROR_INVALID_ARGUMENT);
  // Past the end: only the last chunk fails, and its result is returned.
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 1, 10, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, light.data(), 1, 10, out.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, light.data(), 0xFFFFFFFFu,
                                 2, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_GL, light.data(), 0, 10, out.data()),
      PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(prt_wavelet_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, light.data(), nullptr,
                                      0, 10, out.data()),
            PRT_ERROR_NOT_FOUND);
}

TEST(Workers, CreateChecksItsArguments) {
  Context c;
  prt_workers* w = reinterpret_cast<prt_workers*>(&c);
  prt_workers_desc desc{};
  desc.struct_size = sizeof desc;
  EXPECT_EQ(prt_workers_create(nullptr, &desc, &w), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(w, nullptr);
  EXPECT_EQ(prt_workers_create(c.ctx, &desc, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_context_last_result(c.ctx), PRT_ERROR_INVALID_ARGUMENT);
  prt_context_clear_error(c.ctx);
  desc.struct_size = sizeof(size_t);
  EXPECT_EQ(prt_workers_create(c.ctx, &desc, &w), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(w, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(c.ctx)).find("struct_size"), std::string::npos);
  EXPECT_EQ(prt_workers_thread_count(nullptr), 0u);
  prt_workers_destroy(nullptr);
}

TEST(Workers, DefaultsToAtLeastOneThreadAndSurvivesManyCreations) {
  Context c;
  prt_workers* w = nullptr;
  ASSERT_EQ(prt_workers_create(c.ctx, nullptr, &w), PRT_OK);
  EXPECT_GE(prt_workers_thread_count(w), 1u);
  prt_workers_destroy(w);
  const Transfer t = random_transfer(2, 50, 1, 8, 9);
  LoadedAsset a(c.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = random_floats(4 * 3, 2);
  std::vector<float> out(150);
  for (int i = 0; i < 100; ++i) {
    Pool pool(c.ctx, 1u + uint32_t(i % 7));
    ASSERT_NE(pool.workers, nullptr);
    // Every other pool is destroyed without having run a job.
    if (i % 2) {
      EXPECT_EQ(prt_sh_shade_workers(pool.workers, a.asset, PRT_BACKEND_CPU, light.data(), 0, 50,
                                     out.data()),
                PRT_OK);
    }
  }
}

}  // namespace
