// SPDX-License-Identifier: MIT
// The viewer's technique registry: every technique of the table (techniques.cpp) with its
// options, and the choice of the one a blob is drawn with.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "view_technique.hpp"

namespace CLI {
class App;
}

namespace prt::view {

using MakeViewTechnique = std::unique_ptr<ViewTechnique> (*)();

// The table: techniques.cpp, its only definition.
const std::vector<MakeViewTechnique>& view_technique_table();

// The command-line option of a live parameter, in the help section `group`: a flag for a bool,
// an option taking a number otherwise; given, it calls the parameter's set.
void add_live_parameter_option(CLI::App& app, const std::string& group,
                               const LiveParameter& parameter);

// Gives `to` the values of `from`'s live parameters (matched by option), when both are the same
// technique: how a viewer hands the command line's values to another instance.
void copy_live_parameters(ViewTechnique& from, ViewTechnique& to);

class ViewTechniques {
 public:
  // One instance of every technique in the table; its name is the runtime's
  // (prt_technique_get_info).
  ViewTechniques();

  // --technique NAME and each technique's options, in a help section named after it.
  void add_options(CLI::App& app);

  // The technique to draw the scene's blob with: the one --technique named, else the first in
  // the table that prt_asset_techniques() says the blob holds. Throws ViewerError naming the
  // file when the blob holds none of them or not the one named.
  ViewTechnique& choose(const BlobScene& scene) const;

  // Warns on stderr about options of the other techniques given on the command line (they do
  // nothing for this blob).
  void warn_unused_options(const CLI::App& app, const ViewTechnique& chosen) const;

  // The techniques' names in table order, comma-separated, for messages and help.
  std::string names() const;

  // This registry's instance of `technique`, or nullptr.
  ViewTechnique* find(prt_technique technique) const;

 private:
  struct Entry {
    std::unique_ptr<ViewTechnique> view;
    std::string name;
  };
  std::vector<Entry> entries_;
  std::string requested_;  // --technique

  static std::string options_group(const std::string& name) { return name + " options"; }
  std::string blob_contents(std::uint32_t techniques) const;
};

}  // namespace prt::view
