// SPDX-License-Identifier: MIT
// What the viewer reads off a path: its extension (any case) and its file name, for the mode a
// path opens in and for labels.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace prt::view {

// True when `path` ends in `extension` (e.g. ".hdr"), ignoring case.
inline bool has_extension(const std::string& path, const std::string& extension) {
  if (path.size() < extension.size()) return false;
  std::string tail = path.substr(path.size() - extension.size());
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == extension;
}

// The part of `path` after its last '/'.
inline std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace prt::view
