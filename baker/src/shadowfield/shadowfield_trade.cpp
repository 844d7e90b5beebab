// SPDX-License-Identifier: MIT
// prt-bake trade shadowfield SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade
// of technique `shadowfield` (docs/shadowfield/trade.md), in two modes.
// - SCENE a mesh file: one object alone. Sweeps around a base setting (order, BRDF terms, bits,
//   transfer rays): each setting is baked in-process, written to a blob and loaded through the
//   runtime, then the object is turned about +Y through its centre to a few angles (so the view
//   and the light fall differently on it) and shaded by the runtime (0 bounces, a fixed eye)
//   against the reference renderer's radiance of the same placement towards the same eye (0
//   bounces, the same BRDF; cached).
// - SCENE a preset's name (teapot, bunny, room, procedural; docs/shadowfield/scenes.md): every
//   knob of the technique (order, K, rays, bits, OOF and SRF shells and points per shell, N,
//   bounces), one at a time around a base. Each setting bakes every object (blobs cached by
//   settings), shades the preset's placements at the given times on the runtime (SIMD and
//   scalar, CPU time per frame, runtime memory) and compares them with the reference of the same
//   placement and bounce count, rendered once and cached: it does not depend on the knobs.
// Writes DIR/trade.csv and DIR/trade.md.
#include <prt/prt.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "prt/baker/instances.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/shadowfield/shadowfield_measure.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "shadowfield_technique.hpp"

namespace prt::bake {
namespace {

using namespace trade;

struct SfTradeSettings {
  std::vector<std::uint32_t> orders{2, 3, 4, 5, 6}, terms{1, 2, 4, 8}, rays{64, 256, 1024};
  std::vector<int> bits{8, 16};
  std::uint32_t base_order = 4, base_terms = 4, base_rays = 256;
  int base_bits = 16;
  std::string brdf = "lambert";
  std::uint32_t rotations = 3;
  ShadowfieldBakeSettings bake;  // the rest of the bake (fields, basis, SRF), small by default
};

struct Setting {
  std::uint32_t order = 0, terms = 0, rays = 0;
  int bits = 0;
  std::string sweeps;
};

struct Row {
  std::string map, sweeps;
  Setting setting;
  double degrees = 0.0;
  double error = 0.0, bias = 0.0, ref_noise = 0.0, cpu_ms = 0.0, bake_seconds = 0.0;
  std::size_t blob_bytes = 0, compared = 0;  // compared: vertices facing the eye
};

// Order sweep at the base terms, rays and bits; terms (glossy only), rays and bits at the base
// order. A setting in several sweeps is baked once.
std::vector<Setting> sweep_settings(const SfTradeSettings& o, bool glossy) {
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, int>, std::string> sweeps;
  const std::uint32_t base_terms = glossy ? o.base_terms : 1;
  auto add = [&](std::uint32_t order, std::uint32_t terms, std::uint32_t rays, int bits,
                 const char* sweep) {
    std::string& names = sweeps[{order, terms, rays, bits}];
    const std::string name = sweep;
    // A value given twice to one sweep names it once.
    if (("+" + names + "+").find("+" + name + "+") != std::string::npos) return;
    names += (names.empty() ? "" : "+") + name;
  };
  for (std::uint32_t order : o.orders) add(order, base_terms, o.base_rays, o.base_bits, "order");
  if (glossy) {
    for (std::uint32_t terms : o.terms) add(o.base_order, terms, o.base_rays, o.base_bits, "terms");
  }
  for (std::uint32_t rays : o.rays) add(o.base_order, base_terms, rays, o.base_bits, "rays");
  for (int bits : o.bits) add(o.base_order, base_terms, o.base_rays, bits, "bits");
  std::vector<Setting> settings;
  for (const auto& [key, names] : sweeps)
    settings.push_back(
        {std::get<0>(key), std::get<1>(key), std::get<2>(key), std::get<3>(key), names});
  return settings;
}

void check_settings(const SfTradeSettings& o) {
  if (o.orders.empty() || o.terms.empty() || o.rays.empty() || o.bits.empty())
    throw Error("trade: --orders, --terms, --rays and --bits need at least one value each");
  for (std::uint32_t order : o.orders) {
    if (order < 2 || order > 6)
      throw Error("--orders: " + std::to_string(order) + " is outside 2..6");
  }
  for (std::uint32_t terms : o.terms) {
    if (terms < 1 || terms > 8)
      throw Error("--terms: " + std::to_string(terms) + " is outside 1..8");
  }
  for (std::uint32_t rays : o.rays) {
    if (rays < 1 || rays > 65536)
      throw Error("--rays: " + std::to_string(rays) + " is outside 1..65536");
  }
  for (int bits : o.bits) {
    if (bits != 8 && bits != 16) throw Error("--bits: " + std::to_string(bits) + " is not 8 or 16");
  }
  parse_brdf_option(o.brdf);
}

// The object's turns: evenly spread over a full turn about +Y.
double turn_degrees(std::uint32_t index, std::uint32_t count) {
  return 360.0 * index / count;
}

glm::mat3 turn(double degrees) {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(float(degrees)), {0.0f, 1.0f, 0.0f}));
}

// The bounding sphere's centre stays put: t = c - R c.
Instance turned_instance(double degrees, const glm::vec3& centre) {
  Instance instance;
  instance.rotation = turn(degrees);
  instance.translation = centre - instance.rotation * centre;
  return instance;
}

// The camera: in front of the object, a little above it.
glm::vec3 trade_eye(const BoundingSphere& sphere) {
  return sphere.centre + sphere.radius * glm::vec3(0.0f, 1.0f, 3.0f);
}

// Whether each vertex (scene order) faces `eye` once placed: the camera sees its front. The
// others are not compared: the reference reflects nothing towards an eye below the surface,
// while the runtime reads the BRDF's g at the horizon there.
std::vector<bool> facing_eye(const Scene& scene, const Instance& placed, const glm::vec3& eye) {
  std::vector<bool> facing;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 normal = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
      facing.push_back(glm::dot(placed.rotation * normal, eye - placed.place(mesh.positions[v])) >
                       0.0f);
    }
  }
  return facing;
}

std::vector<glm::vec3> masked(const std::vector<glm::vec3>& values, const std::vector<bool>& keep) {
  std::vector<glm::vec3> kept;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (keep[i]) kept.push_back(values[i]);
  }
  return kept;
}

double mean_bias(const std::vector<glm::vec3>& x, const std::vector<glm::vec3>& ref) {
  double diff = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      diff += double(x[i][c]) - ref[i][c];
      sum += ref[i][c];
    }
  }
  return sum != 0.0 ? diff / sum : 0.0;
}

const std::vector<std::string> kCsvColumns = {"scene",
                                              "map",
                                              "brdf",
                                              "sweeps",
                                              "order",
                                              "terms",
                                              "transfer_rays",
                                              "bits",
                                              "rotation_deg",
                                              "vertices",
                                              "vertices_compared",
                                              "rel_rmse",
                                              "bias",
                                              "ref_noise",
                                              "rel_rmse_noise_removed",
                                              "ref_spp",
                                              "shade_cpu_ms",
                                              "blob_bytes",
                                              "bake_seconds"};

std::vector<std::string> csv_cells(const Row& r, const SfTradeSettings& o, const TradeInput& input,
                                   std::size_t vertices) {
  const Setting& s = r.setting;
  std::string brdf = o.brdf;  // its commas would split the cell
  std::replace(brdf.begin(), brdf.end(), ',', ';');
  return {stem(input.scene),
          r.map,
          brdf,
          r.sweeps,
          std::to_string(s.order),
          std::to_string(s.terms),
          std::to_string(s.rays),
          std::to_string(s.bits),
          format("%g", r.degrees),
          std::to_string(vertices),
          std::to_string(r.compared),
          format("%.6g", r.error),
          format("%.6g", r.bias),
          format("%.6g", r.ref_noise),
          format("%.6g", noise_removed(r.error, r.ref_noise)),
          std::to_string(input.ref_spp),
          ms_text(r.cpu_ms),
          std::to_string(r.blob_bytes),
          format("%.4g", r.bake_seconds)};
}

const std::vector<Column> kMarkdownColumns = {
    {"sweep", false}, {"order"},  {"terms"},       {"rays"},   {"bits"},     {"turn deg"},
    {"error %"},      {"bias %"}, {"ref noise %"}, {"CPU ms"}, {"blob KiB"}, {"bake s"}};

std::vector<std::string> markdown_cells(const Row& r) {
  const Setting& s = r.setting;
  return {r.sweeps,
          std::to_string(s.order),
          std::to_string(s.terms),
          std::to_string(s.rays),
          std::to_string(s.bits),
          format("%g", r.degrees),
          format("%.2f", 100 * r.error),
          format("%+.2f", 100 * r.bias),
          format("%.2f", 100 * r.ref_noise),
          ms_text(r.cpu_ms),
          format("%.0f", r.blob_bytes / 1024.0),
          format("%.2f", r.bake_seconds)};
}

// ---- scene mode: a preset's objects baked per setting, its placements shaded by the runtime ----

// The knobs of the scene sweep, in the order of a setting's key: a setting's bake depends on
// every knob but the last two (bits only quantises, bounces only shades), so settings that share
// a bake are neighbours in the sweep.
enum Knob : std::size_t {
  kOrder,
  kTerms,
  kRays,
  kOofShells,
  kOofFace,
  kSrfShells,
  kSrfFace,
  kBasis,
  kBits,
  kBounces,
  kKnobCount
};

struct KnobInfo {
  const char* sweep;   // the sweep's name in the sweeps column
  const char* column;  // CSV column
  const char* title;   // markdown column
  std::uint32_t min, max;
};

const std::array<KnobInfo, kKnobCount> kKnobs = {{
    {"order", "order", "order", 2, 6},
    {"terms", "terms", "K", 1, 8},
    {"rays", "rays", "rays", 1, 65536},
    {"oof_shells", "oof_shells", "OOF shells", 1, 64},
    {"oof_face", "oof_face", "OOF face", 1, 64},
    {"srf_shells", "srf_shells", "SRF shells", 1, 256},
    {"srf_face", "srf_face", "SRF face", 1, 64},
    {"basis", "basis", "N", 1, 256},
    {"bits", "bits", "bits", 8, 16},
    {"bounces", "bounces", "bounces", 0, PRT_SHADOWFIELD_MAX_BOUNCES},
}};

using KnobValues = std::array<std::uint32_t, kKnobCount>;

struct SceneSetting {
  KnobValues knobs{};
  std::string sweeps;
  std::uint32_t operator[](Knob k) const { return knobs[k]; }
};

// The scene sweep's own options (the order, terms, rays and bits sweeps are the object mode's).
struct SceneSweepOptions {
  std::string shared = "../shared";
  std::vector<std::string> times{"0", "4"};
  std::vector<std::uint32_t> oof_shells{4, 8, 16, 24}, oof_faces{4, 8, 16, 24},
      srf_shells{2, 4, 8, 16}, srf_faces{4, 8, 12}, basis{4, 8, 16, 32}, bounces{0, 1, 2, 3};
  std::uint32_t base_oof_shells = 16, base_oof_face = 16, base_srf_shells = 8, base_srf_face = 8,
                base_basis = 16, base_bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES, lights = 256;
  // The scene mode's rays when --rays / --base-rays are not given: the bake's default.
  std::uint32_t default_rays = 1024;
};

std::vector<float> parse_times(const std::vector<std::string>& texts) {
  std::vector<float> times;
  for (const std::string& text : texts) {
    char* end = nullptr;
    const float t = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(t))
      throw Error("--times: '" + text + "' is not a finite number of seconds");
    times.push_back(t);
  }
  if (times.empty()) throw Error("--times: give at least one time");
  return times;
}

// One knob at a time around the base; a setting in several sweeps is measured once.
std::vector<SceneSetting> scene_sweep_settings(
    const std::array<std::vector<std::uint32_t>, kKnobCount>& values, const KnobValues& base,
    bool glossy) {
  std::map<KnobValues, std::string> sweeps;
  for (std::size_t k = 0; k < kKnobCount; ++k) {
    if (k == kTerms && !glossy) continue;
    for (const std::uint32_t value : values[k]) {
      KnobValues knobs = base;
      knobs[k] = value;
      std::string& names = sweeps[knobs];
      const std::string name = kKnobs[k].sweep;
      if (("+" + names + "+").find("+" + name + "+") != std::string::npos) continue;
      names += (names.empty() ? "" : "+") + name;
    }
  }
  std::vector<SceneSetting> settings;
  for (const auto& [knobs, names] : sweeps) settings.push_back({knobs, names});
  return settings;
}

// Milliseconds of this thread's CPU time: what a frame costs, whatever else the machine runs.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

// Median thread-CPU milliseconds of `frames` calls after a warm-up call; -1 when the warm-up
// says the backend is not available.
double median_cpu_ms(int frames, const std::string& what,
                     const std::function<prt_result()>& frame) {
  const prt_result first = frame();
  if (first == PRT_ERROR_UNSUPPORTED_BACKEND) return -1.0;
  check_runtime(first, what);
  std::vector<double> ms;
  for (int f = 0; f < frames; ++f) {
    const double start = thread_cpu_ms();
    check_runtime(frame(), what);
    ms.push_back(thread_cpu_ms() - start);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

// Counts the bytes a runtime context holds.
struct ByteCounter {
  std::size_t live = 0;
  static void* allocate(void* user, std::size_t size, std::size_t align) {
    static_cast<ByteCounter*>(user)->live += size;
    return std::aligned_alloc(align, (size + align - 1) / align * align);
  }
  static void release(void* user, void* pointer, std::size_t size) {
    static_cast<ByteCounter*>(user)->live -= size;
    std::free(pointer);
  }
};

prt_shadowfield_transform placement_transform(const ShadowfieldPlacement& p) {
  prt_shadowfield_transform t =
      shadowfield_transform(Instance::rotation_of(p.rotation), p.translation);
  t.scale = p.scale;
  return t;
}

// A preset's blobs loaded borrowed (as a game that maps its files) into one runtime scene on a
// counting context, so what the runtime holds is known.
class CountedScene {
 public:
  CountedScene(const ShadowfieldSceneDescription& description,
               const std::vector<std::vector<std::uint8_t>>& blobs)
      : description_(description) {
    const prt_allocator allocator{&ByteCounter::allocate, &ByteCounter::release, &counter_};
    prt_context_desc desc{};
    desc.struct_size = sizeof desc;
    desc.allocator = &allocator;
    check_runtime(prt_context_create(&desc, &context_), "prt_context_create");
    check_runtime(prt_shadowfield_scene_create(
                      context_, std::uint32_t(description.instances.size()), &scene_),
                  "prt_shadowfield_scene_create");
    for (std::size_t o = 0; o < blobs.size(); ++o) {
      // Aligned as malloc aligns, alive as long as the asset.
      storage_.emplace_back((blobs[o].size() + sizeof(std::max_align_t) - 1) /
                            sizeof(std::max_align_t));
      std::memcpy(storage_.back().data(), blobs[o].data(), blobs[o].size());
      prt_asset* asset = nullptr;
      check_runtime(prt_asset_load_memory_borrowed(context_, storage_.back().data(),
                                                   blobs[o].size(), PRT_VALIDATE_QUICK, &asset),
                    "loading the blob of " + description.objects[o].name);
      assets_.push_back(asset);
      std::uint32_t id = 0;
      check_runtime(prt_shadowfield_scene_add_object(scene_, asset, &id),
                    "adding object " + description.objects[o].name);
    }
    for (const ShadowfieldInstance& instance : description.instances) {
      const prt_shadowfield_transform t = placement_transform(instance.path.at(0.0f));
      std::uint32_t id = 0;
      check_runtime(
          prt_shadowfield_scene_add_instance(scene_, std::uint32_t(instance.object), &t, &id),
          "adding an instance of " + description.objects[instance.object].name);
    }
  }
  CountedScene(const CountedScene&) = delete;
  CountedScene& operator=(const CountedScene&) = delete;
  ~CountedScene() {
    if (scene_) prt_shadowfield_scene_destroy(scene_);
    for (prt_asset* asset : assets_) prt_asset_destroy(asset);
    if (context_) prt_context_destroy(context_);
  }

  void place(float time) {
    for (std::size_t i = 0; i < description_.instances.size(); ++i) {
      const prt_shadowfield_transform t =
          placement_transform(description_.instances[i].path.at(time));
      check_runtime(prt_shadowfield_scene_set_transform(scene_, std::uint32_t(i), &t),
                    "prt_shadowfield_scene_set_transform");
    }
  }

  prt_result shade(const std::vector<float>& light, const glm::vec3& eye, std::uint32_t bounces,
                   prt_backend backend) {
    prt_shadowfield_settings settings{};
    settings.struct_size = sizeof settings;
    settings.bounces = bounces;
    settings.backend = backend;
    const float eye_xyz[3] = {eye.x, eye.y, eye.z};
    const std::vector<float*> no_output(description_.instances.size(), nullptr);
    return prt_shadowfield_shade(scene_, light.data(), eye_xyz, &settings, no_output.data());
  }

  // Every instance's outgoing radiance through `pass`, instances in order.
  std::vector<glm::vec3> output(std::uint32_t pass) const {
    std::vector<glm::vec3> radiance;
    for (std::uint32_t i = 0; i < prt_shadowfield_scene_instance_count(scene_); ++i) {
      const std::uint32_t count = prt_shadowfield_instance_vertex_count(scene_, i);
      std::vector<float> rgb(std::size_t(count) * 3);
      check_runtime(prt_shadowfield_output(scene_, i, pass, 0, count, rgb.data()),
                    "prt_shadowfield_output");
      const std::vector<glm::vec3> v = as_vec3(rgb);
      radiance.insert(radiance.end(), v.begin(), v.end());
    }
    return radiance;
  }

  std::size_t runtime_bytes() const { return counter_.live; }

 private:
  const ShadowfieldSceneDescription& description_;
  ByteCounter counter_;
  prt_context* context_ = nullptr;
  prt_shadowfield_scene* scene_ = nullptr;
  std::vector<std::vector<std::max_align_t>> storage_;
  std::vector<prt_asset*> assets_;
};

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const char c : text) hash = (hash ^ std::uint8_t(c)) * 1099511628211ull;
  return hash;
}

std::vector<std::uint8_t> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void write_file_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    check_written(out, temporary);
  }
  std::filesystem::rename(temporary, path);
}

struct SceneRow {
  std::string map;
  const SceneSetting* setting = nullptr;
  float time = 0.0f;
  double error = 0.0, bias = 0.0, ref_noise = 0.0;
  std::vector<double> object_error;  // per object of the description
  double simd_ms = -1.0, scalar_ms = -1.0, bake_seconds = 0.0;
  std::size_t runtime_bytes = 0, blob_bytes = 0;
  std::vector<glm::vec3> radiance, expected;  // for the error pooled over times
};

double pooled_error(const std::vector<const SceneRow*>& rows) {
  std::vector<glm::vec3> x, ref;
  for (const SceneRow* r : rows) {
    x.insert(x.end(), r->radiance.begin(), r->radiance.end());
    ref.insert(ref.end(), r->expected.begin(), r->expected.end());
  }
  return io::relative_rmse(x, ref);
}

// The trade on a preset: each setting bakes every object (blobs cached by settings), the
// placements at the given times are shaded on the runtime and compared with the reference of
// the same placement and bounce count, rendered once and cached.
class SceneSweep {
 public:
  SceneSweep(std::string preset, const SceneSweepOptions& options, const SfTradeSettings& object,
             bool rays_given, bool base_rays_given)
      : preset_(std::move(preset)), o_(options), object_(object) {
    times_ = parse_times(o_.times);
    description_ = make_shadowfield_scene(preset_, o_.shared);
    values_[kOrder] = object.orders;
    values_[kTerms] = object.terms;
    values_[kRays] = rays_given ? object.rays : std::vector<std::uint32_t>{};
    values_[kOofShells] = o_.oof_shells;
    values_[kOofFace] = o_.oof_faces;
    values_[kSrfShells] = o_.srf_shells;
    values_[kSrfFace] = o_.srf_faces;
    values_[kBasis] = o_.basis;
    for (const int bits : object.bits) values_[kBits].push_back(std::uint32_t(bits));
    values_[kBounces] = o_.bounces;
    base_ = {
        object.base_order,  object.base_terms, base_rays_given ? object.base_rays : o_.default_rays,
        o_.base_oof_shells, o_.base_oof_face,  o_.base_srf_shells,
        o_.base_srf_face,   o_.base_basis,     std::uint32_t(object.base_bits),
        o_.base_bounces};
    bool glossy = false;
    for (const ShadowfieldSceneObject& o : description_.objects)
      glossy = glossy || o.material.model != ShadowfieldBrdfModel::Diffuse;
    settings_ = scene_sweep_settings(values_, base_, glossy);
  }

  // The whole scene placed at the first time: what run_trade builds its ray scene of.
  Scene scene() const { return place_shadowfield_scene(description_, times_.front()).scene; }

  void prepare(const TradeInput& input, const Context& ctx) {
    std::uint32_t max_order = 0;
    std::set<std::uint32_t> bounces;
    for (const SceneSetting& s : settings_) {
      max_order = std::max(max_order, s[kOrder]);
      bounces.insert(s[kBounces]);
    }
    for (const std::string& env : input.envs) {
      Light light;
      light.name = env == "sky" || env == kShadowfieldBuiltinSky ? "sky" : stem(env);
      light.map = std::make_unique<io::EnvMap>(load_shadowfield_env(env, "", ctx));
      light.sh = project_env_sh(*light.map, max_order).to_float();
      for (std::size_t t = 0; t < times_.size(); ++t)
        for (const std::uint32_t b : bounces)
          light.references[{t, b}] = reference(light, t, b, input, ctx);
      lights_.push_back(std::move(light));
    }
  }

  void sweep(const TradeInput& input, const Context& ctx) {
    std::vector<SceneRow> rows;
    for (std::size_t i = 0; i < settings_.size(); ++i) {
      const SceneSetting& s = settings_[i];
      std::string text;
      for (std::size_t k = 0; k < kKnobCount; ++k)
        text += format("%s%s %u", k ? ", " : "", kKnobs[k].title, s.knobs[k]);
      ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings_.size()) + " (" +
               s.sweeps + "): " + text);
      measure_setting(s, input, ctx, rows);
    }
    write_tables(rows, input, ctx.thread_count());
  }

 private:
  struct Light {
    std::string name;
    std::unique_ptr<io::EnvMap> map;
    std::vector<float> sh;  // at the largest order swept, the runtime's layout
    std::map<std::pair<std::size_t, std::uint32_t>, Reference> references;  // (time, bounces)
  };

  Reference reference(const Light& light, std::size_t time, std::uint32_t bounces,
                      const TradeInput& input, const Context& ctx) const {
    const std::string key =
        format("shadowfield_%s_%s_t%g_b%u_spp%u_seed%u", preset_.c_str(), light.name.c_str(),
               double(times_[time]), bounces, input.ref_spp, input.seed);
    const std::string npy = input.cache_dir + "/" + key + ".npy", noise_file = npy + ".noise";
    Reference ref;
    std::ifstream noise_in(noise_file);
    if (noise_in >> ref.noise && std::filesystem::exists(npy)) {
      ref.radiance = io::read_npy_vec3(npy);
      if (ref.radiance.size() == description_.instanced_vertex_count()) {
        ctx.info("reference " + key + ": from the cache");
        return ref;
      }
    }
    ctx.info("reference " + key + ": rendering");
    VertexRadiance result =
        render_shadowfield_reference(description_, *light.map, times_[time], int(bounces),
                                     input.ref_spp, description_.camera.eye, ctx, input.seed);
    io::write_npy_vec3(npy, result.radiance);
    std::ofstream noise_out(noise_file);
    noise_out.precision(17);
    noise_out << result.relative_rmse << "\n";
    check_written(noise_out, noise_file);
    ref.radiance = std::move(result.radiance);
    ref.noise = result.relative_rmse;
    return ref;
  }

  ShadowfieldBakeSettings bake_settings(const SceneSetting& s, const TradeInput& input) const {
    ShadowfieldBakeSettings b;
    b.fields.order = s[kOrder];
    b.fields.oof_shells = s[kOofShells];
    b.fields.oof_face_size = s[kOofFace];
    b.fields.field_directions = b.fields.transfer_rays = b.srf.directions = s[kRays];
    b.fields.seed = b.srf.seed = input.seed;
    b.srf.shells = s[kSrfShells];
    b.srf.face_size = s[kSrfFace];
    b.basis.size = s[kBasis];
    b.basis.lights = o_.lights;
    b.brdf.terms = s[kTerms];
    b.brdf.grid_size = object_.bake.brdf.grid_size;
    b.bits = int(s[kBits]);
    return b;
  }

  // What an object's bake depends on (quantisation apart): the settings it reads and its mesh.
  std::string bake_key(const ShadowfieldBakeSettings& b, std::size_t index) const {
    const ShadowfieldSceneObject& o = description_.objects[index];
    const bool glossy = o.material.model != ShadowfieldBrdfModel::Diffuse;
    std::ostringstream text;
    const ShadowfieldFieldSettings& f = b.fields;
    text << f.order << ' ' << f.oof_shells << ' ' << f.inner << ' ' << f.outer << ' '
         << f.oof_face_size << ' ' << f.field_directions << ' ' << f.transfer_rays << ' ' << f.seed
         << ' ' << b.basis.size << ' ' << b.basis.lights << ' ' << b.basis.light_distance << ' '
         << b.srf.shells << ' ' << b.srf.face_size << ' ' << b.srf.inner << ' ' << b.srf.outer
         << ' ' << b.srf.directions << ' ' << b.srf.seed << ' ' << (glossy ? b.brdf.terms : 0)
         << ' ' << (glossy ? b.brdf.grid_size : 0) << ' ' << o.name << ' ' << int(o.material.model)
         << ' ' << o.mesh.vertex_count();
    for (const Mesh& mesh : o.mesh.meshes) {
      text << ' ' << mesh.indices.size();
      for (std::size_t e = 0; e < mesh.positions.size(); e += 97)
        text << ' ' << mesh.positions[e].x;
    }
    return format("%016llx", static_cast<unsigned long long>(fnv1a(text.str())));
  }

  // The object's blob at these settings: from the cache folder, else baked (or quantised from
  // the last bake with the same settings) and cached. `seconds`: the bake's time, when it ran
  // now or was recorded beside the cached blob.
  std::vector<std::uint8_t> object_blob(const ShadowfieldBakeSettings& b, std::size_t index,
                                        const TradeInput& input, const Context& ctx,
                                        double* seconds) {
    const ShadowfieldSceneObject& o = description_.objects[index];
    const std::string key = bake_key(b, index);
    const std::string path = input.cache_dir + "/shadowfield_" + preset_ + "_" + o.name + "_" +
                             key + "_" + std::to_string(b.bits) + "bit.prtk";
    const std::string seconds_file = path + ".seconds";
    if (std::filesystem::exists(path)) {
      std::ifstream in(seconds_file);
      if (!(in >> *seconds)) *seconds = 0.0;
      return read_file_bytes(path);
    }
    auto baked = baked_.find(key);
    if (baked == baked_.end()) {
      if (baked_.size() >= description_.objects.size()) baked_.clear();  // the last setting's
      ctx.info("  baking " + o.name);
      const auto start = std::chrono::steady_clock::now();
      ShadowfieldBakeResult result =
          bake_shadowfield_object(o.mesh, make_shadowfield_material(o.material, b.brdf), b, ctx);
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      baked = baked_.emplace(key, Baked{std::move(result.object), elapsed}).first;
    }
    *seconds = baked->second.seconds;
    const std::vector<std::uint8_t> blob = shadowfield_blob_of(
        baked->second.object, b.bits, "prtkit shadowfield trade: " + preset_ + ", " + o.name);
    write_file_bytes(path, blob);
    std::ofstream out(seconds_file);
    out << *seconds << "\n";
    check_written(out, seconds_file);
    return blob;
  }

  void measure_setting(const SceneSetting& s, const TradeInput& input, const Context& ctx,
                       std::vector<SceneRow>& rows) {
    const ShadowfieldBakeSettings b = bake_settings(s, input);
    check_shadowfield_bake_settings(b);
    std::vector<std::vector<std::uint8_t>> blobs;
    std::size_t blob_bytes = 0;
    double bake_seconds = 0.0;
    for (std::size_t o = 0; o < description_.objects.size(); ++o) {
      double seconds = 0.0;
      blobs.push_back(object_blob(b, o, input, ctx, &seconds));
      blob_bytes += blobs.back().size();
      bake_seconds += seconds;
    }
    CountedScene runtime(description_, blobs);
    const glm::vec3 eye = description_.camera.eye;
    const std::size_t light_floats = std::size_t(s[kOrder]) * s[kOrder] * 3;
    for (const Light& light : lights_) {
      const std::vector<float> l(light.sh.begin(), light.sh.begin() + light_floats);
      for (std::size_t t = 0; t < times_.size(); ++t) {
        runtime.place(times_[t]);
        SceneRow row;
        row.scalar_ms = median_cpu_ms(input.frames, "prt_shadowfield_shade (scalar)", [&] {
          return runtime.shade(l, eye, s[kBounces], PRT_BACKEND_CPU);
        });
        const std::vector<glm::vec3> scalar = runtime.output(s[kBounces]);
        row.simd_ms = median_cpu_ms(input.frames, "prt_shadowfield_shade (SIMD)", [&] {
          return runtime.shade(l, eye, s[kBounces], PRT_BACKEND_SIMD);
        });
        // The error of what a game would run: SIMD where the machine has it.
        row.radiance = row.simd_ms >= 0.0 ? runtime.output(s[kBounces]) : scalar;
        const Reference& ref = light.references.at({t, s[kBounces]});
        row.expected = ref.radiance;
        row.map = light.name;
        row.setting = &s;
        row.time = times_[t];
        row.error = io::relative_rmse(row.radiance, row.expected);
        row.bias = mean_bias(row.radiance, row.expected);
        row.ref_noise = ref.noise;
        const PlacedScene placed = place_shadowfield_scene(description_, times_[t]);
        for (std::size_t o = 0; o < description_.objects.size(); ++o) {
          std::vector<glm::vec3> ours, theirs;
          for (std::size_t i = 0; i < description_.instances.size(); ++i) {
            if (description_.instances[i].object != o) continue;
            const auto first = std::ptrdiff_t(placed.first_vertex[i]),
                       last = std::ptrdiff_t(placed.first_vertex[i + 1]);
            ours.insert(ours.end(), row.radiance.begin() + first, row.radiance.begin() + last);
            theirs.insert(theirs.end(), row.expected.begin() + first, row.expected.begin() + last);
          }
          row.object_error.push_back(ours.empty() ? 0.0 : io::relative_rmse(ours, theirs));
        }
        row.runtime_bytes = runtime.runtime_bytes();
        row.blob_bytes = blob_bytes;
        row.bake_seconds = bake_seconds;
        ctx.info("  " + light.name +
                 format(", t = %g s: error %.2f %%, SIMD %.2f ms, scalar %.2f ms CPU",
                        double(row.time), 100 * row.error, row.simd_ms, row.scalar_ms));
        rows.push_back(std::move(row));
      }
    }
  }

  std::string object_errors(const std::vector<double>& errors) const {
    std::string text;
    for (std::size_t o = 0; o < errors.size(); ++o)
      text += format("%s%s:%.4g", o ? ";" : "", description_.objects[o].name.c_str(), errors[o]);
    return text;
  }

  void write_tables(const std::vector<SceneRow>& rows, const TradeInput& input,
                    unsigned threads) const {
    const std::string csv_path = input.out_dir + "/trade.csv";
    std::ofstream csv(csv_path);
    std::vector<std::string> header = {"scene", "map", "sweeps"};
    for (const KnobInfo& k : kKnobs) header.push_back(k.column);
    for (const char* c : {"time_s", "vertices", "rel_rmse", "bias", "ref_noise",
                          "rel_rmse_noise_removed", "ref_spp", "object_rel_rmse", "simd_cpu_ms",
                          "scalar_cpu_ms", "runtime_bytes", "blob_bytes", "bake_seconds"})
      header.push_back(c);
    write_csv_row(csv, header);
    for (const SceneRow& r : rows) {
      std::vector<std::string> cells = {preset_, r.map, r.setting->sweeps};
      for (const std::uint32_t v : r.setting->knobs) cells.push_back(std::to_string(v));
      for (std::string cell :
           {format("%g", double(r.time)), std::to_string(description_.instanced_vertex_count()),
            format("%.6g", r.error), format("%.6g", r.bias), format("%.6g", r.ref_noise),
            format("%.6g", noise_removed(r.error, r.ref_noise)), std::to_string(input.ref_spp),
            object_errors(r.object_error), ms_text(r.simd_ms), ms_text(r.scalar_ms),
            std::to_string(r.runtime_bytes), std::to_string(r.blob_bytes),
            format("%.4g", r.bake_seconds)})
        cells.push_back(std::move(cell));
      write_csv_row(csv, cells);
    }
    check_written(csv, csv_path);

    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    md << "# Technique shadowfield: the trade on the scene preset `" << preset_
       << "` (prt-bake trade shadowfield)\n\n";
    md << "Preset `" << preset_ << "`: " << description_.objects.size() << " objects (";
    for (std::size_t o = 0; o < description_.objects.size(); ++o)
      md << (o ? ", " : "") << description_.objects[o].name;
    md << "), " << description_.instances.size() << " instances, "
       << description_.instanced_vertex_count() << " instanced vertices; placements at t = ";
    for (std::size_t t = 0; t < times_.size(); ++t) md << (t ? ", " : "") << times_[t];
    md << " s; eye at the preset's camera.\n\n";
    md << "One knob at a time around the base: ";
    for (std::size_t k = 0; k < kKnobCount; ++k)
      md << (k ? ", " : "") << kKnobs[k].title << " " << base_[k];
    md << ". Swept: ";
    bool first = true;
    for (std::size_t k = 0; k < kKnobCount; ++k) {
      if (values_[k].empty()) continue;
      md << (first ? "" : "; ") << kKnobs[k].title << " " << joined(values_[k]);
      first = false;
    }
    md << ". Basis training lights " << o_.lights << ", BRDF grid " << object_.bake.brdf.grid_size
       << ". Reference: " << input.ref_spp << " samples per vertex, seed " << input.seed
       << ", the same placement, eye and bounce count, the exact BRDFs.\n\n";
    md << "Error: relative RMSE of per-vertex RGB radiance over every instanced vertex and the "
          "placements (per object: over its instances' vertices); bias: (sum of runtime - "
          "reference) / sum of reference. The runtime's radiance is the SIMD backend's. CPU ms: "
          "median thread CPU time of "
       << input.frames
       << " whole frames (prt_shadowfield_shade on one thread, placements averaged). Runtime MB: "
          "what the runtime context holds with the blobs loaded borrowed, after a frame; baked "
          "MB: the blobs' bytes; bake s: the objects' bake time (when cached, as recorded).\n\n";
    md << "Machine: " << machine_description(threads) << ".\n";
    for (const Light& light : lights_) {
      md << "\n## " << light.name << "\n\n";
      std::vector<Column> columns = {{"sweep", false}};
      for (const KnobInfo& k : kKnobs) columns.push_back({k.title});
      columns.push_back({"error %"});
      columns.push_back({"bias %"});
      columns.push_back({"ref noise %"});
      for (const ShadowfieldSceneObject& o : description_.objects)
        columns.push_back({o.name + " error %"});
      for (const char* c : {"SIMD CPU ms", "scalar CPU ms", "runtime MB", "baked MB", "bake s"})
        columns.push_back({c});
      write_markdown_header(md, columns);
      // Sweep by sweep, each knob's values in order, the base among them (so in every block).
      std::vector<std::pair<std::size_t, const SceneSetting*>> blocks;
      for (std::size_t k = 0; k < kKnobCount; ++k) {
        std::vector<const SceneSetting*> of_knob;
        for (const SceneSetting& s : settings_) {
          if (("+" + s.sweeps + "+").find(std::string("+") + kKnobs[k].sweep + "+") !=
              std::string::npos)
            of_knob.push_back(&s);
        }
        std::sort(of_knob.begin(), of_knob.end(),
                  [&](const SceneSetting* a, const SceneSetting* b) {
                    return a->knobs[k] < b->knobs[k];
                  });
        for (const SceneSetting* s : of_knob) blocks.emplace_back(k, s);
      }
      for (const auto& [knob, setting] : blocks) {
        const SceneSetting& s = *setting;
        std::vector<const SceneRow*> of;
        for (const SceneRow& r : rows)
          if (r.setting == &s && r.map == light.name) of.push_back(&r);
        if (of.empty()) continue;
        std::vector<std::string> cells = {std::string(kKnobs[knob].sweep) +
                                          (s.knobs == base_ ? " (base)" : "")};
        for (const std::uint32_t v : s.knobs) cells.push_back(std::to_string(v));
        double bias = 0.0, noise = 0.0, simd = 0.0, scalar = 0.0;
        std::vector<double> objects(description_.objects.size(), 0.0);
        for (const SceneRow* r : of) {
          bias += r->bias / double(of.size());
          noise = std::max(noise, r->ref_noise);
          simd += r->simd_ms / double(of.size());
          scalar += r->scalar_ms / double(of.size());
        }
        for (std::size_t o = 0; o < objects.size(); ++o) {
          double squares = 0.0;
          for (const SceneRow* r : of) squares += r->object_error[o] * r->object_error[o];
          objects[o] = std::sqrt(squares / double(of.size()));
        }
        cells.push_back(format("%.2f", 100 * pooled_error(of)));
        cells.push_back(format("%+.2f", 100 * bias));
        cells.push_back(format("%.2f", 100 * noise));
        for (const double e : objects) cells.push_back(format("%.2f", 100 * e));
        cells.push_back(of.front()->simd_ms < 0.0 ? "n/a" : format("%.2f", simd));
        cells.push_back(format("%.2f", scalar));
        cells.push_back(format("%.1f", 1e-6 * double(of.front()->runtime_bytes)));
        cells.push_back(format("%.2f", 1e-6 * double(of.front()->blob_bytes)));
        cells.push_back(format("%.1f", of.front()->bake_seconds));
        write_markdown_row(md, cells);
      }
    }
    check_written(md, md_path);
  }

  struct Baked {
    ShadowfieldObject object;
    double seconds = 0.0;
  };

  std::string preset_;
  SceneSweepOptions o_;
  SfTradeSettings object_;
  std::vector<float> times_;
  ShadowfieldSceneDescription description_;
  std::array<std::vector<std::uint32_t>, kKnobCount> values_;
  KnobValues base_{};
  std::vector<SceneSetting> settings_;
  std::vector<Light> lights_;
  std::map<std::string, Baked> baked_;  // the last setting's float objects, by bake key
};

// The options only the scene mode reads.
const std::set<std::string> kSceneOnly = {
    "--shared",          "--times",         "--oof-shells", "--oof-faces",       "--srf-shells",
    "--srf-faces",       "--basis-sizes",   "--bounces",    "--base-oof-shells", "--base-oof-face",
    "--base-srf-shells", "--base-srf-face", "--base-basis", "--base-bounces",    "--lights"};

class ShadowfieldTrade final : public TechniqueTrade {
 public:
  ShadowfieldTrade() {
    // Small fields by default: the trade measures the object alone (no OOF or SRF read).
    o_.bake.fields.oof_shells = 4;
    o_.bake.fields.oof_face_size = 4;
    o_.bake.fields.field_directions = 256;
    o_.bake.srf.shells = 2;
    o_.bake.srf.face_size = 2;
    o_.bake.srf.directions = 256;
    o_.bake.basis.size = 4;
    o_.bake.basis.lights = 32;
  }

  TradeInput defaults() const override {
    TradeInput input;
    input.ref_spp = 1024;
    input.frames = 10;
    return input;
  }

  OptionList options() override {
    OptionList list;
    // Every option records whether it was given: the modes refuse each other's.
    auto add = [&](const std::string& name, auto* value, const std::string& help) -> OptionSpec& {
      return list.add(name, value, help).record_given(&given_[name]);
    };
    add("--brdf", &o_.brdf, "The object's BRDF: lambert, phong:N[,ks[,kd]], ggx:A[,F0]");
    add("--orders", &o_.orders, "SH orders of the order sweep (2..6)");
    add("--terms", &o_.terms, "BRDF terms K of the terms sweep (glossy only)");
    add("--rays", &o_.rays, "Transfer rays per vertex of the rays sweep");
    add("--bits", &o_.bits, "Quantisation bits of the bits sweep (8, 16)");
    add("--base-order", &o_.base_order, "Order of the other sweeps").range(2, 6);
    add("--base-terms", &o_.base_terms, "Terms of the other sweeps").range(1, 8);
    add("--base-rays", &o_.base_rays, "Transfer rays of the other sweeps").range(1, 65536);
    add("--base-bits", &o_.base_bits, "Bits of the other sweeps").choices({8, 16});
    add("--rotations", &o_.rotations, "Turns of the object about +Y, over a full turn")
        .range(1, 64);
    add("--brdf-grid", &o_.bake.brdf.grid_size, "The BRDF table's grid").range(4, 64);
    // Scene mode (SCENE names a preset): the fields, the basis and the bounces swept as well.
    add("--shared", &s_.shared, "Scene mode: the shared assets folder");
    add("--times", &s_.times, "Scene mode: seconds on the paths of the placements shaded");
    add("--oof-shells", &s_.oof_shells, "Scene mode: OOF shells of the oof_shells sweep");
    add("--oof-faces", &s_.oof_faces,
        "Scene mode: OOF cube face sizes (6 F^2 points a shell) of the oof_face sweep");
    add("--srf-shells", &s_.srf_shells, "Scene mode: SRF shells of the srf_shells sweep");
    add("--srf-faces", &s_.srf_faces, "Scene mode: SRF cube face sizes of the srf_face sweep");
    add("--basis-sizes", &s_.basis, "Scene mode: basis sizes N of the basis sweep");
    add("--bounces", &s_.bounces, "Scene mode: bounce counts of the bounces sweep");
    add("--base-oof-shells", &s_.base_oof_shells, "Scene mode: OOF shells of the others")
        .range(1, 64);
    add("--base-oof-face", &s_.base_oof_face, "Scene mode: OOF face size of the others")
        .range(1, 64);
    add("--base-srf-shells", &s_.base_srf_shells, "Scene mode: SRF shells of the others")
        .range(1, 256);
    add("--base-srf-face", &s_.base_srf_face, "Scene mode: SRF face size of the others")
        .range(1, 64);
    add("--base-basis", &s_.base_basis, "Scene mode: basis size N of the others").range(1, 256);
    add("--base-bounces", &s_.base_bounces, "Scene mode: bounces of the others")
        .range(0, PRT_SHADOWFIELD_MAX_BOUNCES);
    add("--lights", &s_.lights, "Scene mode: the basis's training lights").range(1, 65536);
    return list;
  }

  void check(const TradeInput& input) const override {
    check_settings(o_);
    const bool scene_mode = is_preset(input.scene);
    for (const auto& [name, given] : given_) {
      if (!given) continue;
      const bool object_only = name == "--brdf" || name == "--rotations";
      if (scene_mode && object_only)
        throw Error(name + ": a scene preset has its own placements and materials");
      if (!scene_mode && kSceneOnly.count(name))
        throw Error(name + ": only with a scene preset (" + preset_list() + ") as SCENE");
    }
    if (!scene_mode) return;
    if (!input.albedo.empty()) throw Error("--albedo: a scene preset has its own materials");
    parse_times(s_.times);
    struct SceneList {
      const char* flag;
      const std::vector<std::uint32_t>* values;
      Knob knob;
    };
    for (const SceneList& list : {SceneList{"--oof-shells", &s_.oof_shells, kOofShells},
                                  SceneList{"--oof-faces", &s_.oof_faces, kOofFace},
                                  SceneList{"--srf-shells", &s_.srf_shells, kSrfShells},
                                  SceneList{"--srf-faces", &s_.srf_faces, kSrfFace},
                                  SceneList{"--basis-sizes", &s_.basis, kBasis},
                                  SceneList{"--bounces", &s_.bounces, kBounces}}) {
      const KnobInfo& knob = kKnobs[list.knob];
      for (const std::uint32_t v : *list.values) {
        if (v < knob.min || v > knob.max)
          throw Error(std::string(list.flag) + ": " + std::to_string(v) + " is outside " +
                      std::to_string(knob.min) + ".." + std::to_string(knob.max));
      }
    }
  }

  Scene load_scene(const TradeInput& input, const Context& ctx) override {
    if (!is_preset(input.scene)) return TechniqueTrade::load_scene(input, ctx);
    scene_ =
        std::make_unique<SceneSweep>(input.scene, s_, o_, given("--rays"), given("--base-rays"));
    return scene_->scene();
  }

  void prepare(const Scene& scene, const TradeInput& input, const Context& ctx) override {
    if (scene_) {
      scene_->prepare(input, ctx);
      return;
    }
    surface_ = parse_brdf_option(o_.brdf);
    settings_ = sweep_settings(o_, surface_.model != SurfaceBrdf::Model::Lambert);
    std::uint32_t max_order = 0;
    for (const Setting& s : settings_) max_order = std::max(max_order, s.order);
    std::vector<glm::vec3> positions;
    for (const Mesh& mesh : scene.meshes)
      positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
    sphere_ = bounding_sphere(positions);
    for (std::uint32_t i = 0; i < o_.rotations; ++i)
      facing_.push_back(facing_eye(scene,
                                   turned_instance(turn_degrees(i, o_.rotations), sphere_.centre),
                                   trade_eye(sphere_)));
    for (const std::string& path : input.envs) {
      lights_.push_back(load_sh_light(path, max_order, ctx));
      for (std::uint32_t i = 0; i < o_.rotations; ++i)
        references_[{lights_.back().name, i}] = reference(scene, lights_.back(), i, input, ctx);
    }
  }

  void sweep(const Scene& scene, const EmbreeScene&, const TradeInput& input,
             const Context& ctx) override {
    if (scene_) {
      scene_->sweep(input, ctx);
      return;
    }
    std::vector<Row> rows;
    for (std::size_t i = 0; i < settings_.size(); ++i) {
      const Setting& s = settings_[i];
      ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings_.size()) +
               ": order " + std::to_string(s.order) + ", " + std::to_string(s.terms) + " terms, " +
               std::to_string(s.rays) + " rays, " + std::to_string(s.bits) + " bits");
      measure_setting(scene, s, input, ctx, rows);
    }
    write_tables(scene, rows, input, ctx.thread_count());
  }

 private:
  Reference reference(const Scene& scene, const ShLight& light, std::uint32_t rotation,
                      const TradeInput& input, const Context& ctx) const {
    std::string brdf_key = o_.brdf;
    std::replace(brdf_key.begin(), brdf_key.end(), ',', '-');
    std::replace(brdf_key.begin(), brdf_key.end(), ':', '-');
    std::string albedo_key = input.albedo.empty() ? "material" : input.albedo;
    std::replace(albedo_key.begin(), albedo_key.end(), ',', '-');
    const std::string key = stem(input.scene) + "_" + light.name + "_" + brdf_key + "_turn" +
                            std::to_string(rotation) + "of" + std::to_string(o_.rotations) +
                            "_spp" + std::to_string(input.ref_spp) + "_seed" +
                            std::to_string(input.seed) + "_albedo-" + albedo_key;
    const std::string npy = input.cache_dir + "/" + key + ".npy", noise_file = npy + ".noise";
    Reference ref;
    std::ifstream noise_in(noise_file);
    if (noise_in >> ref.noise && std::filesystem::exists(npy)) {
      ref.radiance = io::read_npy_vec3(npy);
      if (ref.radiance.size() == scene.vertex_count()) {
        ctx.info("reference " + key + ": from the cache");
        return ref;
      }
    }
    ctx.info("reference " + key + ": rendering");
    const PlacedScene placed = place_instances(
        {scene}, {turned_instance(turn_degrees(rotation, o_.rotations), sphere_.centre)});
    ReferenceSettings settings;
    settings.bounces = 0;
    settings.spp = input.ref_spp;
    settings.seed = input.seed;
    settings.brdf = surface_;
    if (!input.albedo.empty()) {
      settings.override_albedo = true;
      settings.albedo = parse_albedo(input.albedo);
    }
    const ReferenceRenderer renderer(placed.scene, *light.map, settings, ctx);
    VertexRadiance result = renderer.render_vertices(ctx, trade_eye(sphere_));
    io::write_npy_vec3(npy, result.radiance);
    std::ofstream noise_out(noise_file);
    noise_out.precision(17);
    noise_out << result.relative_rmse << "\n";
    if (!noise_out) throw Error(noise_file + ": cannot write");
    ref.radiance = std::move(result.radiance);
    ref.noise = result.relative_rmse;
    return ref;
  }

  void measure_setting(const Scene& scene, const Setting& s, const TradeInput& input,
                       const Context& ctx, std::vector<Row>& rows) const {
    ShadowfieldBakeSettings settings = o_.bake;
    settings.fields.order = s.order;
    settings.fields.transfer_rays = s.rays;
    settings.fields.seed = settings.srf.seed = input.seed;
    settings.brdf.terms = s.terms;
    settings.bits = s.bits;
    settings.basis.size = std::min<std::uint32_t>(
        settings.basis.size,
        std::uint32_t(std::min<std::size_t>(scene.vertex_count(),
                                            std::size_t(settings.basis.lights) * s.terms)));
    Scene object_scene = scene;
    if (!input.albedo.empty()) {
      Material material;
      material.base_color = glm::vec4(parse_albedo(input.albedo), 1.0f);
      object_scene.materials.push_back(material);
      for (Mesh& mesh : object_scene.meshes) mesh.material = int(object_scene.materials.size() - 1);
    }
    const auto start = std::chrono::steady_clock::now();
    const ShadowfieldBakeResult baked = bake_shadowfield_object(
        object_scene, shadowfield_material_of(surface_, settings.brdf), settings, ctx);
    const double bake_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::vector<std::uint8_t> blob =
        shadowfield_blob_of(baked.object, s.bits, "prtkit shadowfield trade: " + input.scene);
    const RuntimeAsset runtime = load_runtime_asset(blob);
    const glm::vec3 eye = trade_eye(sphere_);
    for (const ShLight& light : lights_) {
      const std::vector<float> l = light.at_order(s.order);
      for (std::uint32_t i = 0; i < o_.rotations; ++i) {
        const double degrees = turn_degrees(i, o_.rotations);
        const Instance placed = turned_instance(degrees, sphere_.centre);
        const prt_shadowfield_transform transform =
            shadowfield_transform(placed.rotation, placed.translation);
        LoneShadowfieldScene lone(runtime.asset.get(), transform);
        std::vector<float> shaded;
        Row row;
        row.cpu_ms = median_frame_ms(input.frames, "prt_shadowfield_shade", [&] {
          lone.shade(l, eye, &shaded);
          return PRT_OK;
        });
        const Reference& ref = references_.at({light.name, i});
        const std::vector<bool>& keep = facing_.at(i);
        const std::vector<glm::vec3> radiance = masked(as_vec3(shaded), keep);
        const std::vector<glm::vec3> expected = masked(ref.radiance, keep);
        row.map = light.name;
        row.sweeps = s.sweeps;
        row.setting = s;
        row.degrees = degrees;
        row.compared = radiance.size();
        row.error = io::relative_rmse(radiance, expected);
        row.bias = mean_bias(radiance, expected);
        row.ref_noise = ref.noise;
        row.blob_bytes = blob.size();
        row.bake_seconds = bake_seconds;
        ctx.info("  " + light.name + format(", turn %g: error %.3f %%", degrees, 100 * row.error));
        rows.push_back(row);
      }
    }
  }

  void write_tables(const Scene& scene, const std::vector<Row>& rows, const TradeInput& input,
                    unsigned threads) const {
    const std::string csv_path = input.out_dir + "/trade.csv";
    std::ofstream csv(csv_path);
    write_csv_row(csv, kCsvColumns);
    for (const Row& r : rows) write_csv_row(csv, csv_cells(r, o_, input, scene.vertex_count()));
    check_written(csv, csv_path);

    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    md << "# Technique shadowfield: speed versus accuracy (prt-bake trade shadowfield)\n\n";
    md << scene_description(input.scene, scene) << ", baked as one object, BRDF " << o_.brdf
       << "; albedo " << (input.albedo.empty() ? "from the materials" : input.albedo) << ".\n\n";
    md << "Sweeps: order " << joined(o_.orders) << ", BRDF terms " << joined(o_.terms)
       << " (glossy only), transfer rays " << joined(o_.rays) << ", bits 8/16, around order "
       << o_.base_order << ", " << o_.base_terms << " terms, " << o_.base_rays << " rays, "
       << o_.base_bits << " bits. The object alone, turned about +Y through its centre to "
       << o_.rotations
       << " angles, 0 bounces, eye fixed in front of it; only the vertices facing the eye are "
          "compared (the reference reflects nothing towards an eye behind a surface). Reference: "
       << input.ref_spp << " samples per vertex, the same placement, BRDF and eye; seed "
       << input.seed << ".\n\n";
    md << "Error = relative RMSE of per-vertex RGB radiance against the reference; bias = "
          "(sum of runtime - reference) / sum of reference. Shading time = median of "
       << input.frames
       << " frames of prt_shadowfield_shade over the object's vertices, one thread.\n\n";
    md << "Machine: " << machine_description(threads) << ".\n";
    for (const ShLight& light : lights_) {
      md << "\n## " << light.name << "\n\n";
      write_markdown_header(md, kMarkdownColumns);
      for (const Row& r : rows) {
        if (r.map == light.name) write_markdown_row(md, markdown_cells(r));
      }
    }
    check_written(md, md_path);
  }

  bool given(const std::string& name) const {
    const auto found = given_.find(name);
    return found != given_.end() && found->second;
  }

  static bool is_preset(const std::string& scene) {
    const std::vector<std::string> names = shadowfield_scene_names();
    return std::find(names.begin(), names.end(), scene) != names.end();
  }

  static std::string preset_list() {
    std::string text;
    for (const std::string& name : shadowfield_scene_names())
      text += (text.empty() ? "" : ", ") + name;
    return text;
  }

  SfTradeSettings o_;
  SceneSweepOptions s_;
  std::map<std::string, bool> given_;  // by option name: whether the command line gave it
  std::unique_ptr<SceneSweep> scene_;  // scene mode
  SurfaceBrdf surface_;
  BoundingSphere sphere_;
  std::vector<Setting> settings_;
  std::vector<ShLight> lights_;
  std::vector<std::vector<bool>> facing_;  // per turn
  std::map<std::pair<std::string, std::uint32_t>, Reference> references_;
};

}  // namespace

std::unique_ptr<TechniqueTrade> make_shadowfield_trade() {
  return std::make_unique<ShadowfieldTrade>();
}

}  // namespace prt::bake
