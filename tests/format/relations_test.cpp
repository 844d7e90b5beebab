// SPDX-License-Identifier: MIT
// Quick validation's kind relations (formats/SPEC.md §7, §8.1 check 27), driven by the kind
// table: each dependent kind needs its sections, and each vertex-domain kind has VPOS's element
// count. The messages are part of the contract (the runtime and the tools show them).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <prt/format/blob_writer.hpp>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;
using prt::format::BlobWriter;

struct Section {
  uint32_t tag;
  size_t bytes;
  uint64_t element_count;
  uint8_t layout_version = 1;
};

// Writes the sections under stand-in tags (so that the writer's own relation check passes), then
// gives every entry its real tag.
Bytes make_blob(const std::vector<Section>& sections) {
  BlobWriter writer;
  for (size_t i = 0; i < sections.size(); ++i) {
    const std::vector<uint8_t> zeros(sections[i].bytes, 0);
    prt::format::SectionOptions options;
    options.layout_version = sections[i].layout_version;
    writer.add_section(prt::format::make_tag('t', 'm', 'p', char('0' + i)), zeros.data(),
                       zeros.size(), sections[i].element_count, options);
  }
  Bytes blob = writer.finish();
  for (size_t i = 0; i < sections.size(); ++i)
    put_u32(blob, entry(uint32_t(i)) + PRT_BLOB_SEC_OFF_TAG, sections[i].tag);
  fix_header_checksum(blob);
  return blob;
}

// The status and message of quick validation by the reader core.
std::pair<prt_blob_status, std::string> check(const Bytes& blob) {
  char msg[256] = "";
  const prt_blob_status st =
      prt_blob_validate_structure(blob.data(), blob.size(), nullptr, msg, sizeof msg);
  return {st, msg};
}

const uint32_t kVpos = PRT_BLOB_TAG('V', 'P', 'O', 'S'), kVnrm = PRT_BLOB_TAG('V', 'N', 'R', 'M'),
               kTris = PRT_BLOB_TAG('T', 'R', 'I', 'S'), kShtr = PRT_BLOB_TAG('S', 'H', 'T', 'R'),
               kWvlt = PRT_BLOB_TAG('W', 'V', 'L', 'T'), kPstr = PRT_BLOB_TAG('P', 'S', 'T', 'R'),
               kVtan = PRT_BLOB_TAG('V', 'T', 'A', 'N'), kClth = PRT_BLOB_TAG('C', 'L', 'T', 'H');

TEST(KindRelations, ConsistentBlobPasses) {
  const Bytes blob =
      make_blob({{kVpos, 36, 3}, {kVnrm, 36, 3}, {kTris, 12, 1}, {kShtr, 64, 3}, {kWvlt, 64, 3}});
  EXPECT_EQ(check(blob).first, PRT_BLOB_OK) << check(blob).second;
}

TEST(KindRelations, VertexDomainKindsHaveVposCount) {
  const struct {
    Section section;
    const char* message;
  } cases[] = {
      {{kVnrm, 24, 2}, "'VNRM' has 2 normals for 3 vertices"},
      {{kVtan, 48, 4}, "'VTAN' has 4 tangents for 3 vertices"},
      {{kShtr, 64, 2}, "'SHTR' has 2 transfer vectors for 3 vertices"},
      {{kWvlt, 64, 4}, "'WVLT' has 4 transfer rows for 3 vertices"},
      {{kPstr, 64, 2}, "'PSTR' has 2 skinned vertices for 3 vertices"},
  };
  for (const auto& c : cases) {
    const auto [st, msg] = check(make_blob({{kVpos, 36, 3}, c.section}));
    EXPECT_EQ(st, PRT_BLOB_CORRUPT) << c.message;
    EXPECT_EQ(msg, c.message);
  }
}

TEST(KindRelations, DependentsNeedVpos) {
  const struct {
    Section section;
    const char* message;
  } cases[] = {
      {{kTris, 12, 1}, "section 'TRIS' needs a 'VPOS' section"},
      {{kVnrm, 12, 1}, "section 'VNRM' needs a 'VPOS' section"},
      {{kVtan, 12, 1}, "section 'VTAN' needs a 'VPOS' section"},
      {{kShtr, 64, 1}, "section 'SHTR' needs a 'VPOS' section"},
      {{kWvlt, 64, 1}, "section 'WVLT' needs a 'VPOS' section"},
      {{kPstr, 64, 1}, "section 'PSTR' needs a 'VPOS' section"},
  };
  for (const auto& c : cases) {
    const auto [st, msg] = check(make_blob({c.section}));
    EXPECT_EQ(st, PRT_BLOB_CORRUPT) << c.message;
    EXPECT_EQ(msg, c.message);
  }
}

// CLTH counts the material domain: it needs no mesh, and a mesh beside it does not change that.
TEST(KindRelations, ClothNeedsNoMesh) {
  auto [st, msg] = check(make_blob({{kClth, 64, 2}}));
  EXPECT_EQ(st, PRT_BLOB_OK) << msg;
  std::tie(st, msg) = check(make_blob({{kVpos, 36, 3}, {kVtan, 36, 3}, {kClth, 64, 5}}));
  EXPECT_EQ(st, PRT_BLOB_OK) << msg;
}

// The first failing kind is reported in the table's order (TRIS before VNRM), whatever the
// blob's section order.
TEST(KindRelations, FirstFailureInKindOrder) {
  const auto [st, msg] = check(make_blob({{kVnrm, 12, 1}, {kTris, 12, 1}}));
  EXPECT_EQ(st, PRT_BLOB_CORRUPT);
  EXPECT_EQ(msg, "section 'TRIS' needs a 'VPOS' section");
}

// A VPOS of an unknown layout version is not the vertex count: its dependents miss it, and a
// dependent of an unknown layout version has no relations.
TEST(KindRelations, UnknownLayoutVersionsAreNotKnownSections) {
  auto [st, msg] = check(make_blob({{kVpos, 36, 3, 2}, {kVnrm, 36, 3}}));
  EXPECT_EQ(st, PRT_BLOB_CORRUPT);
  EXPECT_EQ(msg, "section 'VNRM' needs a 'VPOS' section");
  std::tie(st, msg) = check(make_blob({{kVnrm, 36, 3, 2}}));
  EXPECT_EQ(st, PRT_BLOB_OK) << msg;
}

}  // namespace
