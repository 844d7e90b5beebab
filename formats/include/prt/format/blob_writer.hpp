// SPDX-License-Identifier: MIT
// Writer for the prtkit blob container (formats/SPEC.md), used by the baker.
//
// Output is deterministic: the same sections added in the same order with the same options give
// byte-identical blobs (zstd runs single-threaded at a fixed level, all padding is zero).
// A BlobWriter is a plain value: use one per thread; distinct writers are independent.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <prt/format/blob_layout.h>

namespace prt::format {

// Four ASCII characters in file order as the u32 tag value (PRT_BLOB_TAG in C).
constexpr uint32_t make_tag(char a, char b, char c, char d) {
  return uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 |
         uint32_t(uint8_t(d)) << 24;
}

enum class Compression : uint8_t {
  kNone,  // stored as is (codec none)
  kZstd,  // zstd if the frame is smaller than the raw bytes, else stored as is
};

struct SectionOptions {
  bool required = false;  // readers that do not know (tag, layout_version) must reject the blob
  uint8_t layout_version = PRT_BLOB_LAYOUT_VERSION_1;
  Compression compression = Compression::kNone;
  int zstd_level = 9;  // 1..19; part of the input as far as determinism is concerned
};

class BlobWriter {
 public:
  BlobWriter() = default;

  // 16 opaque bytes identifying the producing tool; a shorter name is zero-padded, a longer one
  // cut to 16 bytes.
  void set_producer(std::string_view name);
  void set_producer(const std::array<uint8_t, PRT_BLOB_PRODUCER_SIZE>& id) { producer_ = id; }
  // Header flags (formats/SPEC.md §Header flags); 1.0 defines none.
  void set_flags(uint32_t flags) { flags_ = flags; }

  // Adds a section holding a copy of `size` bytes (compressed now if asked). Sections are laid out
  // in the order they are added. Throws std::invalid_argument for a tag that is not four printable
  // ASCII characters, a tag already added, a known kind whose size is not element_count times its
  // element size, an element_count larger than the byte count of an unknown kind, or more than
  // PRT_BLOB_MAX_SECTIONS sections. Throws std::runtime_error if zstd fails.
  void add_section(uint32_t tag, const void* data, size_t size, uint64_t element_count,
                   const SectionOptions& options = {});

  size_t section_count() const { return sections_.size(); }

  // The complete blob.
  std::vector<uint8_t> finish() const;
  // finish() written to `path`; throws std::runtime_error naming the file on failure.
  void write_file(const std::string& path) const;

 private:
  struct Section {
    uint32_t tag;
    uint16_t flags;
    uint8_t codec;
    uint8_t layout_version;
    uint32_t checksum;
    uint64_t raw_size;
    uint64_t element_count;
    std::vector<uint8_t> stored;
  };

  std::array<uint8_t, PRT_BLOB_PRODUCER_SIZE> producer_{};
  uint32_t flags_ = 0;
  std::vector<Section> sections_;
};

}  // namespace prt::format
