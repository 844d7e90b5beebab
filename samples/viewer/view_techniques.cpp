// SPDX-License-Identifier: MIT
#include "view_techniques.hpp"

#include <CLI/CLI.hpp>
#include <prt/prt.hpp>

#include <cstdio>

namespace prt::view {
namespace {

bool holds(std::uint32_t techniques, const ViewTechnique& view) {
  return (techniques >> static_cast<unsigned>(view.technique())) & 1u;
}

}  // namespace

ViewTechniques::ViewTechniques() {
  for (const MakeViewTechnique make : view_technique_table()) {
    Entry entry{make(), {}};
    prt_technique_info info = prt::sized<prt_technique_info>();
    if (prt_technique_get_info(entry.view->technique(), &info) != PRT_OK)
      throw ViewerError("the runtime does not know technique " +
                        std::to_string(static_cast<int>(entry.view->technique())));
    entry.name = info.name;
    entries_.push_back(std::move(entry));
  }
}

void ViewTechniques::add_options(CLI::App& app) {
  std::vector<std::string> names;
  for (const Entry& entry : entries_) names.push_back(entry.name);
  app.add_option("--technique", requested_,
                 "Which technique of the blob to draw (" + this->names() +
                     "); default: the first of these the blob holds")
      ->check(CLI::IsMember(names));
  for (Entry& entry : entries_) {
    const std::string group = options_group(entry.name);
    entry.view->add_options(app, group);
    for (const LiveParameter& parameter : entry.view->live_parameters())
      add_live_parameter_option(app, group, parameter);
  }
}

void add_live_parameter_option(CLI::App& app, const std::string& group,
                               const LiveParameter& parameter) {
  const std::function<void(double)> set = parameter.set;
  switch (parameter.kind) {
    case LiveParameter::Kind::Bool:
      app.add_flag_function(
             parameter.option, [set](std::int64_t count) { set(count > 0 ? 1.0 : 0.0); },
             parameter.help)
          ->group(group);
      break;
    case LiveParameter::Kind::Int:
      app.add_option_function<std::uint32_t>(
             parameter.option, [set](const std::uint32_t& value) { set(double(value)); },
             parameter.help)
          ->group(group);
      break;
    case LiveParameter::Kind::Float:
      app.add_option_function<double>(
             parameter.option, [set](const double& value) { set(value); }, parameter.help)
          ->group(group);
      break;
  }
}

void copy_live_parameters(ViewTechnique& from, ViewTechnique& to) {
  if (from.technique() != to.technique()) return;
  std::vector<LiveParameter> source = from.live_parameters();
  for (const LiveParameter& target : to.live_parameters())
    for (const LiveParameter& given : source)
      if (given.option == target.option) target.set(given.get());
}

ViewTechnique* ViewTechniques::find(prt_technique technique) const {
  for (const Entry& entry : entries_)
    if (entry.view->technique() == technique) return entry.view.get();
  return nullptr;
}

std::string ViewTechniques::names() const {
  std::string text;
  for (const Entry& entry : entries_) text += (text.empty() ? "" : ", ") + entry.name;
  return text;
}

std::string ViewTechniques::blob_contents(std::uint32_t techniques) const {
  std::string text;
  for (unsigned t = 1; t < 32; ++t) {
    if (!((techniques >> t) & 1u)) continue;
    prt_technique_info info = prt::sized<prt_technique_info>();
    const bool known = prt_technique_get_info(static_cast<prt_technique>(t), &info) == PRT_OK;
    text += (text.empty() ? "" : ", ") + (known ? std::string(info.name) : std::to_string(t));
  }
  return text.empty() ? "only a mesh, no technique section" : text;
}

ViewTechnique& ViewTechniques::choose(const BlobScene& scene) const {
  const std::uint32_t held = prt_asset_techniques(scene.asset());
  for (const Entry& entry : entries_) {
    if (!requested_.empty() && entry.name != requested_) continue;
    if (holds(held, *entry.view)) return *entry.view;
    if (!requested_.empty())
      throw ViewerError(scene.path() + ": no `" + requested_ +
                        "` section to draw (the blob holds " + blob_contents(held) + ")");
  }
  throw ViewerError(scene.path() + ": nothing prt-view can draw: the blob holds " +
                    blob_contents(held) + " (prt-view draws " + names() + ")");
}

void ViewTechniques::warn_unused_options(const CLI::App& app, const ViewTechnique& chosen) const {
  std::string chosen_name;
  for (const Entry& entry : entries_)
    if (entry.view.get() == &chosen) chosen_name = entry.name;
  for (const Entry& entry : entries_) {
    if (entry.view.get() == &chosen) continue;
    const std::string group = options_group(entry.name);
    for (const CLI::Option* option :
         app.get_options([&](const CLI::Option* o) { return o->get_group() == group; })) {
      if (option->count() > 0)
        std::fprintf(stderr,
                     "prt-view: %s is a `%s` option: ignored, the blob is drawn with `%s`\n",
                     option->get_name().c_str(), entry.name.c_str(), chosen_name.c_str());
    }
  }
}

}  // namespace prt::view
