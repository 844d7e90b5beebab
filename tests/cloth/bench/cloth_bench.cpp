// SPDX-License-Identifier: MIT
// prt_bench_cloth: frames per second of cloth shading (prt_cloth_shade_workers) at 640x480, full
// screen, on a pool of two threads, for linen_plain and polyester_satin_charmeuse over synthetic
// tables of a realistic size (N_xi 32, 10 levels, 16x16 views, rank 16) under a fitted-sky-like
// light (ten lobes of sharpness 5..100 over the sphere and a sun of 5000):
//   flat:   a flat patch seen in perspective (one frame for every pixel, the view per pixel);
//   draped: a procedural wavy surface (every pixel's frame differs).
// Each backend runs each step of the SIMD kernel's savings apart: no culling (hidden and weak
// lobes kept), culling, and culling with the frame cache; the ratio is to the first step of the
// same backend in the same run. The scalar reference shades every 16th row and is extrapolated
// (a full frame takes it tens of seconds). Printed, never asserted.
// Frames per second are given by the wall clock and, since the machine may be shared, by the
// process's CPU time (threads x frame / CPU seconds: what the threads would give on cores of
// their own).
//   prt_bench_cloth [--threads N] [--repeat N] [--only SCENE/FABRIC/BACKEND/STEP] (a substring)
#include <prt/prt_cloth_asset.h>
#include <prt/prt_workers.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <time.h>

#include "cloth/simd/cloth_synthetic.hpp"

namespace {

constexpr std::uint32_t kWidth = 640, kHeight = 480;

struct Screen {
  std::vector<float> normals, warps, views;
  std::uint32_t rows = 0;
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p{};
    p.struct_size = sizeof p;
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
};

void normalize(float v[3]) {
  const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; ++i) v[i] /= l;
}

// A camera at (0, -3, 2.2) looking down at the plane z = 0 (vertical field of view 50 degrees,
// pitched 40 degrees down: every pixel sees the plane). Rows `row_step` apart. The wavy surface
// is z = a sin(3 x) cos(2 y) + a/2 sin(5 y + x): its normal and warp (the x tangent) at the point
// where the pixel's ray meets z = 0; the view from there to the eye.
Screen screen(bool draped, std::uint32_t row_step) {
  const float eye[3] = {0.0f, -3.0f, 2.2f};
  const float pitch = 40.0f * 3.14159265f / 180.0f, half = std::tan(25.0f * 3.14159265f / 180.0f);
  const float fwd[3] = {0.0f, std::cos(pitch), -std::sin(pitch)};
  const float up[3] = {0.0f, std::sin(pitch), std::cos(pitch)};
  const float right[3] = {1.0f, 0.0f, 0.0f};
  const float a = draped ? 0.12f : 0.0f;
  Screen s;
  for (std::uint32_t y = 0; y < kHeight; y += row_step) {
    ++s.rows;
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float u = (2.0f * (float(x) + 0.5f) / kWidth - 1.0f) * half * kWidth / kHeight;
      const float v = (1.0f - 2.0f * (float(y) + 0.5f) / kHeight) * half;
      float d[3];
      for (int i = 0; i < 3; ++i) d[i] = fwd[i] + u * right[i] + v * up[i];
      normalize(d);
      const float t = -eye[2] / d[2];
      const float px = eye[0] + t * d[0], py = eye[1] + t * d[1];
      const float hx = a * 3.0f * std::cos(3.0f * px) * std::cos(2.0f * py) +
                       a * 0.5f * std::cos(5.0f * py + px);
      const float hy = -a * 2.0f * std::sin(3.0f * px) * std::sin(2.0f * py) +
                       a * 2.5f * std::cos(5.0f * py + px);
      float n[3] = {-hx, -hy, 1.0f}, w[3] = {1.0f, 0.0f, hx}, view[3] = {-d[0], -d[1], -d[2]};
      normalize(n);
      normalize(w);
      s.normals.insert(s.normals.end(), n, n + 3);
      s.warps.insert(s.warps.end(), w, w + 3);
      s.views.insert(s.views.end(), view, view + 3);
    }
  }
  return s;
}

struct Step {
  const char* name;
  std::uint32_t flags;
};

const Step kSteps[] = {
    {"no culling",
     PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES | PRT_CLOTH_NO_FRAME_CACHE},
    {"culling", PRT_CLOTH_NO_FRAME_CACHE},
    {"+ frame cache", 0u},
};

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Timing {
  double wall = 1e30, cpu = 1e30;
};

// Wall and CPU seconds for one shade of the screen (the best of `repeat`).
Timing seconds(prt_workers* workers, const prt_asset* asset, prt_backend backend,
               std::uint32_t fabric, const prt_cloth_light& light, std::uint32_t flags,
               const Screen& s, int repeat) {
  prt_cloth_settings settings = prt::sized<prt_cloth_settings>();
  settings.flags = flags;
  const prt_cloth_pixels pixels = s.pixels();
  const std::uint32_t count = std::uint32_t(s.normals.size() / 3);
  std::vector<float> out(3 * std::size_t(count));
  Timing best;
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_now();
    const auto t0 = std::chrono::steady_clock::now();
    const prt_result res = prt_cloth_shade_workers(workers, asset, backend, fabric, nullptr, &light,
                                                   &settings, &pixels, 0, count, out.data());
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = cpu_now();
    if (res != PRT_OK) {
      std::fprintf(stderr, "prt_cloth_shade_workers: %s\n", prt_result_string(res));
      std::exit(1);
    }
    best.wall = std::min(best.wall, std::chrono::duration<double>(t1 - t0).count());
    best.cpu = std::min(best.cpu, c1 - c0);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint32_t threads = 2;
  int repeat = 3;
  std::string only;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--only") == 0) only = argv[i + 1];
    if (std::strcmp(argv[i], "--threads") == 0) threads = std::uint32_t(std::atoi(argv[i + 1]));
    if (std::strcmp(argv[i], "--repeat") == 0) repeat = std::atoi(argv[i + 1]);
  }
  prt_test::SyntheticGrid grid;
  grid.xi_size = 32;
  grid.levels = 10;
  grid.view_theta = grid.view_phi = 16;
  grid.rank = grid.cone_rank = 16;
  grid.bits = 16;
  const std::vector<std::string> fabrics = {"linen_plain", "polyester_satin_charmeuse"};
  const std::vector<std::uint8_t> blob = prt_test::synthetic_cloth_blob(grid, fabrics, 1);
  auto context = prt::create_context().handle;
  prt_asset* asset = nullptr;
  if (prt_asset_load_memory(context.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset) !=
      PRT_OK) {
    std::fprintf(stderr, "load: %s\n", prt_context_last_message(context.get()));
    return 1;
  }
  prt_workers_desc desc = prt::sized<prt_workers_desc>();
  desc.thread_count = threads;
  prt_workers* workers = nullptr;
  if (prt_workers_create(context.get(), &desc, &workers) != PRT_OK) return 1;
  const std::vector<prt_cloth_lobe> lobes = prt_test::sky_lobes(10, 5.0f, 100.0f, true, 3);
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = std::uint32_t(lobes.size());
  light.lobes = lobes.data();
  const bool simd = prt_context_backend(context.get()) == PRT_BACKEND_SIMD;
  std::printf(
      "cloth shading at %ux%u on %u threads, K = %zu lobes, tables N_xi %u L %u views "
      "%ux%u rank %u (scalar: every 16th row, extrapolated)\n",
      kWidth, kHeight, threads, lobes.size(), grid.xi_size, grid.levels, grid.view_theta,
      grid.view_phi, grid.rank);
  std::printf("%-7s %-26s %-7s %-14s %9s %9s %6s\n", "scene", "fabric", "backend", "step",
              "fps wall", "fps cpu", "ratio");
  for (bool draped : {false, true}) {
    const Screen full = screen(draped, 1), sparse = screen(draped, 16);
    for (std::uint32_t f = 0; f < fabrics.size(); ++f) {
      for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
        if (backend == PRT_BACKEND_SIMD && !simd) continue;
        const Screen& s = backend == PRT_BACKEND_CPU ? sparse : full;
        const double share = double(s.rows) / kHeight;
        double first = 0.0;
        for (const Step& step : kSteps) {
          if (backend == PRT_BACKEND_CPU && (step.flags & PRT_CLOTH_NO_FRAME_CACHE) == 0) continue;
          const std::string name = std::string(draped ? "draped" : "flat") + "/" + fabrics[f] +
                                   "/" + prt_backend_name(backend) + "/" + step.name;
          if (name.find(only) == std::string::npos) continue;
          const Timing t = seconds(workers, asset, backend, f, light, step.flags, s,
                                   backend == PRT_BACKEND_CPU ? 1 : repeat);
          const double fps = share / t.wall, fps_cpu = threads * share / t.cpu;
          if (first == 0.0) first = fps_cpu;
          std::printf("%-7s %-26s %-7s %-14s %9.3f %9.3f %6.2f\n", draped ? "draped" : "flat",
                      fabrics[f].c_str(), prt_backend_name(backend), step.name, fps, fps_cpu,
                      fps_cpu / first);
          std::fflush(stdout);
        }
      }
    }
  }
  prt_workers_destroy(workers);
  prt_asset_destroy(asset);
  return 0;
}
