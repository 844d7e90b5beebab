// SPDX-License-Identifier: MIT
// prt_bench_shadowfield_scenes: technique `shadowfield`'s frame on the presets the issue sets
// marks for ("teapot": a teapot on a floor; "room": the room with its moving objects), baked
// in-process at the default settings (blobs cached in the build folder, keyed by the settings
// and the mesh, so a re-run only loads them), loaded into a runtime scene and animated along
// their paths while the eye orbits and the light turns, 3 bounces unless said:
//   Frame/<scene>/<backend>/threads:<t>  one whole frame (prepare, passes, output), wall clock
//                                        and process CPU time per frame;
//   Frame/<scene>/simd-log/threads:<t>   the same on SIMD with the log-space product;
//   Frame/<scene>/simd-<b>-bounce(s)/...  the same on SIMD with b < 3 bounces;
//   Frame/<scene>/gl                     the same on GL (prt_gl_shadowfield_shade, then a read of
//                                        one vertex to wait for it), where a headless GL exists;
//   StreamTriad/<t>                      the memory-bandwidth roofline of the same run.
// It also prints how far the backends' outputs are apart on one frame of each preset, relative
// to the largest output (scalar, SIMD and GL should agree to rounding).
// At the end it prints per scene the baked bytes (sum of the blobs) and the runtime memory
// (everything the context holds once loaded: the decoded objects and the scene's buffers; the
// blobs are loaded borrowed) against the marks, and each frame's time against its mark.
// Printed, never asserted.
#include <benchmark/benchmark.h>

#include <prt/prt.h>
#include <prt/prt_shadowfield.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "support/bench_triad.hpp"
#if PRT_BENCH_GL
#include "support/bench_gl.hpp"
#endif

extern "C" {
#include "shadowfield_scene.h"
}

namespace {

namespace bake = prt::bake;

// Counts the bytes the runtime holds, and the most it held.
struct ByteCounter {
  size_t live = 0, peak = 0;
  static void* alloc(void* user, size_t size, size_t align) {
    auto* self = static_cast<ByteCounter*>(user);
    self->live += size;
    if (self->live > self->peak) self->peak = self->live;
    return std::aligned_alloc(align, (size + align - 1) / align * align);
  }
  static void release(void* user, void* ptr, size_t size) {
    static_cast<ByteCounter*>(user)->live -= size;
    std::free(ptr);
  }
};

struct Mark {
  double frame_ms, baked_mb;
};
const std::map<std::string, Mark> kMarks = {{"teapot", {16.0, 16.0}}, {"room", {50.0, 32.0}}};

bake::ShadowfieldBakeSettings default_settings() {
  return bake::ShadowfieldBakeSettings{};
}

// What a cached blob depends on: the settings and the mesh (its size and a sample of its data).
std::string cache_key(const bake::ShadowfieldBakeSettings& s, const bake::ShadowfieldSceneObject& o,
                      size_t index) {
  std::ostringstream text;
  const auto& f = s.fields;
  text << f.order << ' ' << f.oof_shells << ' ' << f.inner << ' ' << f.outer << ' '
       << f.oof_face_size << ' ' << f.field_directions << ' ' << f.transfer_rays << ' ' << f.seed
       << ' ' << s.basis.size << ' ' << s.basis.lights << ' ' << s.basis.light_distance << ' '
       << s.srf.shells << ' ' << s.srf.face_size << ' ' << s.srf.inner << ' ' << s.srf.outer << ' '
       << s.srf.directions << ' ' << s.srf.seed << ' ' << s.brdf.terms << ' ' << s.brdf.grid_size
       << ' ' << s.bits << ' ' << index << ' ' << o.name << ' ' << int(o.material.model);
  for (const auto& mesh : o.mesh.meshes) {
    text << ' ' << mesh.positions.size() << ' ' << mesh.indices.size();
    for (size_t e = 0; e < mesh.positions.size(); e += 97) text << ' ' << mesh.positions[e].x;
  }
  uint64_t hash = 1469598103934665603ull;  // FNV-1a
  for (const char c : text.str()) hash = (hash ^ uint8_t(c)) * 1099511628211ull;
  char name[17];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(hash));
  return name;
}

std::vector<uint8_t> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// One object's blob, from the cache or baked (and cached).
std::vector<uint8_t> object_blob(const std::string& scene, const bake::ShadowfieldSceneObject& o,
                                 size_t index, const bake::ShadowfieldBakeSettings& settings) {
  const std::filesystem::path dir = PRT_BENCH_CACHE_DIR;
  const std::filesystem::path path =
      dir / (scene + "_" + std::to_string(index) + "_" + cache_key(settings, o, index) + ".prt");
  if (std::filesystem::exists(path)) return read_file(path);
  std::fprintf(stderr, "baking %s object %zu (%s)...\n", scene.c_str(), index, o.name.c_str());
  bake::Context ctx;
  const bake::ShadowfieldMaterial material =
      bake::make_shadowfield_material(o.material, settings.brdf);
  const bake::ShadowfieldBakeResult result =
      bake::bake_shadowfield_object(o.mesh, material, settings, ctx);
  std::vector<uint8_t> blob = bake::shadowfield_blob_of(result.object, settings.bits, o.name);
  std::filesystem::create_directories(dir);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(blob.data()), std::streamsize(blob.size()));
  return blob;
}

prt_shadowfield_transform transform_of(const bake::ShadowfieldPlacement& p) {
  prt_shadowfield_transform t{};
  t.struct_size = sizeof t;
  const glm::mat3 m = glm::mat3_cast(p.rotation);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) t.rotation[3 * r + c] = m[c][r];  // glm is column-major
  for (int c = 0; c < 3; ++c) t.translation[c] = p.translation[c];
  t.scale = p.scale;
  return t;
}

// A preset loaded into a runtime scene, with its output buffers.
struct LoadedScene {
  bake::ShadowfieldSceneDescription description;
  ByteCounter counter;
  prt_context* context = nullptr;
  std::vector<prt_asset*> assets;
  // The blobs, 16-byte aligned and alive as long as their assets (loaded borrowed, as a game
  // that maps its files would: the runtime then holds only what it decodes).
  std::vector<std::vector<std::max_align_t>> blobs;
  prt_shadowfield_scene* scene = nullptr;
  std::vector<std::vector<float>> out;
  std::vector<float*> out_pointers;
  size_t baked_bytes = 0, runtime_bytes = 0, peak_bytes = 0;
  size_t streamed_bytes = 0;  // the SRF rows the projections of a frame read
  uint32_t vertices = 0;

  explicit LoadedScene(const std::string& name) {
    description = bake::make_shadowfield_scene(name, PRT_SHARED_DIR);
    const prt_allocator allocator{&ByteCounter::alloc, &ByteCounter::release, &counter};
    prt_context_desc desc{};
    desc.struct_size = sizeof desc;
    desc.allocator = &allocator;
    prt_context_create(&desc, &context);
    prt_shadowfield_scene_create(context, uint32_t(description.instances.size()), &scene);
    for (size_t o = 0; o < description.objects.size(); ++o) {
      const std::vector<uint8_t> blob =
          object_blob(name, description.objects[o], o, default_settings());
      baked_bytes += blob.size();
      blobs.emplace_back((blob.size() + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t));
      std::memcpy(blobs.back().data(), blob.data(), blob.size());
      prt_asset* asset = nullptr;
      if (prt_asset_load_memory_borrowed(context, blobs.back().data(), blob.size(),
                                         PRT_VALIDATE_QUICK, &asset) != PRT_OK) {
        std::fprintf(stderr, "%s\n", prt_context_last_message(context));
        std::abort();
      }
      assets.push_back(asset);
      uint32_t id = 0;
      prt_shadowfield_scene_add_object(scene, asset, &id);
    }
    for (const auto& instance : description.instances) {
      const prt_shadowfield_transform t = transform_of(instance.path.at(0.0f));
      uint32_t id = 0;
      prt_shadowfield_scene_add_instance(scene, uint32_t(instance.object), &t, &id);
      const uint32_t v = prt_shadowfield_instance_vertex_count(scene, id);
      vertices += v;
      out.emplace_back(size_t(v) * 3u);
    }
    for (auto& o : out) out_pointers.push_back(o.data());
  }
  ~LoadedScene() {
    prt_shadowfield_scene_destroy(scene);
    for (prt_asset* a : assets) prt_asset_destroy(a);
    prt_context_destroy(context);
  }

  // The frame at time t: the instances on their paths and the eye turned about the target.
  void frame_at(float t, float eye[3]) {
    place(t);
    const glm::vec3 target = description.camera.target, offset = description.camera.eye - target;
    const float turn = 0.2f * t;
    eye[0] = target.x + offset.x * std::cos(turn) + offset.z * std::sin(turn);
    eye[1] = target.y + offset.y;
    eye[2] = target.z - offset.x * std::sin(turn) + offset.z * std::cos(turn);
  }

  // The instances at time t on their paths.
  void place(float t) {
    for (size_t i = 0; i < description.instances.size(); ++i) {
      const prt_shadowfield_transform transform = transform_of(description.instances[i].path.at(t));
      prt_shadowfield_scene_set_transform(scene, uint32_t(i), &transform);
    }
  }
};

// A sky-like order-4 environment (bright above, warm ambient), turned about +Y by `angle`.
std::vector<float> light_at(float angle) {
  std::vector<float> sky(16 * 3, 0.0f);
  const float base[16] = {1.2f,  0.6f,  0.2f,  0.3f,  0.05f,  0.1f,  0.15f, -0.08f,
                          0.04f, 0.02f, 0.01f, 0.03f, -0.02f, 0.01f, 0.02f, 0.01f};
  for (int k = 0; k < 16; ++k)
    for (int c = 0; c < 3; ++c) sky[3 * k + c] = base[k] * (1.0f - 0.1f * c);
  const float s = std::sin(angle), co = std::cos(angle);
  const float yaw[9] = {co, 0.0f, s, 0.0f, 1.0f, 0.0f, -s, 0.0f, co};
  std::vector<float> turned(sky.size());
  prt_sh_rotate(4, yaw, sky.data(), turned.data(), 3);
  return turned;
}

std::map<std::string, std::unique_ptr<LoadedScene>> g_scenes;
struct FrameFigure {
  double wall_ms = 0.0, cpu_ms = 0.0;
  bool ran = false;
};
std::map<std::string, FrameFigure> g_frames;  // by "scene/backend/threads"
prt_bench::Rate g_triad[3];

LoadedScene& scene_named(const std::string& name) {
  auto& slot = g_scenes[name];
  if (!slot) slot = std::make_unique<LoadedScene>(name);
  return *slot;
}

void record(benchmark::State& state, const std::string& key, double wall, double cpu,
            uint32_t vertices) {
  if (state.iterations() == 0) return;
  FrameFigure& f = g_frames[key];
  f.wall_ms = 1e3 * wall / double(state.iterations());
  f.cpu_ms = 1e3 * cpu / double(state.iterations());
  f.ran = true;
  state.counters["cpu_ms"] = f.cpu_ms;
  state.counters["vertices"] = vertices;
}

// What a frame is timed on: the backend, the product, the bounces, and its label in the keys.
struct Variant {
  prt_backend backend;
  prt_shadowfield_product product;
  uint32_t bounces;
  const char* label;
  float probe_spacing = 0.0f;  // bounce probes' spacing in object units; 0: per vertex
};

// The default product and bounces: the variants whose memory and streamed bytes are recorded.
bool is_default(const Variant& v) {
  return v.product == PRT_SHADOWFIELD_PRODUCT_TRIPLE && v.bounces == 3 && v.probe_spacing == 0.0f;
}

void BM_Frame(benchmark::State& state, const std::string& name, const Variant& variant) {
  LoadedScene& s = scene_named(name);
  if (prt_shadowfield_scene_set_product(s.scene, variant.product) != PRT_OK) {
    state.SkipWithError(prt_context_last_message(s.context));
    return;
  }
  const uint32_t threads = uint32_t(state.range(0));
  prt_workers* workers = nullptr;
  if (threads > 1) {
    prt_workers_desc desc{};
    desc.struct_size = sizeof desc;
    desc.thread_count = threads;
    prt_workers_create(s.context, &desc, &workers);
  }
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = variant.bounces;
  settings.backend = variant.backend;
  settings.bounce_probe_spacing = variant.probe_spacing;
  float time = 0.0f;
  double cpu = 0.0, wall = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    time += 1.0f / 60.0f;
    float eye[3];
    s.frame_at(time, eye);
    const std::vector<float> light = light_at(0.5f * time);
    state.ResumeTiming();
    const double c0 = prt_bench::process_cpu_seconds();
    const auto w0 = std::chrono::steady_clock::now();
    const prt_result r =
        workers
            ? prt_shadowfield_shade_workers(workers, s.scene, light.data(), eye, &settings,
                                            s.out_pointers.data())
            : prt_shadowfield_shade(s.scene, light.data(), eye, &settings, s.out_pointers.data());
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    cpu += prt_bench::process_cpu_seconds() - c0;
    if (r != PRT_OK) {
      state.SkipWithError(prt_context_last_message(s.context));
      break;
    }
  }
  prt_workers_destroy(workers);
  const std::string key = name + "/" + variant.label + "/" + std::to_string(threads);
  if (!is_default(variant)) {
    prt_shadowfield_scene_set_product(s.scene, PRT_SHADOWFIELD_PRODUCT_TRIPLE);
    record(state, key, wall, cpu, s.vertices);
    return;
  }
  s.runtime_bytes = s.counter.live;
  s.streamed_bytes = 0;
  for (uint32_t i = 0; i < s.scene->instance_count; ++i) {
    const prt_sf_instance& instance = s.scene->instances[i];
    const prt_sf_object* object = s.scene->objects[instance.object];
    if (!instance.is_source) continue;
    // The last frame's casts: only the SRF points its receivers read.
    uint64_t points = 0;
    for (uint64_t p = 0; p < prt_sf_point_count(&object->srf_shells); ++p)
      points += instance.needed[p] ? 1u : 0u;
    s.streamed_bytes += sizeof(float) * settings.bounces * object->basis_size * object->terms *
                        points * object->order * object->order;
  }
  s.peak_bytes = s.counter.peak;
  record(state, key, wall, cpu, s.vertices);
}

#if PRT_BENCH_GL
prt_bench::SharedGl g_gl;

void BM_FrameGl(benchmark::State& state, const std::string& name) {
  headless_gl* gl = g_gl.get();
  if (!gl) {
    state.SkipWithError(g_gl.missing().c_str());
    return;
  }
  LoadedScene& s = scene_named(name);
  prt_gl_shadowfield* shader = nullptr;
  if (prt_gl_shadowfield_create(s.scene, headless_gl_get_proc, gl, &shader) != PRT_OK) {
    state.SkipWithError(prt_context_last_message(s.context));
    return;
  }
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 3;
  settings.backend = PRT_BACKEND_GL;
  float time = 0.0f, one[3];
  double cpu = 0.0, wall = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    time += 1.0f / 60.0f;
    float eye[3];
    s.frame_at(time, eye);
    const std::vector<float> light = light_at(0.5f * time);
    state.ResumeTiming();
    const double c0 = prt_bench::process_cpu_seconds();
    const auto w0 = std::chrono::steady_clock::now();
    prt_result r = prt_gl_shadowfield_shade(shader, light.data(), eye, &settings);
    if (r == PRT_OK) r = prt_gl_shadowfield_read(shader, 0, 0, 1, one);  // waits for the frame
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    cpu += prt_bench::process_cpu_seconds() - c0;
    if (r != PRT_OK) {
      state.SkipWithError(prt_context_last_message(s.context));
      break;
    }
  }
  prt_gl_shadowfield_destroy(shader);
  record(state, name + "/gl/" + std::to_string(prt_bench::llvmpipe_threads()), wall, cpu,
         s.vertices);
}
#endif

void BM_StreamTriad(benchmark::State& state) {
  const int threads = int(state.range(0));
  g_triad[threads] = prt_bench::stream_triad(state, threads);
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void register_frames() {
#if PRT_BENCH_GL
  for (const char* name : {"teapot", "room"})
    benchmark::RegisterBenchmark((std::string("BM_Frame/") + name + "/gl").c_str(),
                                 [name](benchmark::State& state) { BM_FrameGl(state, name); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(2.0);
#endif
  // The log-space product on SIMD too (a receiver here has a few blockers, not the many it is
  // for), fewer bounces, and bounce probes at three spacings: the frame's cost against the
  // error per bounce count and per spacing of docs/shadowfield/accuracy.md.
  static const Variant variants[] = {
      {PRT_BACKEND_CPU, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 3, "scalar"},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 3, "simd"},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_LOG, 3, "simd-log"},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 1, "simd-1-bounce"},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 0, "simd-0-bounces"},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 3, "simd-probes-0.2", 0.2f},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 3, "simd-probes-0.3", 0.3f},
      {PRT_BACKEND_SIMD, PRT_SHADOWFIELD_PRODUCT_TRIPLE, 3, "simd-probes-0.4", 0.4f}};
  for (const char* name : {"teapot", "room"})
    for (const Variant& v : variants)
      benchmark::RegisterBenchmark(
          (std::string("BM_Frame/") + name + "/" + v.label).c_str(),
          [name, &v](benchmark::State& state) { BM_Frame(state, name, v); })
          ->ArgName("threads")
          ->Arg(1)
          ->Arg(2)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(2.0);
}

// One frame's outputs (every instance's vertices, one after another) on `backend` with bounce
// probes at `probe_spacing` (0: per vertex); empty when the backend is not usable here.
std::vector<float> shade_once(LoadedScene& s, prt_backend backend, float probe_spacing = 0.0f) {
  float eye[3];
  s.frame_at(1.0f, eye);
  const std::vector<float> light = light_at(0.5f);
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 3;
  settings.backend = backend;
  settings.bounce_probe_spacing = probe_spacing;
  std::vector<float> all;
  if (backend == PRT_BACKEND_GL) {
#if PRT_BENCH_GL
    headless_gl* gl = g_gl.get();
    prt_gl_shadowfield* shader = nullptr;
    if (!gl || prt_gl_shadowfield_create(s.scene, headless_gl_get_proc, gl, &shader) != PRT_OK)
      return all;
    if (prt_gl_shadowfield_shade(shader, light.data(), eye, &settings) == PRT_OK)
      for (uint32_t i = 0; i < uint32_t(s.out.size()); ++i) {
        std::vector<float> part(s.out[i].size());
        prt_gl_shadowfield_read(shader, i, 0, uint32_t(part.size() / 3), part.data());
        all.insert(all.end(), part.begin(), part.end());
      }
    prt_gl_shadowfield_destroy(shader);
#endif
    return all;
  }
  if (prt_shadowfield_shade(s.scene, light.data(), eye, &settings, s.out_pointers.data()) != PRT_OK)
    return all;
  for (const auto& part : s.out) all.insert(all.end(), part.begin(), part.end());
  return all;
}

// How far a frame's outputs are from another's, over the other's largest output.
double apart(const std::vector<float>& other, const std::vector<float>& scalar) {
  double largest = 0.0, worst = 0.0;
  for (const float v : scalar) largest = std::max(largest, double(std::fabs(v)));
  for (size_t e = 0; e < other.size(); ++e)
    worst = std::max(worst, double(std::fabs(other[e] - scalar[e])));
  return largest > 0.0 ? worst / largest : 0.0;
}

// The object of the instance whose vertex is furthest apart in two frames' outputs, and the
// vertex.
std::string worst_instance(const LoadedScene& s, const std::vector<float>& a,
                           const std::vector<float>& b) {
  size_t worst = 0;
  for (size_t e = 0; e < a.size(); ++e)
    if (std::fabs(a[e] - b[e]) > std::fabs(a[worst] - b[worst])) worst = e;
  size_t vertex = worst / 3;
  for (size_t i = 0; i < s.out.size(); ++i) {
    if (vertex < s.out[i].size() / 3) {
      const auto& object = s.description.objects[s.description.instances[i].object];
      return object.name + " (instance " + std::to_string(i) + ", vertex " +
             std::to_string(vertex) + ")";
    }
    vertex -= s.out[i].size() / 3;
  }
  return "none";
}

// How far SIMD's and GL's outputs of one frame are from scalar's, over the largest output; and
// with bounce probes, SIMD's and GL's from scalar's, and scalar's from the per-vertex frame.
void print_agreement(LoadedScene& s) {
  const std::vector<float> scalar = shade_once(s, PRT_BACKEND_CPU);
  double largest = 0.0;
  for (const float v : scalar) largest = std::max(largest, double(std::fabs(v)));
  std::printf("    one frame, largest output %.3g; apart from scalar by", largest);
  for (const prt_backend backend : {PRT_BACKEND_SIMD, PRT_BACKEND_GL}) {
    const std::vector<float> other = shade_once(s, backend);
    if (other.size() != scalar.size() || largest == 0.0) {
      std::printf(" %s: not run;", backend == PRT_BACKEND_GL ? "gl" : "simd");
      continue;
    }
    std::printf(" %s %.2g of it;", backend == PRT_BACKEND_GL ? "gl" : "simd", apart(other, scalar));
  }
  std::printf("\n");
  const float spacing = 0.3f;
  const std::vector<float> probed = shade_once(s, PRT_BACKEND_CPU, spacing);
  size_t over = 0;  // vertices with a channel more than 1 % of the largest output apart
  for (size_t v = 0; v < scalar.size() / 3; ++v) {
    double d = 0.0;
    for (size_t c = 0; c < 3; ++c)
      d = std::max(d, double(std::fabs(probed[3 * v + c] - scalar[3 * v + c])));
    over += d > 0.01 * largest;
  }
  std::printf(
      "    with bounce probes %g apart: scalar from per vertex %.2g (most on %s; %zu of %zu "
      "vertices over 0.01);",
      double(spacing), apart(probed, scalar), worst_instance(s, probed, scalar).c_str(), over,
      scalar.size() / 3);
  for (const prt_backend backend : {PRT_BACKEND_SIMD, PRT_BACKEND_GL}) {
    const std::vector<float> other = shade_once(s, backend, spacing);
    const char* name = backend == PRT_BACKEND_GL ? "gl" : "simd";
    if (other.size() == probed.size())
      std::printf(" %s from scalar %.2g;", name, apart(other, probed));
    else
      std::printf(" %s: not run;", name);
  }
  std::printf("\n");
}

void print_summary() {
  std::printf(
      "\nshadowfield presets, 3 bounces (roofline: STREAM triad %.1f GB/s on 1 thread, "
      "%.1f GB/s on 2, by CPU time)\n",
      1e-9 * g_triad[1].cpu, 1e-9 * g_triad[2].cpu);
  for (const auto& [name, scene] : g_scenes) {
    const Mark mark = kMarks.at(name);
    std::printf(
        "  %s: %u vertices over %zu instances; baked %.2f MB (mark %.0f MB); runtime "
        "memory %.2f MB (peak while loading %.2f MB); a frame streams %.1f MB of source "
        "fields\n",
        name.c_str(), scene->vertices, scene->description.instances.size(),
        1e-6 * double(scene->baked_bytes), mark.baked_mb, 1e-6 * double(scene->runtime_bytes),
        1e-6 * double(scene->peak_bytes), 1e-6 * double(scene->streamed_bytes));
    for (const auto& [key, f] : g_frames) {
      if (key.rfind(name + "/", 0) != 0 || !f.ran) continue;
      // The bandwidth floor: the source fields read at the triad's rate on as many threads.
      const int threads = key.back() == '2' ? 2 : 1;
      const double floor_ms = 1e3 * double(scene->streamed_bytes) / g_triad[threads].cpu;
      std::printf(
          "    %-16s %8.2f ms wall %8.2f ms CPU  %.2f x the %.0f ms mark; CPU %.1f x "
          "the bandwidth floor\n",
          key.c_str(), f.wall_ms, f.cpu_ms, f.wall_ms / mark.frame_ms, mark.frame_ms,
          g_triad[threads].cpu > 0.0 ? f.cpu_ms / floor_ms : 0.0);
    }
    print_agreement(*scene);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_frames();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  if (!g_scenes.empty()) print_summary();
  g_scenes.clear();
#if PRT_BENCH_GL
  g_gl.destroy();
#endif
  benchmark::Shutdown();
  return 0;
}
