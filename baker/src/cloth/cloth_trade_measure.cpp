// SPDX-License-Identifier: MIT
// Technique `cloth`'s trade: samples, texels, the cached reference, the method's shading, the
// error figures (cloth_trade_measure.hpp).
#include "cloth_trade_measure.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "../common/numbers.hpp"
#include "../common/trade_common.hpp"
#include "cloth_technique.hpp"
#include "prt/baker/cloth/cloth_light.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"
#include "prt/baker/text.hpp"

namespace prt::bake::cloth_trade {
namespace {

struct WorkersDeleter {
  void operator()(prt_workers* w) const { prt_workers_destroy(w); }
};
using WorkersPtr = std::unique_ptr<prt_workers, WorkersDeleter>;

WorkersPtr make_workers(prt_context* context, const Context& ctx) {
  prt_workers_desc desc = prt::sized<prt_workers_desc>();
  desc.thread_count = ctx.thread_count();
  prt_workers* workers = nullptr;
  trade::check_runtime(prt_workers_create(context, &desc, &workers), "prt_workers_create");
  return WorkersPtr(workers);
}

// FNV-1a over bytes: the reference cache's key.
struct Hash {
  std::uint64_t value = 1469598103934665603ull;
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) value = (value ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }
  template <typename T>
  void add_values(const std::vector<T>& v) {
    add(v.data(), v.size() * sizeof(T));
  }
};

std::uint64_t reference_key(const ClothPreset& fabric, const Samples& samples,
                            const io::EnvMap& map, const std::string& map_name, int block) {
  Hash h;
  h.add(fabric.name);
  for (const prt_cloth_thread& t : fabric.params.threads) h.add(&t, sizeof t);
  h.add(fabric.weave.tangent_count, sizeof fabric.weave.tangent_count);
  h.add(fabric.weave.offsets, sizeof fabric.weave.offsets);
  h.add(fabric.weave.multiplicity, sizeof fabric.weave.multiplicity);
  h.add_values(samples.normals);
  h.add_values(samples.warps);
  h.add_values(samples.views);
  h.add(map_name);
  h.add(&map.rotation(), sizeof(glm::mat3));
  h.add(&block, sizeof block);
  return h.value;
}

bool read_floats(const std::string& path, std::size_t count, std::vector<float>& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  out.resize(count);
  in.read(reinterpret_cast<char*>(out.data()), std::streamsize(count * sizeof(float)));
  return in.gcount() == std::streamsize(count * sizeof(float)) && in.peek() == EOF;
}

// Written under a temporary name and renamed, so an interrupted run leaves no torn file.
void write_floats(const std::string& path, const std::vector<float>& values) {
  const std::string partial = path + ".partial";
  {
    std::ofstream out(partial, std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()),
              std::streamsize(values.size() * sizeof(float)));
    trade::check_written(out, partial);
  }
  std::filesystem::rename(partial, path);
}

}  // namespace

std::vector<SurfaceFrame> surface_frames(const Scene& scene, std::uint32_t limit) {
  std::vector<SurfaceFrame> frames;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.vertex_count() && frames.size() < limit; ++v) {
      const glm::vec3 n = glm::normalize(mesh.normals[v]);
      if (!std::isfinite(n.x)) continue;
      const SurfaceFrame f{n, cloth_warp(n, mesh.tangents.empty() ? nullptr : &mesh.tangents[v])};
      const bool known = std::any_of(frames.begin(), frames.end(), [&](const SurfaceFrame& g) {
        return glm::all(glm::equal(g.normal, f.normal)) && glm::all(glm::equal(g.warp, f.warp));
      });
      if (!known) frames.push_back(f);
    }
  }
  if (frames.empty()) throw Error(scene.source + ": no vertex with a normal to measure cloth on");
  return frames;
}

std::vector<glm::vec3> frame_views(const SurfaceFrame& frame) {
  const glm::vec3 side = glm::cross(frame.normal, frame.warp);
  std::vector<glm::vec3> views;
  for (int e = 0; e < 4; ++e) {
    const double elevation = (15.0 + 20.0 * e) * kPi / 180.0;
    for (int a = 0; a < 8; ++a) {
      const double azimuth = (45.0 * a + (e % 2 ? 22.5 : 0.0)) * kPi / 180.0;
      const glm::vec3 d = float(std::cos(elevation) * std::cos(azimuth)) * frame.warp +
                          float(std::cos(elevation) * std::sin(azimuth)) * side +
                          float(std::sin(elevation)) * frame.normal;
      views.push_back(glm::normalize(d));
    }
  }
  return views;
}

prt_cloth_pixels Samples::pixels() const {
  prt_cloth_pixels p = prt::sized<prt_cloth_pixels>();
  p.normals = normals.data();
  p.warps = warps.data();
  p.views = views.data();
  return p;
}

Samples make_samples(const std::vector<SurfaceFrame>& frames) {
  Samples s;
  for (const SurfaceFrame& f : frames)
    for (const glm::vec3& v : frame_views(f)) {
      s.normals.insert(s.normals.end(), {f.normal.x, f.normal.y, f.normal.z});
      s.warps.insert(s.warps.end(), {f.warp.x, f.warp.y, f.warp.z});
      s.views.insert(s.views.end(), {v.x, v.y, v.z});
    }
  return s;
}

prt_cloth_env_texels EnvTexels::view() const {
  prt_cloth_env_texels t = prt::sized<prt_cloth_env_texels>();
  t.count = static_cast<std::uint32_t>(solid_angles.size());
  t.directions = directions.data();
  t.power = power.data();
  return t;
}

EnvTexels env_texels(const io::EnvMap& map, int block) {
  EnvTexels out;
  for (int y0 = 0; y0 < map.height(); y0 += block)
    for (int x0 = 0; x0 < map.width(); x0 += block) {
      glm::dvec3 power(0.0), weighted(0.0), plain(0.0);
      double solid_angle = 0.0;
      for (int y = y0; y < std::min(y0 + block, map.height()); ++y)
        for (int x = x0; x < std::min(x0 + block, map.width()); ++x) {
          glm::vec3 d;
          float omega = 0.0f;
          if (!map.texel(x, y, &d, &omega)) continue;
          const glm::dvec3 p = glm::dvec3(map.texel_value(x, y)) * double(omega);
          power += p;
          weighted += (p.x + p.y + p.z) * glm::dvec3(d);
          plain += double(omega) * glm::dvec3(d);
          solid_angle += omega;
        }
      if (solid_angle <= 0.0) continue;
      const glm::dvec3 mean = glm::length(weighted) > 0.0 ? weighted : plain;
      const glm::vec3 d = glm::vec3(glm::normalize(mean));
      out.directions.insert(out.directions.end(), {d.x, d.y, d.z});
      out.power.insert(out.power.end(), {float(power.x), float(power.y), float(power.z)});
      out.solid_angles.push_back(float(solid_angle));
    }
  return out;
}

EnvTexels sg_texels(const std::vector<prt_cloth_lobe>& lobes) {
  constexpr int kRings = 64, kAzimuths = 64;
  EnvTexels out;
  for (const prt_cloth_lobe& lobe : lobes) {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(lobe.axis[0], lobe.axis[1], lobe.axis[2]));
    const glm::dvec3 helper = std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(axis, helper)), e2 = glm::cross(axis, e1);
    // Mass of exp(lambda (c - 1)) over c in [c, 1], per unit azimuth: (1 - exp(lambda (c - 1))) /
    // lambda; the rings split the whole sphere's mass evenly, c_k from its inverse.
    const double lambda = lobe.sharpness, total = -std::expm1(-2.0 * lambda);
    auto c_at = [&](double fraction) { return 1.0 + std::log1p(-fraction * total) / lambda; };
    const double mass = total / lambda * 2.0 * kPi / (double(kRings) * kAzimuths);
    for (int k = 0; k < kRings; ++k) {
      const double c = std::clamp(c_at((k + 0.5) / kRings), -1.0, 1.0);
      const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
      for (int a = 0; a < kAzimuths; ++a) {
        const double phi = 2.0 * kPi * (a + 0.5) / kAzimuths;
        const glm::dvec3 d = c * axis + s * (std::cos(phi) * e1 + std::sin(phi) * e2);
        out.directions.insert(out.directions.end(), {float(d.x), float(d.y), float(d.z)});
        for (int ch = 0; ch < 3; ++ch) out.power.push_back(float(lobe.rgb[ch] * mass));
        out.solid_angles.push_back(float(mass));  // the cell's lobe mass (radiance 1 at the axis)
      }
    }
  }
  return out;
}

std::vector<float> reference(const ClothPreset& fabric, const Samples& samples,
                             const EnvTexels& texels, const Context& ctx) {
  auto [context, made] = prt::create_context();
  trade::check_runtime(made, "prt_context_create");
  const WorkersPtr workers = make_workers(context.get(), ctx);
  const prt_cloth_env_texels env = texels.view();
  const prt_cloth_pixels pixels = samples.pixels();
  std::vector<float> rgb(3 * std::size_t(samples.count()));
  trade::check_runtime(prt_cloth_reference_workers(workers.get(), &fabric.params, &fabric.weave,
                                                   &env, &pixels, 0, samples.count(), rgb.data()),
                       "prt_cloth_reference");
  return rgb;
}

std::vector<float> cached_reference(const ClothPreset& fabric, const Samples& samples,
                                    const io::EnvMap& map, const std::string& map_name, int block,
                                    const std::string& cache_dir, const Context& ctx) {
  const std::uint64_t key = reference_key(fabric, samples, map, map_name, block);
  const std::string path = cache_dir + "/cloth_" + fabric.name + "_" + map_name +
                           format("_%016llx.f32", static_cast<unsigned long long>(key));
  std::vector<float> rgb;
  if (read_floats(path, 3 * std::size_t(samples.count()), rgb)) return rgb;
  const auto start = std::chrono::steady_clock::now();
  const EnvTexels texels = env_texels(map, block);
  rgb = reference(fabric, samples, texels, ctx);
  write_floats(path, rgb);
  ctx.info(format("cloth trade: reference of %s under %s (%zu texels, %u samples) in %.1f s",
                  fabric.name.c_str(), map_name.c_str(), texels.solid_angles.size(),
                  samples.count(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
  return rgb;
}

Shading shade(const std::vector<std::uint8_t>& blob, prt_backend backend, const Samples& samples,
              const std::vector<prt_cloth_lobe>& lobes, const prt_cloth_settings& settings,
              int frames, const Context& ctx) {
  const trade::RuntimeAsset runtime = trade::load_runtime_asset(blob);
  const WorkersPtr workers = make_workers(runtime.context.get(), ctx);
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = static_cast<std::uint32_t>(lobes.size());
  light.lobes = lobes.data();
  const prt_cloth_pixels pixels = samples.pixels();
  Shading s;
  s.rgb.resize(3 * std::size_t(samples.count()));
  const double ms = trade::median_frame_ms(frames, "prt_cloth_shade", [&] {
    return prt_cloth_shade_workers(workers.get(), runtime.asset.get(), backend, 0, nullptr, &light,
                                   &settings, &pixels, 0, samples.count(), s.rgb.data());
  });
  if (ms >= 0.0)
    s.microseconds_per_sample = 1000.0 * ms / samples.count();
  else
    s.rgb.clear();
  return s;
}

double nrmse(const std::vector<float>& x, const std::vector<float>& reference) {
  double squares = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = double(x[i]) - double(reference[i]);
    squares += d * d;
    sum += reference[i];
  }
  const double n = double(x.size());
  return sum > 0.0 ? std::sqrt(squares / n) / (sum / n) : 0.0;
}

double bias(const std::vector<float>& x, const std::vector<float>& reference) {
  double a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    a += x[i];
    b += reference[i];
  }
  return b > 0.0 ? a / b - 1.0 : 0.0;
}

namespace {

ClothFactor truncated(const ClothFactor& f, std::uint32_t rank) {
  if (rank >= f.rank) return f;
  ClothFactor t;
  t.rank = rank;
  const std::size_t rows = f.u.size() / f.rank, columns = f.v.size() / f.rank;
  for (std::size_t i = 0; i < rows; ++i)
    t.u.insert(t.u.end(), f.u.begin() + std::ptrdiff_t(i * f.rank),
               f.u.begin() + std::ptrdiff_t(i * f.rank + rank));
  for (std::size_t i = 0; i < columns; ++i)
    t.v.insert(t.v.end(), f.v.begin() + std::ptrdiff_t(i * f.rank),
               f.v.begin() + std::ptrdiff_t(i * f.rank + rank));
  return t;
}

}  // namespace

ClothSection truncated_section(const ClothSection& section,
                               const std::vector<std::vector<double>>& full_singular_values,
                               const std::vector<std::vector<double>>& cone_singular_values,
                               double energy) {
  ClothSection out = section;
  for (std::size_t t = 0; t < out.tables.size(); ++t) {
    out.tables[t].full =
        truncated(section.tables[t].full, cloth_rank_for_energy(full_singular_values[t], energy));
    out.tables[t].cone =
        truncated(section.tables[t].cone, cloth_rank_for_energy(cone_singular_values[t], energy));
  }
  return out;
}

}  // namespace prt::bake::cloth_trade
