// SPDX-License-Identifier: MIT
// Deterministic parallel loops for the baker's tracing stages (private header).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>

#include "prt/baker/context.hpp"
#include "tracing_thread.hpp"

namespace prt::bake::render {

// Runs body(task) for task in [0, tasks) on ctx.thread_count() threads (FTZ/DAZ set for Embree)
// and reports progress under `stage`; every task writes only its own outputs, so the result does
// not depend on scheduling. Throws Error("cancelled") when the progress callback says stop.
template <typename Body>
void parallel_tasks(std::size_t tasks, const Context& ctx, const std::string& stage, Body body) {
  std::atomic<std::size_t> done{0};
  std::atomic<bool> cancelled{false};
  std::mutex progress_mutex;
  tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tasks, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        TracingThreadScope fp_mode;  // FTZ/DAZ for Embree
                        for (std::size_t task = range.begin(); task != range.end(); ++task) {
                          if (cancelled.load(std::memory_order_relaxed)) return;
                          body(task);
                          const std::size_t finished = ++done;
                          if (ctx.progress) {
                            std::lock_guard<std::mutex> lock(progress_mutex);
                            if (!ctx.progress(static_cast<double>(finished) / tasks, stage)) {
                              cancelled = true;
                            }
                          }
                        }
                      });
  });
  if (cancelled) throw Error("cancelled");
}

}  // namespace prt::bake::render
