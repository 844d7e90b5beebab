// SPDX-License-Identifier: MIT
// Test helpers: the shared assets folder (tests skip when it is missing), a scratch folder for
// files the tests write (broken inputs are made on the fly, never stored in the repo) and reading
// a file whole.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace prt_test {

// Full path of shared/assets/<relative>, or "" when it does not exist.
inline std::string shared_asset(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(PRT_SHARED_DIR) / "assets" / relative;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

// A fresh directory under the system temp folder, removed with everything in it.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("prt_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string dir() const { return path_.string(); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string p = file(name);
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

 private:
  std::filesystem::path path_;
};

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace prt_test
