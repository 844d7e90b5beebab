// SPDX-License-Identifier: MIT
// The scene manifest (formats/SPEC.md §7.6): the writer's blobs pass full validation and read
// back field for field through scene_layout.h; every rule of the SCNE checker fails a written
// blob patched to break it (checksums recomputed, so only the rule can fail), with a message
// naming the record and field; the writer refuses what the checker refuses; and the golden
// manifest formats/golden/1.0/scene_quads.prts holds the values its generator
// (formats/golden/make_scene_golden.cpp) was given, restated here by hand.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <prt/format/scene_layout.h>
#include <prt/format/blob_writer.hpp>
#include <prt/format/scene_writer.hpp>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;
using prt::format::SceneManifestObject;
using prt::format::SceneManifestOptions;
using prt::format::write_scene_manifest;

const uint32_t kShtr = PRT_BLOB_TAG('S', 'H', 'T', 'R'), kWvlt = PRT_BLOB_TAG('W', 'V', 'L', 'T'),
               kClth = PRT_BLOB_TAG('C', 'L', 'T', 'H'), kSfld = PRT_BLOB_TAG('S', 'F', 'L', 'D'),
               kPstr = PRT_BLOB_TAG('P', 'S', 'T', 'R');

SceneManifestObject object(uint32_t tag, std::string name, std::string blob,
                           uint32_t node = PRT_BLOB_SCNE_NO_NODE) {
  SceneManifestObject o;
  o.technique_tag = tag;
  o.name = std::move(name);
  o.blob = std::move(blob);
  o.node = node;
  return o;
}

// Three objects with distinct fields: a placed node, a node at the identity, no node.
std::vector<SceneManifestObject> three_objects() {
  std::vector<SceneManifestObject> objects = {
      object(kShtr, "floor", "floor.prtk", 0),
      object(kSfld, "crate \xC3\xA9t\xC3\xA9", "props/crate_ete.prtk", 7),
      object(kPstr, "hero", "characters/hero/hero.prtk"),
  };
  // A scale, a rotation and a translation: every element but the last row differs.
  objects[0].rest = {2.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,   -2.0f, 0.0f,
                     0.0f, 2.0f, 0.0f, 0.0f, 1.5f, -0.25f, 3.0f,  1.0f};
  return objects;
}

// The SCNE section's table index and its offset in the blob (it is stored uncompressed).
std::pair<uint32_t, size_t> scne_section(const Bytes& blob) {
  const uint32_t count = get_u32(blob, PRT_BLOB_OFF_SECTION_COUNT);
  for (uint32_t i = 0; i < count; ++i)
    if (get_u32(blob, entry(i) + PRT_BLOB_SEC_OFF_TAG) == PRT_BLOB_TAG_SCNE)
      return {i, size_t(get_u64(blob, entry(i) + PRT_BLOB_SEC_OFF_OFFSET))};
  ADD_FAILURE() << "no SCNE section";
  return {0, 0};
}

// Offset in the blob of record i's field `field`.
size_t record_field(const Bytes& blob, uint32_t i, uint32_t field) {
  const size_t at = scne_section(blob).second;
  return at + PRT_BLOB_SCNE_HEADER_SIZE + size_t{i} * get_u32(blob, at + 4) + field;
}

// The status and message of full validation through the runtime's API.
std::pair<prt_result, std::string> validate_full(const Bytes& blob) {
  Context ctx;
  auto copy = exact_copy(blob);
  char msg[256] = "";
  const prt_result r =
      prt_asset_validate(ctx.ctx, copy.get(), blob.size(), PRT_VALIDATE_FULL, msg, sizeof msg);
  return {r, msg};
}

// Full validation of `blob` after `patch` edited its SCNE bytes (the checksums recomputed).
template <typename Patch>
std::pair<prt_result, std::string> patched(Bytes blob, Patch patch) {
  patch(blob);
  fix_section_checksum(blob, scne_section(blob).first);
  return validate_full(blob);
}

#define EXPECT_REFUSED(result, status, text)                                      \
  do {                                                                            \
    const std::pair<prt_result, std::string> refusal = (result);                  \
    EXPECT_EQ(refusal.first, (status)) << refusal.second;                         \
    EXPECT_NE(refusal.second.find(text), std::string::npos) << refusal.second;    \
    EXPECT_EQ(refusal.second.find('\n'), std::string::npos) << "one line please"; \
  } while (0)

// Bytes [offset, offset + size) of the string table.
std::string string_at(const Bytes& blob, uint32_t offset, uint32_t size) {
  const size_t at = scne_section(blob).second;
  prt_blob_scne_header h;
  prt_blob_scne_read_header(blob.data() + at, &h);
  const size_t strings = at + size_t(prt_blob_scne_strings(&h));
  return std::string(reinterpret_cast<const char*>(blob.data()) + strings + offset, size);
}

TEST(SceneManifest, WrittenBlobPassesFullValidation) {
  const Bytes blob = write_scene_manifest(three_objects());
  const auto [r, msg] = validate_full(blob);
  EXPECT_EQ(r, PRT_OK) << msg;
  Context ctx;
  EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_OK);
  EXPECT_EQ(load(ctx.ctx, blob, PRT_VALIDATE_FULL), PRT_OK);
}

TEST(SceneManifest, ReadsBackFieldForField) {
  const std::vector<SceneManifestObject> objects = three_objects();
  const Bytes blob = write_scene_manifest(objects);
  // One required, uncompressed SCNE section and no INFO without an info text.
  ASSERT_EQ(get_u32(blob, PRT_BLOB_OFF_SECTION_COUNT), 1u);
  EXPECT_EQ(get_u32(blob, entry(0) + PRT_BLOB_SEC_OFF_TAG), PRT_BLOB_TAG_SCNE);
  EXPECT_EQ(blob[entry(0) + PRT_BLOB_SEC_OFF_FLAGS], PRT_BLOB_SECTION_REQUIRED);
  EXPECT_EQ(blob[entry(0) + PRT_BLOB_SEC_OFF_CODEC], PRT_BLOB_CODEC_NONE);
  EXPECT_EQ(blob[entry(0) + PRT_BLOB_SEC_OFF_LAYOUT_VERSION], 1u);
  EXPECT_EQ(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT), 3u);

  const size_t at = scne_section(blob).second;
  const uint8_t* p = blob.data() + at;
  prt_blob_scne_header h;
  prt_blob_scne_read_header(p, &h);
  EXPECT_EQ(h.objects, 3u);
  EXPECT_EQ(h.record_size, PRT_BLOB_SCNE_RECORD_SIZE);
  std::string strings;
  for (const SceneManifestObject& o : objects) strings += o.name + o.blob;
  EXPECT_EQ(h.string_size, strings.size());
  EXPECT_EQ(get_u32(blob, at + PRT_BLOB_SCNE_OFF_RESERVED), 0u);
  EXPECT_EQ(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_RAW_SIZE), prt_blob_scne_raw_size(&h));
  EXPECT_EQ(string_at(blob, 0, h.string_size), strings);  // name then path, in record order

  uint32_t offset = 0;
  for (uint32_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const SceneManifestObject& o = objects[i];
    prt_blob_scne_record r;
    prt_blob_scne_read_record(p, &h, i, &r);
    EXPECT_EQ(r.technique, o.technique_tag);
    EXPECT_EQ(r.flags, 0u);
    EXPECT_EQ(r.name_offset, offset);
    EXPECT_EQ(r.name_size, o.name.size());
    EXPECT_EQ(r.blob_offset, offset + o.name.size());
    EXPECT_EQ(r.blob_size, o.blob.size());
    EXPECT_EQ(string_at(blob, r.name_offset, r.name_size), o.name);
    EXPECT_EQ(string_at(blob, r.blob_offset, r.blob_size), o.blob);
    EXPECT_EQ(r.node, o.node);
    EXPECT_EQ(get_u32(blob, record_field(blob, i, PRT_BLOB_SCNE_REC_RESERVED)), 0u);
    for (int k = 0; k < 16; ++k) EXPECT_EQ(r.rest[k], o.rest[size_t(k)]) << k;
    offset += uint32_t(o.name.size() + o.blob.size());
  }
}

TEST(SceneManifest, DefaultsAreNoNodeAndIdentity) {
  const SceneManifestObject o;
  EXPECT_EQ(o.node, PRT_BLOB_SCNE_NO_NODE);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_EQ(o.rest[size_t(4 * c + r)], c == r ? 1.0f : 0.0f);
}

TEST(SceneManifest, InfoAndProducer) {
  SceneManifestOptions options;
  options.producer = "prtkit-test";
  options.info = "a test scene";
  const Bytes blob = write_scene_manifest(three_objects(), options);
  EXPECT_EQ(validate_full(blob).first, PRT_OK) << validate_full(blob).second;
  EXPECT_EQ(std::memcmp(blob.data() + PRT_BLOB_OFF_PRODUCER, "prtkit-test\0\0\0\0\0", 16), 0);
  ASSERT_EQ(get_u32(blob, PRT_BLOB_OFF_SECTION_COUNT), 2u);
  EXPECT_EQ(get_u32(blob, entry(0) + PRT_BLOB_SEC_OFF_TAG), PRT_BLOB_TAG_INFO);
  const size_t info = size_t(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_OFFSET));
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(blob.data()) + info, options.info.size()),
            options.info);
  EXPECT_EQ(get_u32(blob, entry(1) + PRT_BLOB_SEC_OFF_TAG), PRT_BLOB_TAG_SCNE);
}

TEST(SceneManifest, IsDeterministic) {
  EXPECT_EQ(write_scene_manifest(three_objects()), write_scene_manifest(three_objects()));
}

TEST(SceneManifest, EmptySceneIsValid) {
  const Bytes blob = write_scene_manifest({});
  const auto [r, msg] = validate_full(blob);
  EXPECT_EQ(r, PRT_OK) << msg;
  EXPECT_EQ(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_RAW_SIZE), PRT_BLOB_SCNE_HEADER_SIZE);
  EXPECT_EQ(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT), 0u);
}

// A technique tag no kind names is the runtime's to refuse, not the format's.
TEST(SceneManifest, UnknownPrintableTagIsValid) {
  const Bytes blob = write_scene_manifest({object(PRT_BLOB_TAG('N', 'E', 'W', '!'), "a", "a")});
  EXPECT_EQ(validate_full(blob).first, PRT_OK) << validate_full(blob).second;
}

// Longer records (a later minor version's) are skipped by readers of layout 1.
TEST(SceneManifest, LongerRecordsAreSkipped) {
  const std::vector<SceneManifestObject> objects = three_objects();
  const Bytes written = write_scene_manifest(objects);
  const size_t at = scne_section(written).second;
  prt_blob_scne_header h;
  prt_blob_scne_read_header(written.data() + at, &h);
  // The same section with 112-byte records (16 bytes of a later field each), as a new blob.
  Bytes section(PRT_BLOB_SCNE_HEADER_SIZE + 3 * 112 + h.string_size, 0);
  std::memcpy(section.data(), written.data() + at, PRT_BLOB_SCNE_HEADER_SIZE);
  prt_le_store_u32(section.data() + PRT_BLOB_SCNE_OFF_RECORD_SIZE, 112);
  for (size_t i = 0; i < 3; ++i) {
    std::memcpy(section.data() + 16 + 112 * i, written.data() + at + 16 + 96 * i, 96);
    std::memset(section.data() + 16 + 112 * i + 96, 0xA5, 16);
  }
  std::memcpy(section.data() + 16 + 3 * 112, written.data() + at + prt_blob_scne_strings(&h),
              h.string_size);
  prt::format::BlobWriter writer;
  prt::format::SectionOptions required;
  required.required = true;
  writer.add_section(PRT_BLOB_TAG_SCNE, section.data(), section.size(), 3, required);
  const Bytes blob = writer.finish();
  EXPECT_EQ(validate_full(blob).first, PRT_OK) << validate_full(blob).second;
  prt_blob_scne_header h2;
  const uint8_t* p = blob.data() + scne_section(blob).second;
  prt_blob_scne_read_header(p, &h2);
  prt_blob_scne_record r;
  prt_blob_scne_read_record(p, &h2, 2, &r);
  EXPECT_EQ(r.technique, kPstr);
  EXPECT_EQ(r.blob_size, objects[2].blob.size());
}

// --- The header rules, one written blob patched per rule --------------------------------------

TEST(SceneManifestChecker, SectionShorterThanTheHeader) {
  const uint8_t eight[8] = {};
  prt::format::BlobWriter writer;
  writer.add_section(PRT_BLOB_TAG_SCNE, eight, sizeof eight, 0);
  EXPECT_REFUSED(validate_full(writer.finish()), PRT_ERROR_CORRUPT,
                 "'SCNE': 8 bytes cannot hold the 16-byte header");
}

TEST(SceneManifestChecker, TooManyObjects) {
  EXPECT_REFUSED(patched(write_scene_manifest(three_objects()),
                         [](Bytes& b) {
                           put_u32(b, scne_section(b).second + PRT_BLOB_SCNE_OFF_OBJECTS, 65537);
                         }),
                 PRT_ERROR_CORRUPT, "'SCNE': 65537 objects (must be at most 65536)");
}

TEST(SceneManifestChecker, RecordSize) {
  for (uint32_t size : {0u, 80u, 95u, 100u, 104u}) {
    SCOPED_TRACE(size);
    EXPECT_REFUSED(
        patched(write_scene_manifest(three_objects()),
                [size](Bytes& b) {
                  put_u32(b, scne_section(b).second + PRT_BLOB_SCNE_OFF_RECORD_SIZE, size);
                }),
        PRT_ERROR_CORRUPT,
        "'SCNE': record size " + std::to_string(size) + " (must be a multiple of 16, at least 96)");
  }
}

TEST(SceneManifestChecker, ReservedHeaderWord) {
  EXPECT_REFUSED(
      patched(write_scene_manifest(three_objects()),
              [](Bytes& b) { put_u32(b, scne_section(b).second + PRT_BLOB_SCNE_OFF_RESERVED, 1); }),
      PRT_ERROR_CORRUPT, "'SCNE': reserved header field is not zero");
}

TEST(SceneManifestChecker, RawSizeIsTheHeaders) {
  const Bytes blob = write_scene_manifest(three_objects());
  const size_t raw = size_t(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_RAW_SIZE));
  prt_blob_scne_header h;
  prt_blob_scne_read_header(blob.data() + scne_section(blob).second, &h);
  // The string table one byte longer, and records so large that 32-bit arithmetic would wrap.
  EXPECT_REFUSED(patched(blob,
                         [](Bytes& b) {
                           const size_t at = scne_section(b).second;
                           put_u32(b, at + PRT_BLOB_SCNE_OFF_STRING_SIZE,
                                   get_u32(b, at + PRT_BLOB_SCNE_OFF_STRING_SIZE) + 1);
                         }),
                 PRT_ERROR_CORRUPT,
                 "'SCNE': " + std::to_string(raw) + " raw bytes, the header implies " +
                     std::to_string(raw + 1));
  EXPECT_REFUSED(
      patched(blob,
              [](Bytes& b) {
                const size_t at = scne_section(b).second;
                put_u32(b, at + PRT_BLOB_SCNE_OFF_OBJECTS, 65536);
                put_u32(b, at + PRT_BLOB_SCNE_OFF_RECORD_SIZE, 0xFFFF0000u);
              }),
      PRT_ERROR_CORRUPT,
      "the header implies " + std::to_string(16 + 65536ull * 0xFFFF0000u + h.string_size));
}

TEST(SceneManifestChecker, ElementCountIsTheObjectCount) {
  Bytes blob = write_scene_manifest(three_objects());
  put_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 2);
  fix_header_checksum(blob);
  EXPECT_REFUSED(validate_full(blob), PRT_ERROR_CORRUPT,
                 "'SCNE': header says 3 objects, element count 2");
}

// --- The record rules ------------------------------------------------------------------------

// Record 1's u32 field set to `value`.
std::pair<prt_result, std::string> with_field(uint32_t field, uint32_t value) {
  return patched(write_scene_manifest(three_objects()),
                 [=](Bytes& b) { put_u32(b, record_field(b, 1, field), value); });
}

TEST(SceneManifestChecker, TechniqueTagIsPrintable) {
  for (uint32_t tag : {0u, PRT_BLOB_TAG('S', 'H', 'T', 0x1F), PRT_BLOB_TAG(0x7F, 'H', 'T', 'R'),
                       PRT_BLOB_TAG('S', 0x80, 'T', 'R')}) {
    SCOPED_TRACE(tag);
    EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_TECHNIQUE, tag), PRT_ERROR_CORRUPT,
                   "'SCNE': object 1: technique tag 0x");
    EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_TECHNIQUE, tag), PRT_ERROR_CORRUPT,
                   "is not four printable ASCII characters");
  }
  // The printable extremes are tags.
  EXPECT_EQ(with_field(PRT_BLOB_SCNE_REC_TECHNIQUE, PRT_BLOB_TAG(' ', '~', ' ', '~')).first,
            PRT_OK);
}

TEST(SceneManifestChecker, FlagsAreZero) {
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_FLAGS, 4), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: unknown flags 0x4");
}

TEST(SceneManifestChecker, ReservedRecordWord) {
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_RESERVED, 0x100), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: reserved field is not zero");
}

TEST(SceneManifestChecker, NameSize) {
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_NAME_SIZE, 0), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name size 0 (must be 1..255)");
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_NAME_SIZE, 256), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name size 256 (must be 1..255)");
}

TEST(SceneManifestChecker, NameInsideTheStringTable) {
  const Bytes blob = write_scene_manifest(three_objects());
  prt_blob_scne_header h;
  prt_blob_scne_read_header(blob.data() + scne_section(blob).second, &h);
  const uint64_t size = three_objects()[1].name.size();
  const std::string table =
      " are not in the " + std::to_string(h.string_size) + "-byte string table";
  // The last byte one past the end, and an offset whose sum with the size wraps in 32 bits.
  const uint32_t offset = uint32_t(h.string_size - size + 1);
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_NAME_OFFSET, offset), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name bytes " + std::to_string(offset) + ".." +
                     std::to_string(h.string_size) + table);
  EXPECT_EQ(with_field(PRT_BLOB_SCNE_REC_NAME_OFFSET, offset - 1).first, PRT_OK);
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_NAME_OFFSET, 0xFFFFFFFEu), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name bytes 4294967294.." +
                     std::to_string(0xFFFFFFFEull + size - 1) + table);
}

TEST(SceneManifestChecker, BlobPathSize) {
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_BLOB_SIZE, 0), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path size 0 (must be 1..1024)");
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_BLOB_SIZE, 1025), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path size 1025 (must be 1..1024)");
}

TEST(SceneManifestChecker, BlobPathInsideTheStringTable) {
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_BLOB_OFFSET, 0xFFFFFFF0u), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path bytes 4294967280..");
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_BLOB_SIZE, 1024), PRT_ERROR_CORRUPT,
                 "are not in the");
}

// Object 1 written with a stand-in string of the same size, then the stored bytes replaced by
// `text`: the name (or the blob path) the writer would refuse.
std::pair<prt_result, std::string> with_string(bool name, const std::string& text) {
  std::vector<SceneManifestObject> objects = three_objects();
  (name ? objects[1].name : objects[1].blob) = std::string(text.size(), 'x');
  return patched(write_scene_manifest(objects), [&](Bytes& b) {
    const size_t at = scne_section(b).second;
    prt_blob_scne_header h;
    prt_blob_scne_read_header(b.data() + at, &h);
    prt_blob_scne_record r;
    prt_blob_scne_read_record(b.data() + at, &h, 1, &r);
    const size_t strings = at + size_t(prt_blob_scne_strings(&h));
    std::memcpy(b.data() + strings + (name ? r.name_offset : r.blob_offset), text.data(),
                text.size());
  });
}

TEST(SceneManifestChecker, NameHasNoNul) {
  EXPECT_REFUSED(with_string(true, std::string("cr\0te", 5)), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name has a NUL byte (byte 2)");
}

TEST(SceneManifestChecker, NameIsUtf8) {
  EXPECT_REFUSED(with_string(true, "cr\xC3\x28te"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: name is not UTF-8 (byte 2)");
}

TEST(SceneManifestChecker, BlobPathHasNoNul) {
  EXPECT_REFUSED(with_string(false, std::string("a.prtk\0", 7)), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a NUL byte (byte 6)");
}

TEST(SceneManifestChecker, BlobPathIsUtf8) {
  EXPECT_REFUSED(with_string(false, "props/\xFF.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path is not UTF-8 (byte 6)");
}

TEST(SceneManifestChecker, BlobPathHasNoBackslash) {
  EXPECT_REFUSED(with_string(false, "props\\crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a backslash (byte 5)");
}

TEST(SceneManifestChecker, BlobPathIsNotAbsolute) {
  EXPECT_REFUSED(with_string(false, "/props/crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path starts with '/'");
}

TEST(SceneManifestChecker, BlobPathHasNoColon) {
  EXPECT_REFUSED(with_string(false, "C:/crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a ':' (byte 1)");
  EXPECT_REFUSED(with_string(false, "https://x/crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a ':' (byte 5)");
  EXPECT_REFUSED(with_string(false, "crate.prtk:stream"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a ':' (byte 10)");
}

TEST(SceneManifestChecker, BlobPathHasNoEmptyComponent) {
  EXPECT_REFUSED(with_string(false, "props//crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has an empty component (byte 6)");
  EXPECT_REFUSED(with_string(false, "props/"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has an empty component (byte 6)");
}

TEST(SceneManifestChecker, BlobPathHasNoDotComponent) {
  EXPECT_REFUSED(with_string(false, "./crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a '.' component (byte 0)");
  EXPECT_REFUSED(with_string(false, "props/."), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a '.' component (byte 6)");
}

TEST(SceneManifestChecker, BlobPathHasNoDotDotComponent) {
  EXPECT_REFUSED(with_string(false, "../crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a '..' component (byte 0)");
  EXPECT_REFUSED(with_string(false, "props/../../crate.prtk"), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: blob path has a '..' component (byte 6)");
}

// Names that only look like the refused components are plain names.
TEST(SceneManifestChecker, DotsInsideComponentsAreFine) {
  for (const char* path : {"...", ".hidden/a..b/c.", "..a/b../.c"}) {
    EXPECT_EQ(with_string(false, path).first, PRT_OK) << path;
    EXPECT_NO_THROW(write_scene_manifest({object(kShtr, "a", path)})) << path;
  }
}

TEST(SceneManifestChecker, RestIsFinite) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const struct {
    uint32_t k;
    float value;
  } cases[] = {{0, nan}, {12, inf}, {15, -inf}};
  for (const auto& c : cases) {
    uint32_t bits;
    std::memcpy(&bits, &c.value, sizeof bits);
    EXPECT_REFUSED(
        with_field(PRT_BLOB_SCNE_REC_REST + 4 * c.k, bits), PRT_ERROR_NON_FINITE,
        "'SCNE': object 1: rest matrix element " + std::to_string(c.k) + " is not finite");
  }
}

TEST(SceneManifestChecker, RestLastRowIsAffine) {
  const float one = 1.0f, half = 0.5f;
  uint32_t one_bits, half_bits;
  std::memcpy(&one_bits, &one, 4);
  std::memcpy(&half_bits, &half, 4);
  for (uint32_t k : {3u, 7u, 11u}) {
    EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_REST + 4 * k, one_bits), PRT_ERROR_CORRUPT,
                   "'SCNE': object 1: rest matrix's last row is");
  }
  EXPECT_REFUSED(with_field(PRT_BLOB_SCNE_REC_REST + 4 * 15, half_bits), PRT_ERROR_CORRUPT,
                 "'SCNE': object 1: rest matrix's last row is (0, 0, 0, 0.5), not (0, 0, 0, 1)");
  // -0 is 0.
  EXPECT_EQ(with_field(PRT_BLOB_SCNE_REC_REST + 4 * 7, 0x80000000u).first, PRT_OK);
}

// The first bad record is reported, in record order.
TEST(SceneManifestChecker, FirstBadRecordIsReported) {
  EXPECT_REFUSED(patched(write_scene_manifest(three_objects()),
                         [](Bytes& b) {
                           put_u32(b, record_field(b, 2, PRT_BLOB_SCNE_REC_FLAGS), 1);
                           put_u32(b, record_field(b, 1, PRT_BLOB_SCNE_REC_RESERVED), 1);
                         }),
                 PRT_ERROR_CORRUPT, "'SCNE': object 1: reserved field is not zero");
}

// --- The writer refuses what the checker refuses ---------------------------------------------

void expect_refused(const std::vector<SceneManifestObject>& objects, const std::string& text) {
  try {
    write_scene_manifest(objects);
    ADD_FAILURE() << "no exception; expected: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(SceneManifestWriter, RefusesBadNames) {
  expect_refused({object(kShtr, "", "a.prtk")}, "object 0: name size 0 (must be 1..255)");
  expect_refused({object(kShtr, "ok", "ok.prtk"), object(kShtr, std::string(256, 'n'), "a")},
                 "object 1: name size 256 (must be 1..255)");
  expect_refused({object(kShtr, std::string("a\0b", 3), "a.prtk")},
                 "object 0: name has a NUL byte (byte 1)");
  expect_refused({object(kShtr, "caf\xE9", "a.prtk")}, "object 0: name is not UTF-8 (byte 3)");
  EXPECT_NO_THROW(write_scene_manifest({object(kShtr, std::string(255, 'n'), "a")}));
}

TEST(SceneManifestWriter, RefusesBadPaths) {
  const struct {
    const char* path;
    const char* message;
  } cases[] = {
      {"", "blob path size 0 (must be 1..1024)"},
      {"../up.prtk", "blob path has a '..' component"},
      {"a/./b.prtk", "blob path has a '.' component"},
      {"a//b.prtk", "blob path has an empty component"},
      {"a/", "blob path has an empty component"},
      {"/abs.prtk", "blob path starts with '/'"},
      {"C:/x.prtk", "blob path has a ':'"},
      {"a\\b.prtk", "blob path has a backslash"},
      {"a\xC0\xAF.prtk", "blob path is not UTF-8"},
  };
  for (const auto& c : cases) expect_refused({object(kShtr, "a", c.path)}, c.message);
  expect_refused({object(kShtr, "a", std::string(1025, 'p'))},
                 "blob path size 1025 (must be 1..1024)");
  expect_refused({object(kShtr, "a", std::string("a\0b", 3))}, "blob path has a NUL byte");
  EXPECT_NO_THROW(write_scene_manifest({object(kShtr, "a", std::string(1024, 'p'))}));
}

TEST(SceneManifestWriter, RefusesBadTagsAndMatrices) {
  expect_refused({object(0, "a", "a")}, "object 0: technique tag 0x00000000");
  SceneManifestObject o = object(kShtr, "a", "a");
  o.rest[5] = std::numeric_limits<float>::quiet_NaN();
  expect_refused({o}, "object 0: rest matrix element 5 is not finite");
  o.rest[5] = 1.0f;
  o.rest[11] = 1.0f;  // a projection, not a placement
  expect_refused({o}, "object 0: rest matrix's last row");
}

TEST(SceneManifestWriter, RefusesBadInfoAndTooManyObjects) {
  SceneManifestOptions options;
  options.info = "bad \xFF";
  try {
    write_scene_manifest({}, options);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'INFO' is not UTF-8"), std::string::npos) << e.what();
  }
  const std::vector<SceneManifestObject> many(PRT_BLOB_SCNE_MAX_OBJECTS + 1,
                                              object(kShtr, "a", "a"));
  expect_refused(many, "65537 objects (must be at most 65536)");
}

// Distinct names are the baker's business: the format does not compare them.
TEST(SceneManifestWriter, RepeatedNamesAreValid) {
  const Bytes blob =
      write_scene_manifest({object(kShtr, "twin", "a.prtk"), object(kWvlt, "twin", "b.prtk")});
  EXPECT_EQ(validate_full(blob).first, PRT_OK);
}

// --- The golden manifest ---------------------------------------------------------------------

const char kGoldenInfo[] = "prtkit golden scene manifest 1.0: the technique blobs of golden/1.0";

// The generator's objects, restated: each golden technique blob, without a node, at rest.
std::vector<SceneManifestObject> golden_objects() {
  return {object(kShtr, "sh_quad", "sh_quad.prtk"),
          object(kWvlt, "wavelet_quad", "wavelet_quad.prtk"),
          object(kClth, "cloth_quad", "cloth_quad.prtk"),
          object(kSfld, "shadowfield_quad", "shadowfield_quad.prtk"),
          object(kPstr, "pose_hinge", "pose_hinge.prtk")};
}

std::string golden_manifest_path() {
  return std::string(PRT_GOLDEN_DIR) + "/1.0/scene_quads.prts";
}

TEST(GoldenSceneManifest, ContainerFacts) {
  const Bytes blob = read_file(golden_manifest_path());
  ASSERT_EQ(blob.size(), 880u);
  const auto [r, msg] = validate_full(blob);
  ASSERT_EQ(r, PRT_OK) << msg;
  EXPECT_EQ(std::memcmp(blob.data() + PRT_BLOB_OFF_PRODUCER, "prtkit-golden\0\0\0", 16), 0);
  EXPECT_EQ(get_u32(blob, PRT_BLOB_OFF_CHECKSUM), 0x3EB1C4EEu);
  ASSERT_EQ(get_u32(blob, PRT_BLOB_OFF_SECTION_COUNT), 2u);
  // INFO at align16(64 + 2 x 48) = 160, 67 bytes; SCNE at align16(227) = 240:
  // 16 + 5 x 96 + 135 = 631 bytes; total align16(871) = 880.
  const struct {
    uint32_t tag, flags, checksum;
    uint64_t offset, size, elements;
  } expected[2] = {
      {PRT_BLOB_TAG_INFO, 0, 0x3BE9E517u, 160, sizeof kGoldenInfo - 1, sizeof kGoldenInfo - 1},
      {PRT_BLOB_TAG_SCNE, PRT_BLOB_SECTION_REQUIRED, 0xED4F38BDu, 240, 631, 5}};
  for (uint32_t i = 0; i < 2; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(get_u32(blob, entry(i) + PRT_BLOB_SEC_OFF_TAG), expected[i].tag);
    EXPECT_EQ(blob[entry(i) + PRT_BLOB_SEC_OFF_FLAGS], expected[i].flags);
    EXPECT_EQ(blob[entry(i) + PRT_BLOB_SEC_OFF_CODEC], PRT_BLOB_CODEC_NONE);
    EXPECT_EQ(blob[entry(i) + PRT_BLOB_SEC_OFF_LAYOUT_VERSION], 1u);
    EXPECT_EQ(get_u32(blob, entry(i) + PRT_BLOB_SEC_OFF_CHECKSUM), expected[i].checksum);
    EXPECT_EQ(get_u64(blob, entry(i) + PRT_BLOB_SEC_OFF_OFFSET), expected[i].offset);
    EXPECT_EQ(get_u64(blob, entry(i) + PRT_BLOB_SEC_OFF_STORED_SIZE), expected[i].size);
    EXPECT_EQ(get_u64(blob, entry(i) + PRT_BLOB_SEC_OFF_RAW_SIZE), expected[i].size);
    EXPECT_EQ(get_u64(blob, entry(i) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT), expected[i].elements);
  }
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(blob.data()) + 160, sizeof kGoldenInfo - 1),
            kGoldenInfo);
}

TEST(GoldenSceneManifest, Records) {
  const Bytes blob = read_file(golden_manifest_path());
  ASSERT_EQ(blob.size(), 880u);
  const uint8_t* p = blob.data() + 240;
  prt_blob_scne_header h;
  prt_blob_scne_read_header(p, &h);
  EXPECT_EQ(h.objects, 5u);
  EXPECT_EQ(h.record_size, 96u);
  EXPECT_EQ(h.string_size, 135u);  // 7+12 + 12+17 + 10+15 + 16+21 + 10+15
  const struct {
    uint32_t tag, name_offset, name_size, blob_offset, blob_size;
    const char* name;
  } expected[5] = {{kShtr, 0, 7, 7, 12, "sh_quad"},
                   {kWvlt, 19, 12, 31, 17, "wavelet_quad"},
                   {kClth, 48, 10, 58, 15, "cloth_quad"},
                   {kSfld, 73, 16, 89, 21, "shadowfield_quad"},
                   {kPstr, 110, 10, 120, 15, "pose_hinge"}};
  for (uint32_t i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    prt_blob_scne_record r;
    prt_blob_scne_read_record(p, &h, i, &r);
    EXPECT_EQ(r.technique, expected[i].tag);
    EXPECT_EQ(r.flags, 0u);
    EXPECT_EQ(r.name_offset, expected[i].name_offset);
    EXPECT_EQ(r.name_size, expected[i].name_size);
    EXPECT_EQ(r.blob_offset, expected[i].blob_offset);
    EXPECT_EQ(r.blob_size, expected[i].blob_size);
    EXPECT_EQ(r.node, 0xFFFFFFFFu);
    EXPECT_EQ(string_at(blob, r.name_offset, r.name_size), expected[i].name);
    EXPECT_EQ(string_at(blob, r.blob_offset, r.blob_size), std::string(expected[i].name) + ".prtk");
    for (int k = 0; k < 16; ++k) EXPECT_EQ(r.rest[k], k % 5 == 0 ? 1.0f : 0.0f) << k;
  }
}

// Nothing is compressed, so today's writer makes the frozen bytes exactly.
TEST(GoldenSceneManifest, WriterMakesTheSameBytes) {
  SceneManifestOptions options;
  options.producer = "prtkit-golden";
  options.info = kGoldenInfo;
  EXPECT_EQ(write_scene_manifest(golden_objects(), options), read_file(golden_manifest_path()));
}

// Every object's blob is beside the manifest and holds the section its record names.
TEST(GoldenSceneManifest, BlobsHoldTheirTechniqueSections) {
  for (const SceneManifestObject& o : golden_objects()) {
    SCOPED_TRACE(o.blob);
    Context ctx;
    prt_asset* asset = nullptr;
    const std::string path = std::string(PRT_GOLDEN_DIR) + "/1.0/" + o.blob;
    ASSERT_EQ(prt_asset_load_file(ctx.ctx, path.c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK)
        << prt_context_last_message(ctx.ctx);
    const void* data = nullptr;
    size_t size = 0;
    EXPECT_EQ(prt_asset_section_data(asset, o.technique_tag, &data, &size), PRT_OK);
    EXPECT_GT(size, 0u);
    prt_asset_destroy(asset);
  }
}

}  // namespace
