// SPDX-License-Identifier: MIT
// Files written whole or not at all (atomic_file.hpp).
#include "atomic_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "prt/baker/context.hpp"

namespace prt::bake {

void write_file_atomic(const std::string& path, const std::string& bytes) {
  namespace fs = std::filesystem;
  // The process id keeps two writers of one folder (two shards of a farm) off each other's file.
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file || !file.write(bytes.data(), std::streamsize(bytes.size())) || !file.flush()) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw Error(path + ": cannot write");
    }
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    fs::remove(temporary, error);
    throw Error(path + ": cannot write (the rename failed)");
  }
}

void write_file_atomic(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file_atomic(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace prt::bake
