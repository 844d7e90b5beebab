// SPDX-License-Identifier: MIT
#include "prt/io/file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "prt/io/error.hpp"

namespace prt::io {

std::vector<unsigned char> read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(path + ": cannot open file: it is a directory");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot open file: " + std::strerror(errno));
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  if (file.bad()) throw Error(path + ": cannot read file: " + std::strerror(errno));
  return bytes;
}

}  // namespace prt::io
