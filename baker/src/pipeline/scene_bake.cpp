// SPDX-License-Identifier: MIT
// prt-bake scene: picks, bakes and measures each object's technique and settings
// (prt/baker/scene_bake.hpp).
#include "prt/baker/scene_bake.hpp"

#include <prt/prt_version.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/text.hpp"

#include "../common/atomic_file.hpp"
#include "../common/numbers.hpp"
#include "../common/trade_common.hpp"
#include "content_hash.hpp"
#include "scene_bake_detail.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;
using pipeline::Candidate;
using pipeline::LightInfo;
using pipeline::ObjectResult;
using pipeline::SingleTechnique;

struct Light {
  LightInfo info;
  std::unique_ptr<io::EnvMap> map;
};

std::vector<Light> load_lights(const SceneBakeSettings& settings, const Context& ctx) {
  std::vector<Light> lights;
  if (settings.envs.empty()) {
    Light sky;
    sky.map = std::make_unique<io::EnvMap>(make_demo_sky());
    ContentHash hash;
    hash.values(sky.map->pixels());
    sky.info = {"sky", hash.hex()};
    lights.push_back(std::move(sky));
  }
  for (const std::string& path : settings.envs) {
    Light light;
    light.map = std::make_unique<io::EnvMap>(
        io::load_envmap(path, io::EnvMapping::Auto, ctx.io_messages()));
    light.info = {fs::path(path).stem().string(), file_hash(path)};
    lights.push_back(std::move(light));
  }
  return lights;
}

// "NAME=TECHNIQUE[:ARG,ARG,...]" overrides, by object name.
struct Override {
  std::string technique;
  std::vector<std::string> args;
};

std::optional<Override> override_for(const SceneBakeSettings& settings, const SceneObject& object,
                                     const Scene& scene) {
  for (const std::string& text : settings.overrides) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || text.substr(0, eq) != object.name) continue;
    const std::string rest = text.substr(eq + 1);
    const std::size_t colon = rest.find(':');
    Override o{rest.substr(0, colon), {}};
    if (colon != std::string::npos) {
      std::stringstream args(rest.substr(colon + 1));
      for (std::string arg; std::getline(args, arg, ',');) o.args.push_back(arg);
    }
    return o;
  }
  const Node::Hints& hints = scene.nodes[std::size_t(object.node)].hints;
  if (hints.technique.empty()) return std::nullopt;
  Override o{hints.technique, {}};
  for (const auto& [key, value] : hints.settings) o.args.insert(o.args.end(), {key, value});
  return o;
}

// Measures and caches candidates of one object; the reference is rendered on first need.
class ObjectBaker {
 public:
  ObjectBaker(const SceneBakeSettings& settings, const Scene& scene,
              const std::vector<Light>& lights, const SceneObject& object,
              const std::string& object_hash, const Context& ctx)
      : settings_(settings),
        scene_(scene),
        lights_(lights),
        object_(object),
        hash_(object_hash),
        ctx_(ctx) {}

  Candidate candidate(const Technique& technique, const std::vector<std::string>& args,
                      std::vector<std::uint8_t>* blob) {
    Candidate c;
    c.technique = technique.name();
    c.args = args;
    const std::string key = candidate_key(c);
    if (read_cached(key, &c, blob)) return c;
    try {
      bake(technique, args, &c, blob);
      measure(technique, *blob, &c);
    } catch (const Error& e) {
      c.failure = e.what();
      blob->clear();
      return c;
    }
    write_cached(key, c, *blob);
    return c;
  }

 private:
  std::string candidate_key(const Candidate& c) const {
    ContentHash hash;
    hash.text(hash_).text(c.technique).value(c.args.size());
    for (const std::string& arg : c.args) hash.text(arg);
    return hash.hex();
  }

  void bake(const Technique& technique, const std::vector<std::string>& args, Candidate* c,
            std::vector<std::uint8_t>* blob) {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<TechniqueBake> bake = technique.make_bake();
    apply_option_args(bake->options(), args);
    BakeInput input;
    input.scene = "object " + object_.name;  // not the path: a moved file bakes the same bytes
    input.seed = settings_.seed;
    bake->bake(object_.scene, input, ctx_);
    bake->quantize();
    *blob = bake->write(object_.scene, input);
    const SelfCheck check = bake->self_check(*blob);
    if (!check.passed) throw Error("self-check: " + check.message);
    c->bytes = blob->size();
    c->bake_seconds = seconds_since(start);
  }

  void measure(const Technique& technique, const std::vector<std::uint8_t>& blob, Candidate* c) {
    std::unique_ptr<ObjectMeasure>& measure = measures_[technique.measure()];
    if (!measure) {
      ObjectMeasureInput input;
      input.scene = &scene_;
      input.object = &object_.scene;
      input.node = object_.node;
      for (const Light& light : lights_) input.lights.push_back(light.map.get());
      input.bounces = settings_.bounces;
      input.ref_spp = settings_.ref_spp;
      input.probe_vertices = settings_.probe_vertices;
      input.seed = settings_.seed;
      measure = technique.measure()(input);
    }
    const Measurement m = measure->measure(technique, blob, ctx_);
    c->error = m.error;
    c->ref_noise = m.ref_noise;
    c->meets = c->error <= settings_.error_budget;
  }

  std::string cache_path(const std::string& key, const char* extension) const {
    return settings_.cache_dir + "/" + key + extension;
  }

  bool read_cached(const std::string& key, Candidate* c, std::vector<std::uint8_t>* blob) const {
    std::ifstream figures(cache_path(key, ".txt"));
    std::ifstream bytes(cache_path(key, ".prtk"), std::ios::binary);
    if (!figures || !bytes) return false;
    if (!(figures >> c->error >> c->ref_noise >> c->bake_seconds)) return false;
    blob->assign(std::istreambuf_iterator<char>(bytes), std::istreambuf_iterator<char>());
    c->bytes = blob->size();
    c->from_cache = true;
    c->meets = c->error <= settings_.error_budget;
    return !blob->empty();
  }

  void write_cached(const std::string& key, const Candidate& c,
                    const std::vector<std::uint8_t>& blob) const {
    std::ostringstream figures;
    figures.precision(17);
    figures << c.error << ' ' << c.ref_noise << ' ' << c.bake_seconds << '\n';
    // The blob first: a figures file is only ever next to a whole blob.
    write_file_atomic(cache_path(key, ".prtk"), std::string(blob.begin(), blob.end()));
    write_file_atomic(cache_path(key, ".txt"), figures.str());
  }

  const SceneBakeSettings& settings_;
  const Scene& scene_;
  const std::vector<Light>& lights_;
  const SceneObject& object_;
  std::string hash_;
  const Context& ctx_;
  // One measurement per factory: techniques that share it share its references.
  std::map<ObjectMeasureFactory, std::unique_ptr<ObjectMeasure>> measures_;
};

std::string joined(const std::vector<std::string>& args) {
  std::string text;
  for (const std::string& arg : args) text += (text.empty() ? "" : " ") + arg;
  return text;
}

// Everything a candidate's figures depend on besides its technique and settings.
std::string object_hash(const SceneBakeSettings& settings, const std::vector<Light>& lights,
                        const SceneObject& object) {
  ContentHash hash;
  hash.text(PRT_VERSION_STRING);
  hash_object_scene(hash, object.scene, object.node);
  for (const Light& light : lights) hash.text(light.info.name).text(light.info.hash);
  hash.value(settings.bounces).value(settings.ref_spp).value(settings.probe_vertices);
  hash.value(settings.seed);
  return hash.hex();
}

// The techniques to try on the object and the settings of each: an override's one technique
// (with its settings when given, else its ladder), or every technique that suits it.
struct Plan {
  const Technique* technique;
  std::vector<Rung> rungs;
};

std::vector<Plan> plan_object(const SceneBakeSettings& settings, const Scene& scene,
                              const SceneObject& object, ObjectResult* result) {
  std::vector<Plan> plans;
  if (const std::optional<Override> o = override_for(settings, object, scene)) {
    const Technique* technique = find_technique(o->technique);
    if (!technique) {
      result->problems.push_back("no technique is named '" + o->technique + "'");
      return plans;
    }
    result->reason = "forced (command line or the node's extras)";
    plans.push_back({technique, o->args.empty() ? technique->ladder(settings.bounces)
                                                : std::vector<Rung>{{o->args}}});
    return plans;
  }
  for (const Technique* technique : techniques()) {
    const ObjectFit fit = technique->fit(scene, object.node);
    result->fits.push_back(std::string(technique->name()) + ": " + fit.reason);
    if (fit.suits) plans.push_back({technique, technique->ladder(settings.bounces)});
  }
  if (plans.empty()) result->problems.push_back("no technique suits it");
  return plans;
}

// When no candidate meets E, more bytes soon buy almost nothing: this keeps the fewest bytes
// whose error is within kOverBudgetSlack of the smallest error found.
constexpr double kOverBudgetSlack = 1.05;

void settle_over_budget(ObjectBaker& baker, ObjectResult* result, std::vector<std::uint8_t>* blob) {
  const double smallest = result->choice()->error;
  for (std::size_t i = 0; i < result->candidates.size(); ++i) {
    const Candidate& c = result->candidates[i];
    if (c.failure.empty() && c.error <= kOverBudgetSlack * smallest &&
        c.bytes < result->choice()->bytes)
      result->chosen = int(i);
  }
  const Candidate& chosen = *result->choice();
  const Technique* technique = find_technique(chosen.technique);
  baker.candidate(*technique, chosen.args, blob);  // from the cache
}

// Climbs each plan's ladder to its first rung that meets E; keeps the fewest bytes among those
// that do, else the smallest error. Returns the chosen blob.
std::vector<std::uint8_t> choose(const std::vector<Plan>& plans, ObjectBaker& baker,
                                 ObjectResult* result, const Context& ctx) {
  std::vector<std::uint8_t> best_blob, blob;
  for (const Plan& plan : plans) {
    if (plan.rungs.empty())
      result->problems.push_back(std::string(plan.technique->name()) + " has no settings to try");
    for (const Rung& rung : plan.rungs) {
      result->candidates.push_back(baker.candidate(*plan.technique, rung.args, &blob));
      const Candidate& c = result->candidates.back();
      ctx.info(result->object->name + ": " + c.technique + " " + joined(c.args) + ": " +
               (c.failure.empty() ? format("error %.3g %%, %zu bytes%s", 100 * c.error, c.bytes,
                                           c.from_cache ? " (cached)" : "")
                                  : "failed: " + c.failure));
      if (!c.failure.empty()) continue;
      const Candidate* best = result->choice();
      const bool better = !best || (c.meets && (!best->meets || c.bytes < best->bytes)) ||
                          (!c.meets && !best->meets && c.error < best->error);
      if (better) {
        result->chosen = int(result->candidates.size()) - 1;
        best_blob = blob;
      }
      // The ladder only grows from here: a rung that meets E, or one already larger than a
      // choice that does, ends this technique's climb.
      if (c.meets || (result->choice()->meets && c.bytes >= result->choice()->bytes)) break;
    }
  }
  if (!result->choice() && result->problems.empty())
    result->problems.push_back("no candidate could be baked (see its candidates)");
  if (result->choice() && !result->choice()->meets) settle_over_budget(baker, result, &best_blob);
  return best_blob;
}

// Chooses, bakes and writes the object; returns its baker (which holds its references) when
// something was baked.
std::unique_ptr<ObjectBaker> bake_object(const SceneBakeSettings& settings, const Scene& scene,
                                         const std::vector<Light>& lights, ObjectResult* result,
                                         const Context& ctx) {
  const SceneObject& object = *result->object;
  if (object.skipped || !object.problems.empty()) return nullptr;
  const std::vector<Plan> plans = plan_object(settings, scene, object, result);
  if (plans.empty()) return nullptr;
  result->hash = object_hash(settings, lights, object);
  auto baker = std::make_unique<ObjectBaker>(settings, scene, lights, object, result->hash, ctx);
  const std::vector<std::uint8_t> blob = choose(plans, *baker, result, ctx);
  const Candidate* chosen = result->choice();
  if (!chosen) return nullptr;
  if (result->reason.empty()) {
    result->reason = chosen->meets ? "the fewest bytes that meet the budget"
                                   : "no candidate meets the budget: the fewest bytes within 5 % "
                                     "of the smallest error";
  }
  if (settings.shard_count > 1) return baker;  // a shard writes the cache only
  result->blob_file = object.name + ".prtk";
  write_file_atomic(settings.out_dir + "/" + result->blob_file,
                    std::string(blob.begin(), blob.end()));
  return baker;
}

// The first rung of `ladder` that meets E for the object, or the last rung when none does.
std::size_t rung_meeting(const Technique& technique, const std::vector<Rung>& ladder,
                         ObjectBaker& baker, bool* meets) {
  std::vector<std::uint8_t> blob;
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    if (baker.candidate(technique, ladder[k].args, &blob).meets) return k;
  }
  *meets = false;
  return ladder.size() - 1;
}

// The objects of each technique in a baseline, and the rung the hardest of them needs.
struct BaselineGroup {
  const Technique* technique;
  std::vector<std::size_t> objects;
};

// What a pipeline without a choice per object would bake: every baked object that `technique`
// suits with it, the others with their chosen technique (the only kind that bakes them), each
// technique at one setting: the rung its hardest object needs. Null when `technique` suits no
// baked object or has no ladder.
std::optional<SingleTechnique> single_technique(
    const Technique& technique, const SceneBakeSettings& settings, const Scene& scene,
    const std::vector<ObjectResult>& results,
    const std::vector<std::unique_ptr<ObjectBaker>>& bakers) {
  if (technique.ladder(settings.bounces).empty()) return std::nullopt;
  std::vector<BaselineGroup> groups{{&technique, {}}};
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (!bakers[i]) continue;
    const Technique* own = technique.fit(scene, results[i].object->node).suits
                               ? &technique
                               : find_technique(results[i].choice()->technique);
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const BaselineGroup& g) { return g.technique == own; });
    if (group == groups.end()) group = groups.insert(groups.end(), {own, {}});
    group->objects.push_back(i);
  }
  if (groups.front().objects.empty()) return std::nullopt;
  SingleTechnique single;
  single.technique = technique.name();
  std::vector<std::uint8_t> blob;
  for (const BaselineGroup& group : groups) {
    const std::vector<Rung> ladder = group.technique->ladder(settings.bounces);
    if (ladder.empty()) return std::nullopt;
    std::size_t hardest = 0;
    for (const std::size_t i : group.objects)
      hardest =
          std::max(hardest, rung_meeting(*group.technique, ladder, *bakers[i], &single.meets));
    for (const std::size_t i : group.objects) {
      single.bytes += bakers[i]->candidate(*group.technique, ladder[hardest].args, &blob).bytes;
      single.objects.push_back({results[i].object->name, group.technique->name()});
    }
    single.settings.push_back({group.technique->name(), ladder[hardest].args});
  }
  single.args = single.settings.front().second;
  return single;
}

SceneBakeSummary summarise(const std::vector<ObjectResult>& results) {
  SceneBakeSummary s;
  for (const ObjectResult& r : results) {
    ++s.objects;
    if (!r.problems.empty() && !r.choice()) ++s.broken;
    if (const Candidate* c = r.choice()) {
      ++s.baked;
      s.from_cache += c->from_cache;
      s.over_budget += !c->meets;
      s.bytes += c->bytes;
    }
  }
  return s;
}

}  // namespace

SceneBakeSummary run_scene_bake(const SceneBakeSettings& settings, const Context& ctx) {
  // Keep going: a broken primitive, node or texture becomes a problem of its object (import: ...).
  const Scene scene = import_scene(settings.scene, ctx, ImportOptions{true});
  return run_scene_bake(settings, scene, ctx);
}

SceneBakeSummary run_scene_bake(const SceneBakeSettings& input, const Scene& scene,
                                const Context& ctx) {
  SceneBakeSettings settings = input;
  if (!(settings.error_budget > 0.0) || !std::isfinite(settings.error_budget))
    throw Error("--error-budget: must be a positive fraction, e.g. 0.02 for 2 %");
  if (settings.ref_spp < 2) throw Error("--ref-spp: must be >= 2");
  if (settings.bounces < 0) throw Error("--bounces: must be >= 0");
  if (settings.shard_count < 1 || settings.shard_index >= settings.shard_count)
    throw Error("--shard: expected i/N with 0 <= i < N");
  if (settings.cache_dir.empty()) settings.cache_dir = settings.out_dir + "/.cache";
  fs::create_directories(settings.out_dir);
  fs::create_directories(settings.cache_dir);

  const std::vector<Light> lights = load_lights(settings, ctx);
  const std::vector<SceneObject> objects = scene_objects(scene);
  std::vector<ObjectResult> results(objects.size());
  std::vector<std::unique_ptr<ObjectBaker>> bakers(objects.size());
  const bool shard = settings.shard_count > 1;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    results[i].object = &objects[i];
    if (shard && i % settings.shard_count != settings.shard_index) continue;
    results[i].problems = objects[i].problems;
    bakers[i] = bake_object(settings, scene, lights, &results[i], ctx);
    for (const std::string& problem : results[i].problems)
      ctx.warn(objects[i].name + ": " + problem);
  }
  if (shard) {
    // A shard fills the cache only; the run without --shard writes every output from it.
    std::vector<ObjectResult> own;
    for (std::size_t i = settings.shard_index; i < results.size(); i += settings.shard_count)
      own.push_back(results[i]);
    return summarise(own);
  }
  SceneBakeSummary summary = summarise(results);
  std::vector<SingleTechnique> singles;
  if (settings.compare_single) {
    for (const Technique* technique : techniques()) {
      if (auto single = single_technique(*technique, settings, scene, results, bakers)) {
        ctx.info(format("every object with %s %s: %zu bytes%s", single->technique.c_str(),
                        joined(single->args).c_str(), single->bytes,
                        single->meets ? "" : " (the budget is not met everywhere)"));
        if (single->meets && (summary.single_bytes == 0 || single->bytes < summary.single_bytes))
          summary.single_bytes = single->bytes;
        singles.push_back(std::move(*single));
      }
    }
  }
  std::vector<LightInfo> light_infos;
  for (const Light& light : lights) light_infos.push_back(light.info);
  pipeline::write_manifest(settings, results);
  pipeline::write_report(settings, light_infos, results, singles, summary);
  return summary;
}

}  // namespace prt::bake
