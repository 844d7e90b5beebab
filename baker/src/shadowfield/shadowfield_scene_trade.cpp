// SPDX-License-Identifier: MIT
// The scene mode of prt-bake trade shadowfield (docs/shadowfield/trade.md): SCENE a preset's name
// (teapot, bunny, room, procedural; docs/shadowfield/scenes.md). Every knob of the technique
// (order, K, rays, bits, OOF and SRF shells and points per shell, N, bounces), one at a time
// around a base. Each setting bakes every object (blobs cached by settings), shades the preset's
// placements at the given times on the runtime (SIMD and scalar, CPU time per frame, runtime
// memory) and compares them with the reference of the same placement and bounce count, rendered
// once and cached: it does not depend on the knobs.
#include "shadowfield_scene_trade.hpp"

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
#include <iomanip>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/instances.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/shadowfield/shadowfield_measure.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "shadowfield_technique.hpp"

namespace prt::bake::sf_trade {
namespace {

using namespace trade;

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

// "order 4, K 4, rays 1024, ...": a setting's knobs, for the log.
std::string knobs_text(const SceneSetting& s) {
  std::string text;
  for (std::size_t k = 0; k < kKnobCount; ++k)
    text += format("%s%s %u", k ? ", " : "", kKnobs[k].title, s.knobs[k]);
  return text;
}

bool in_sweep(const SceneSetting& s, const char* sweep) {
  return ("+" + s.sweeps + "+").find(std::string("+") + sweep + "+") != std::string::npos;
}

class ShadowfieldSceneSweep final : public SceneSweep {
 public:
  ShadowfieldSceneSweep(std::string preset, const SceneSweepOptions& options,
                        const SfTradeSettings& object, bool rays_given, bool base_rays_given)
      : preset_(std::move(preset)), o_(options), object_(object) {
    times_ = parse_times(o_.times);
    description_ = make_shadowfield_scene(preset_, o_.shared);
    values_ = swept_values(rays_given);
    base_ = base_values(base_rays_given);
    bool glossy = false;
    for (const ShadowfieldSceneObject& o : description_.objects)
      glossy = glossy || o.material.model != ShadowfieldBrdfModel::Diffuse;
    settings_ = scene_sweep_settings(values_, base_, glossy);
  }

  Scene scene() const override {
    return place_shadowfield_scene(description_, times_.front()).scene;
  }

  void prepare(const TradeInput& input, const Context& ctx) override {
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

  void sweep(const TradeInput& input, const Context& ctx) override {
    std::vector<SceneRow> rows;
    for (std::size_t i = 0; i < settings_.size(); ++i) {
      const SceneSetting& s = settings_[i];
      ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings_.size()) + " (" +
               s.sweeps + "): " + knobs_text(s));
      measure_setting(s, input, ctx, rows);
    }
    write_csv(rows, input);
    write_markdown(rows, input, ctx.thread_count());
  }

 private:
  struct Light {
    std::string name;
    std::unique_ptr<io::EnvMap> map;
    std::vector<float> sh;  // at the largest order swept, the runtime's layout
    std::map<std::pair<std::size_t, std::uint32_t>, Reference> references;  // (time, bounces)
  };

  struct Baked {
    ShadowfieldObject object;
    double seconds = 0.0;
  };

  // Every object's blob at one setting, their bytes and bake seconds summed.
  struct SettingBlobs {
    std::vector<std::vector<std::uint8_t>> blobs;
    std::size_t bytes = 0;
    double bake_seconds = 0.0;
  };

  std::array<std::vector<std::uint32_t>, kKnobCount> swept_values(bool rays_given) const {
    std::array<std::vector<std::uint32_t>, kKnobCount> values;
    values[kOrder] = object_.orders;
    values[kTerms] = object_.terms;
    values[kRays] = rays_given ? object_.rays : std::vector<std::uint32_t>{};
    values[kOofShells] = o_.oof_shells;
    values[kOofFace] = o_.oof_faces;
    values[kSrfShells] = o_.srf_shells;
    values[kSrfFace] = o_.srf_faces;
    values[kBasis] = o_.basis;
    for (const int bits : object_.bits) values[kBits].push_back(std::uint32_t(bits));
    values[kBounces] = o_.bounces;
    return values;
  }

  KnobValues base_values(bool base_rays_given) const {
    return {object_.base_order,
            object_.base_terms,
            base_rays_given ? object_.base_rays : o_.default_rays,
            o_.base_oof_shells,
            o_.base_oof_face,
            o_.base_srf_shells,
            o_.base_srf_face,
            o_.base_basis,
            std::uint32_t(object_.base_bits),
            o_.base_bounces};
  }

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
    const Baked& baked = baked_object(b, index, key, ctx);
    *seconds = baked.seconds;
    const std::vector<std::uint8_t> blob = shadowfield_blob_of(
        baked.object, b.bits, "prtkit shadowfield trade: " + preset_ + ", " + o.name);
    write_file_bytes(path, blob);
    // Every digit, so that a run reading the cache reports the time this one does.
    std::ofstream out(seconds_file);
    out << std::setprecision(std::numeric_limits<double>::max_digits10) << *seconds << "\n";
    check_written(out, seconds_file);
    return blob;
  }

  // The float object of bake key `key`: kept from an earlier setting (one that differs only in
  // bits), else baked now.
  const Baked& baked_object(const ShadowfieldBakeSettings& b, std::size_t index,
                            const std::string& key, const Context& ctx) {
    auto baked = baked_.find(key);
    if (baked != baked_.end()) return baked->second;
    if (baked_.size() >= description_.objects.size()) baked_.clear();  // the last setting's
    const ShadowfieldSceneObject& o = description_.objects[index];
    ctx.info("  baking " + o.name);
    const auto start = std::chrono::steady_clock::now();
    ShadowfieldBakeResult result =
        bake_shadowfield_object(o.mesh, make_shadowfield_material(o.material, b.brdf), b, ctx);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return baked_.emplace(key, Baked{std::move(result.object), elapsed}).first->second;
  }

  SettingBlobs setting_blobs(const ShadowfieldBakeSettings& b, const TradeInput& input,
                             const Context& ctx) {
    SettingBlobs blobs;
    for (std::size_t o = 0; o < description_.objects.size(); ++o) {
      double seconds = 0.0;
      blobs.blobs.push_back(object_blob(b, o, input, ctx, &seconds));
      blobs.bytes += blobs.blobs.back().size();
      blobs.bake_seconds += seconds;
    }
    return blobs;
  }

  void measure_setting(const SceneSetting& s, const TradeInput& input, const Context& ctx,
                       std::vector<SceneRow>& rows) {
    const ShadowfieldBakeSettings b = bake_settings(s, input);
    check_shadowfield_bake_settings(b);
    const SettingBlobs blobs = setting_blobs(b, input, ctx);
    CountedScene runtime(description_, blobs.blobs);
    for (const Light& light : lights_) {
      for (std::size_t t = 0; t < times_.size(); ++t) {
        SceneRow row = measure_placement(runtime, s, light, t, input.frames);
        row.runtime_bytes = runtime.runtime_bytes();
        row.blob_bytes = blobs.bytes;
        row.bake_seconds = blobs.bake_seconds;
        ctx.info("  " + light.name +
                 format(", t = %g s: error %.2f %%, SIMD %.2f ms, scalar %.2f ms CPU",
                        double(row.time), 100 * row.error, row.simd_ms, row.scalar_ms));
        rows.push_back(std::move(row));
      }
    }
  }

  // The placements at time `t` shaded under `light` on both backends and compared with the
  // reference.
  SceneRow measure_placement(CountedScene& runtime, const SceneSetting& s, const Light& light,
                             std::size_t t, int frames) const {
    const glm::vec3 eye = description_.camera.eye;
    const std::size_t light_floats = std::size_t(s[kOrder]) * s[kOrder] * 3;
    const std::vector<float> l(light.sh.begin(), light.sh.begin() + light_floats);
    runtime.place(times_[t]);
    SceneRow row;
    row.scalar_ms = median_cpu_ms(frames, "prt_shadowfield_shade (scalar)", [&] {
      return runtime.shade(l, eye, s[kBounces], PRT_BACKEND_CPU);
    });
    const std::vector<glm::vec3> scalar = runtime.output(s[kBounces]);
    row.simd_ms = median_cpu_ms(frames, "prt_shadowfield_shade (SIMD)", [&] {
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
    row.object_error = per_object_errors(row, t);
    return row;
  }

  // The row's error over each object's instances' vertices (0 for an object without any).
  std::vector<double> per_object_errors(const SceneRow& row, std::size_t t) const {
    const PlacedScene placed = place_shadowfield_scene(description_, times_[t]);
    std::vector<double> errors;
    for (std::size_t o = 0; o < description_.objects.size(); ++o) {
      std::vector<glm::vec3> ours, theirs;
      for (std::size_t i = 0; i < description_.instances.size(); ++i) {
        if (description_.instances[i].object != o) continue;
        const auto first = std::ptrdiff_t(placed.first_vertex[i]),
                   last = std::ptrdiff_t(placed.first_vertex[i + 1]);
        ours.insert(ours.end(), row.radiance.begin() + first, row.radiance.begin() + last);
        theirs.insert(theirs.end(), row.expected.begin() + first, row.expected.begin() + last);
      }
      errors.push_back(ours.empty() ? 0.0 : io::relative_rmse(ours, theirs));
    }
    return errors;
  }

  std::string object_errors(const std::vector<double>& errors) const {
    std::string text;
    for (std::size_t o = 0; o < errors.size(); ++o)
      text += format("%s%s:%.4g", o ? ";" : "", description_.objects[o].name.c_str(), errors[o]);
    return text;
  }

  void write_csv(const std::vector<SceneRow>& rows, const TradeInput& input) const {
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
  }

  void write_markdown(const std::vector<SceneRow>& rows, const TradeInput& input,
                      unsigned threads) const {
    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    write_markdown_intro(md, input, threads);
    const std::vector<std::pair<std::size_t, const SceneSetting*>> blocks = sweep_blocks();
    for (const Light& light : lights_) {
      md << "\n## " << light.name << "\n\n";
      write_markdown_header(md, markdown_columns());
      for (const auto& [knob, setting] : blocks) {
        std::vector<const SceneRow*> of;
        for (const SceneRow& r : rows)
          if (r.setting == setting && r.map == light.name) of.push_back(&r);
        if (!of.empty()) write_markdown_row(md, summary_cells(knob, *setting, of));
      }
    }
    check_written(md, md_path);
  }

  void write_markdown_intro(std::ostream& md, const TradeInput& input, unsigned threads) const {
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
  }

  std::vector<Column> markdown_columns() const {
    std::vector<Column> columns = {{"sweep", false}};
    for (const KnobInfo& k : kKnobs) columns.push_back({k.title});
    columns.push_back({"error %"});
    columns.push_back({"bias %"});
    columns.push_back({"ref noise %"});
    for (const ShadowfieldSceneObject& o : description_.objects)
      columns.push_back({o.name + " error %"});
    for (const char* c : {"SIMD CPU ms", "scalar CPU ms", "runtime MB", "baked MB", "bake s"})
      columns.push_back({c});
    return columns;
  }

  // Sweep by sweep, each knob's values in order, the base among them (so in every block).
  std::vector<std::pair<std::size_t, const SceneSetting*>> sweep_blocks() const {
    std::vector<std::pair<std::size_t, const SceneSetting*>> blocks;
    for (std::size_t k = 0; k < kKnobCount; ++k) {
      std::vector<const SceneSetting*> of_knob;
      for (const SceneSetting& s : settings_) {
        if (in_sweep(s, kKnobs[k].sweep)) of_knob.push_back(&s);
      }
      std::sort(of_knob.begin(), of_knob.end(), [&](const SceneSetting* a, const SceneSetting* b) {
        return a->knobs[k] < b->knobs[k];
      });
      for (const SceneSetting* s : of_knob) blocks.emplace_back(k, s);
    }
    return blocks;
  }

  // One markdown row: a setting's rows (its placements under one light) summarised.
  std::vector<std::string> summary_cells(std::size_t knob, const SceneSetting& s,
                                         const std::vector<const SceneRow*>& of) const {
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
    return cells;
  }

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

}  // namespace

void check_scene_sweep_options(const SceneSweepOptions& options) {
  parse_times(options.times);
  struct SceneList {
    const char* flag;
    const std::vector<std::uint32_t>* values;
    Knob knob;
  };
  for (const SceneList& list : {SceneList{"--oof-shells", &options.oof_shells, kOofShells},
                                SceneList{"--oof-faces", &options.oof_faces, kOofFace},
                                SceneList{"--srf-shells", &options.srf_shells, kSrfShells},
                                SceneList{"--srf-faces", &options.srf_faces, kSrfFace},
                                SceneList{"--basis-sizes", &options.basis, kBasis},
                                SceneList{"--bounces", &options.bounces, kBounces}}) {
    const KnobInfo& knob = kKnobs[list.knob];
    for (const std::uint32_t v : *list.values) {
      if (v < knob.min || v > knob.max)
        throw Error(std::string(list.flag) + ": " + std::to_string(v) + " is outside " +
                    std::to_string(knob.min) + ".." + std::to_string(knob.max));
    }
  }
}

std::unique_ptr<SceneSweep> make_scene_sweep(std::string preset, const SceneSweepOptions& options,
                                             const SfTradeSettings& object, bool rays_given,
                                             bool base_rays_given) {
  return std::make_unique<ShadowfieldSceneSweep>(std::move(preset), options, object, rays_given,
                                                 base_rays_given);
}

}  // namespace prt::bake::sf_trade
