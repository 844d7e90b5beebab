// SPDX-License-Identifier: MIT
// A caller-supplied allocator for the tests of the C API's allocation contract: it counts what is
// live, checks that each free is given the size its allocation asked for, and fails on demand (one
// chosen allocation, or all of them); and the sweep that fails each allocation of an operation in
// turn.
#pragma once

#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cstddef>
#include <cstdlib>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace prt_test {

struct CountingAllocator {
  int live = 0;
  int total = 0;      // allocations asked for, failed ones included
  int fail_at = -1;   // the allocation number that returns NULL, -1 never
  bool fail = false;  // every allocation returns NULL while set
  bool size_mismatch = false;
  std::vector<std::pair<void*, size_t>> blocks;

  static void* alloc(void* user, size_t size, size_t align) {
    auto* self = static_cast<CountingAllocator*>(user);
    if (self->total++ == self->fail_at || self->fail) return nullptr;
    void* p = std::aligned_alloc(align, (size + align - 1) / align * align);
    self->blocks.emplace_back(p, size);
    ++self->live;
    return p;
  }
  static void release(void* user, void* ptr, size_t size) {
    auto* self = static_cast<CountingAllocator*>(user);
    for (auto it = self->blocks.begin(); it != self->blocks.end(); ++it)
      if (it->first == ptr) {
        if (it->second != size) self->size_mismatch = true;
        self->blocks.erase(it);
        break;
      }
    --self->live;
    std::free(ptr);
  }
  prt_allocator api() { return prt_allocator{&alloc, &release, this}; }
};

// Runs `attempt` in a fresh context whose allocator fails allocation 1, then 2, ... (allocation 0
// is the context's own) until a run needs no failing allocation. Each failure must give
// PRT_ERROR_OUT_OF_MEMORY, and every run must give back all it allocated, sizes included; the
// last must succeed after at least one allocation of its own. `what` names the attempt.
inline void expect_every_allocation_failure_reported(
    const std::function<prt_result(prt_context*)>& attempt, const std::string& what) {
  for (int fail_at = 1;; ++fail_at) {
    CountingAllocator counter;
    counter.fail_at = fail_at;
    const prt_allocator allocator = counter.api();
    prt_context_desc desc = prt::sized<prt_context_desc>();
    desc.allocator = &allocator;
    prt_context* context = nullptr;
    ASSERT_EQ(prt_context_create(&desc, &context), PRT_OK) << what;
    const prt_result r = attempt(context);
    prt_context_destroy(context);
    EXPECT_EQ(counter.live, 0) << what << ", allocation " << fail_at << " failing";
    EXPECT_FALSE(counter.size_mismatch) << what << ", allocation " << fail_at << " failing";
    if (counter.total <= fail_at) {  // no allocation failed: done
      EXPECT_EQ(r, PRT_OK) << what;
      EXPECT_GT(fail_at, 1) << what << ": at least one allocation was exercised";
      return;
    }
    EXPECT_EQ(r, PRT_ERROR_OUT_OF_MEMORY) << what << ", allocation " << fail_at << " failing";
  }
}

}  // namespace prt_test
