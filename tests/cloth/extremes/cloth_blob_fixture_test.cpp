// SPDX-License-Identifier: MIT
// The fixture the other tests of this binary share under ctest: the small bake written to the
// file PRT_CLOTH_EXTREMES_BLOB names (skipped without it). Written beside and renamed into place,
// so that a test reading it meanwhile sees a whole blob; the bake is fresh, never the file's.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "cloth/extremes/cloth_extremes.hpp"

namespace {

using namespace prt_test;

TEST(ClothExtremesBlob, WritesTheBakedBlob) {
  const char* path = std::getenv(kExtremesBlobVariable);
  if (!path) GTEST_SKIP() << kExtremesBlobVariable << " is not set";
  const Bytes blob = bake_extremes_blob();
  {
    // The blob loads: the tests would otherwise bake it again, silently.
    Context ctx;
    const LoadedAsset asset(ctx.ctx, blob);
    ASSERT_EQ(asset.result, PRT_OK);
  }
  const std::string part = std::string(path) + "." + std::to_string(getpid());
  {
    std::ofstream out(part, std::ios::binary);
    out.write(reinterpret_cast<const char*>(blob.data()), std::streamsize(blob.size()));
    ASSERT_TRUE(out.good()) << part;
  }
  ASSERT_EQ(std::rename(part.c_str(), path), 0) << path;
  EXPECT_EQ(read_file(path), blob);
}

}  // namespace
