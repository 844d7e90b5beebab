// SPDX-License-Identifier: MIT
// What the content pipeline decides for each object, and the files it writes from it (private to
// the pipeline: scene_bake.cpp decides, scene_outputs.cpp writes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/scene_bake.hpp"

namespace prt::bake::pipeline {

// One light the scene will see: its name (the map's file stem, or "sky" for the built-in one)
// and the hash of its content.
struct LightInfo {
  std::string name, hash;
};

// One setting of one technique, baked and measured.
struct Candidate {
  std::string technique;
  std::vector<std::string> args;
  double error = -1.0;     // worst light's relative RMSE, the reference's noise taken out
  double ref_noise = 0.0;  // worst light's reference noise estimate
  std::size_t bytes = 0;
  double bake_seconds = 0.0;  // when it was baked (a cached candidate keeps its first figure)
  bool from_cache = false;
  bool meets = false;
  std::string failure;  // why it could not be baked or measured; empty: it was
};

struct ObjectResult {
  const SceneObject* object = nullptr;
  std::string hash;                   // of everything but the technique and its settings
  std::vector<std::string> fits;      // "sh: static, diffuse", one per technique asked
  std::string reason;                 // why its technique was chosen
  std::vector<Candidate> candidates;  // in the order tried
  int chosen = -1;                    // index into candidates; -1: nothing baked
  std::string blob_file;              // relative to OUT_DIR; empty when nothing was written
  std::vector<std::string> problems;  // why it is broken; empty: it is not

  const Candidate* choice() const { return chosen >= 0 ? &candidates[chosen] : nullptr; }
};

// Every object baked with one technique at the settings its hardest object needs
// (SceneBakeSettings::compare_single); objects it does not suit keep their chosen technique,
// also at one setting for all of them.
struct SingleTechnique {
  std::string technique;
  std::vector<std::string> args;  // of `technique`
  // Each technique of the baseline and its one setting, `technique` first.
  std::vector<std::pair<std::string, std::vector<std::string>>> settings;
  // Each object and the technique it is baked with.
  std::vector<std::pair<std::string, std::string>> objects;
  std::size_t bytes = 0;
  bool meets = true;  // false: some object does not meet E even at the ladder's top
};

// OUT_DIR/scene.json and OUT_DIR/scene.prts (formats/SPEC.md §7.6, what the runtime loads): the
// objects that were baked, their blobs, techniques and placement.
void write_manifest(const SceneBakeSettings& settings, const std::vector<ObjectResult>& results);
// OUT_DIR/report.json: the settings, lights, and per object what was chosen and why, with every
// candidate tried and its figures.
void write_report(const SceneBakeSettings& settings, const std::vector<LightInfo>& lights,
                  const std::vector<ObjectResult>& results,
                  const std::vector<SingleTechnique>& singles, const SceneBakeSummary& summary);

}  // namespace prt::bake::pipeline
