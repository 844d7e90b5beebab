// SPDX-License-Identifier: MIT
// Per-frame cost of the wavelet light (resample a 1024 x 512 lat-long, transform, select M) at
// N = 32, 64, 128 on both parameterisations. Prints milliseconds; not a test (no assertions), run
// by hand: prt_wavelet_light_timing [frames].
#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

namespace {
double cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 20;
  const uint32_t width = 1024, height = 512, m = 200;
  std::vector<float> map(size_t(width) * height * 3);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> value(0.0f, 4.0f);
  for (float& v : map) v = value(rng);
  for (uint32_t param : {PRT_WAVELET_PARAM_CUBE, PRT_WAVELET_PARAM_DUAL_PARABOLOID}) {
    for (uint32_t size : {32u, 64u, 128u}) {
      std::vector<float> light(4 * size_t(prt_wavelet_coefficient_count(param, size)));
      // The fastest frame of each step, in thread CPU time: the machine is shared, and this is what
      // the code costs when it has a core to itself.
      double t_resample = 1e30, t_transform = 1e30, t_select = 1e30;
      for (int frame = 0; frame < frames; ++frame) {
        const double angle = 0.1 * frame, c = std::cos(angle), s = std::sin(angle);
        const float rotation[9] = {float(c), 0, float(s), 0, 1, 0, float(-s), 0, float(c)};
        const double t0 = cpu_ms();
        prt_wavelet_resample_latlong(param, size, map.data(), width, height, rotation,
                                     light.data());
        const double t1 = cpu_ms();
        prt_wavelet_transform_light(param, size, light.data());
        const double t2 = cpu_ms();
        prt_wavelet_select_light(param, size, m, light.data());
        const double t3 = cpu_ms();
        t_resample = std::min(t_resample, t1 - t0);
        t_transform = std::min(t_transform, t2 - t1);
        t_select = std::min(t_select, t3 - t2);
      }
      std::printf(
          "%s N=%3u: resample %.2f ms, transform %.2f ms, select(M=%u) %.2f ms, "
          "total %.2f ms per frame (fastest frame, thread CPU time)\n",
          param == PRT_WAVELET_PARAM_CUBE ? "cube      " : "paraboloid", size, t_resample,
          t_transform, m, t_select, t_resample + t_transform + t_select);
    }
  }
  return 0;
}
