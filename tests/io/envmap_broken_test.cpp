// SPDX-License-Identifier: MIT
// Broken .hdr input gives an Error whose message names the file and what is wrong. Every broken
// file is written here, in a temp folder: from a small valid file written by stb, or a damaged
// copy of a shared asset.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <filesystem>
#include <string>
#include <vector>

#include "prt/io/envmap.hpp"
#include "support/test_files.hpp"

namespace prt::io {
namespace {

using prt_test::read_bytes;
using prt_test::shared_asset;
using prt_test::TempDir;

// Loads path and expects an Error whose message contains the file path and every fragment.
void expect_envmap_error(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    load_envmap(path, EnvMapping::Auto);
    ADD_FAILURE() << path << " loaded without error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }
}

TEST(EnvMapBroken, NonImageHdr) {
  const TempDir dir("broken_hdr");
  expect_envmap_error(dir.write("text.hdr", "just some text\n"), {"not a Radiance .hdr image"});
  // A real PNG with the wrong name: stb could decode it, but it is not HDR radiance.
  const std::string png = dir.file("picture.hdr");
  const unsigned char pixels[4 * 2 * 3] = {};
  ASSERT_NE(stbi_write_png(png.c_str(), 4, 2, 3, pixels, 4 * 3), 0);
  expect_envmap_error(png, {"not a Radiance .hdr image"});
  expect_envmap_error(dir.file("absent.hdr"), {"cannot open", "No such file"});
  // A folder given where a map is expected is named as one (a stream read would only say that a
  // read failed).
  const std::string folder = dir.file("folder.hdr");
  std::filesystem::create_directory(folder);
  expect_envmap_error(folder, {"cannot open", "is a directory"});
}

TEST(EnvMapBroken, TruncatedAndMisshapenHdr) {
  const TempDir dir("broken_hdr_shape");
  std::vector<float> rgb(10 * 7 * 3, 1.0f);
  const std::string odd = dir.file("odd_shape.hdr");
  ASSERT_NE(stbi_write_hdr(odd.c_str(), 10, 7, 3, rgb.data()), 0);
  expect_envmap_error(odd, {"cannot tell the environment mapping", "10x7"});
  // Only the start of the header of a valid file.
  const std::string cut = dir.write("header_only.hdr", read_bytes(odd).substr(0, 40));
  expect_envmap_error(cut, {"truncated .hdr", "header"});
  // Run-length encoded pixel data cut short (stb alone would spin forever on it).
  std::vector<float> wide(64 * 32 * 3);
  for (std::size_t i = 0; i < wide.size(); ++i) wide[i] = float(i % 11) + 0.5f;
  const std::string full = dir.file("full.hdr");
  ASSERT_NE(stbi_write_hdr(full.c_str(), 64, 32, 3, wide.data()), 0);
  const std::string bytes = read_bytes(full);
  const std::string half = dir.write("half.hdr", bytes.substr(0, bytes.size() / 2));
  expect_envmap_error(half, {"truncated .hdr", "scanline"});
}

TEST(EnvMapBroken, TruncatedCopyOfSharedProbe) {
  const std::string source = shared_asset("envmaps/rnl_probe.hdr");
  if (source.empty()) GTEST_SKIP() << "shared assets not found";
  const TempDir dir("broken_probe");
  const std::string bytes = read_bytes(source);
  expect_envmap_error(dir.write("rnl_probe_cut.hdr", bytes.substr(0, bytes.size() - 1000)),
                      {"truncated .hdr", "scanline"});
}

}  // namespace
}  // namespace prt::io
