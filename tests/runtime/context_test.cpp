// SPDX-License-Identifier: MIT
// Contexts: version, result strings, caller allocator, message callback, last error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <prt/prt.hpp>

#include "support/counting_allocator.hpp"

namespace {

TEST(Version, LibraryMatchesHeaders) {
  EXPECT_EQ(prt_get_version(), uint32_t(PRT_VERSION));
  EXPECT_STREQ(prt_get_version_string(), PRT_VERSION_STRING);
  EXPECT_EQ(PRT_VERSION, PRT_VERSION_MAJOR * 10000 + PRT_VERSION_MINOR * 100 + PRT_VERSION_PATCH);
  EXPECT_EQ(std::to_string(PRT_VERSION_MAJOR) + "." + std::to_string(PRT_VERSION_MINOR) + "." +
                std::to_string(PRT_VERSION_PATCH),
            PRT_VERSION_STRING);
}

TEST(ResultString, EveryCodeHasItsOwnName) {
  const prt_result codes[] = {PRT_OK,
                              PRT_ERROR_INVALID_ARGUMENT,
                              PRT_ERROR_INVALID_OPERATION,
                              PRT_ERROR_BUFFER_TOO_SMALL,
                              PRT_ERROR_NOT_FOUND,
                              PRT_ERROR_OUT_OF_MEMORY,
                              PRT_ERROR_IO,
                              PRT_ERROR_BAD_MAGIC,
                              PRT_ERROR_UNSUPPORTED_VERSION,
                              PRT_ERROR_UNSUPPORTED_FEATURE,
                              PRT_ERROR_TRUNCATED,
                              PRT_ERROR_SIZE_MISMATCH,
                              PRT_ERROR_CORRUPT,
                              PRT_ERROR_CHECKSUM_MISMATCH,
                              PRT_ERROR_NON_FINITE,
                              PRT_ERROR_INDEX_OUT_OF_RANGE,
                              PRT_ERROR_UNSUPPORTED_BACKEND};
  std::set<std::string> seen;
  for (prt_result r : codes) {
    const std::string s = prt_result_string(r);
    EXPECT_TRUE(seen.insert(s).second) << s;
    EXPECT_NE(s.find("PRT_"), std::string::npos) << s;
  }
  EXPECT_STREQ(prt_result_string(static_cast<prt_result>(12345)), "unknown prt_result");
  // Explicit, grouped numbers are part of the ABI.
  EXPECT_EQ(PRT_ERROR_OUT_OF_MEMORY, 10);
  EXPECT_EQ(PRT_ERROR_BAD_MAGIC, 20);
  EXPECT_EQ(PRT_ERROR_UNSUPPORTED_BACKEND, 40);
}

using prt_test::CountingAllocator;

TEST(Context, CustomAllocatorGetsEveryAllocationBack) {
  CountingAllocator counter;
  prt_allocator allocator = counter.api();
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.allocator = &allocator;
  prt_context* ctx = nullptr;
  ASSERT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
  EXPECT_GE(counter.live, 1);
  prt_context_destroy(ctx);
  EXPECT_EQ(counter.live, 0);
  EXPECT_FALSE(counter.size_mismatch);
}

TEST(Context, CreationFailures) {
  EXPECT_EQ(prt_context_create(nullptr, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  prt_context* ctx = reinterpret_cast<prt_context*>(1);
  prt_allocator half{&CountingAllocator::alloc, nullptr, nullptr};
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.allocator = &half;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(ctx, nullptr);
  desc = prt::sized<prt_context_desc>();
  desc.backend_limit = static_cast<prt_backend>(9);
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_INVALID_ARGUMENT);
  desc = prt::sized<prt_context_desc>();
  desc.flags = 0x80;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_INVALID_ARGUMENT);

  CountingAllocator counter;
  counter.fail_at = 0;
  prt_allocator failing = counter.api();
  desc = prt::sized<prt_context_desc>();
  desc.allocator = &failing;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(ctx, nullptr);
  prt_context_destroy(nullptr);  // allowed
}

struct Messages {
  std::vector<std::pair<prt_result, std::string>> errors;
  static void sink(void* user, prt_result result, prt_severity severity, const char* text) {
    if (severity == PRT_SEVERITY_ERROR)
      static_cast<Messages*>(user)->errors.emplace_back(result, text);
  }
};

TEST(Context, ErrorsReachCallbackAndLastMessage) {
  Messages messages;
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.message = &Messages::sink;
  desc.message_user = &messages;
  prt_context* ctx = nullptr;
  ASSERT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
  EXPECT_EQ(prt_context_last_result(ctx), PRT_OK);
  EXPECT_STREQ(prt_context_last_message(ctx), "");

  const char not_a_blob[] = "definitely not a prtkit blob....";
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_asset_load_memory(ctx, not_a_blob, sizeof not_a_blob, PRT_VALIDATE_QUICK, &asset),
            PRT_ERROR_BAD_MAGIC);
  EXPECT_EQ(asset, nullptr);
  EXPECT_EQ(prt_context_last_result(ctx), PRT_ERROR_BAD_MAGIC);
  EXPECT_NE(std::string(prt_context_last_message(ctx)).find("magic"), std::string::npos);
  ASSERT_EQ(messages.errors.size(), 1u);
  EXPECT_EQ(messages.errors[0].first, PRT_ERROR_BAD_MAGIC);
  EXPECT_EQ(messages.errors[0].second, prt_context_last_message(ctx));

  // A later success keeps the last failure; clearing forgets it.
  EXPECT_EQ(prt_asset_validate(ctx, nullptr, 0, PRT_VALIDATE_QUICK, nullptr, 0),
            PRT_ERROR_TRUNCATED);
  EXPECT_EQ(prt_context_last_result(ctx), PRT_ERROR_TRUNCATED);
  prt_context_clear_error(ctx);
  EXPECT_EQ(prt_context_last_result(ctx), PRT_OK);
  EXPECT_STREQ(prt_context_last_message(ctx), "");
  prt_context_destroy(ctx);
}

// Contexts are independent: an error in one is not visible in another.
TEST(Context, NoSharedState) {
  prt_context* a = nullptr;
  prt_context* b = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &a), PRT_OK);
  ASSERT_EQ(prt_context_create(nullptr, &b), PRT_OK);
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_asset_load_memory(a, "PRTK", 4, PRT_VALIDATE_QUICK, &asset), PRT_ERROR_TRUNCATED);
  EXPECT_EQ(prt_context_last_result(a), PRT_ERROR_TRUNCATED);
  EXPECT_EQ(prt_context_last_result(b), PRT_OK);
  prt_context_destroy(a);
  prt_context_destroy(b);
}

}  // namespace
