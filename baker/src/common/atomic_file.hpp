// SPDX-License-Identifier: MIT
// Files written whole or not at all (private to the baker).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prt::bake {

// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so a reader
// never sees half a file and a failed write leaves what was there; Error naming the file on
// failure (the temporary is removed).
void write_file_atomic(const std::string& path, const std::string& bytes);
void write_file_atomic(const std::string& path, const std::vector<std::uint8_t>& bytes);

}  // namespace prt::bake
