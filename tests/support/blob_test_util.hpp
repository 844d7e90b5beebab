// SPDX-License-Identifier: MIT
// Helpers for the blob tests: reading files, editing fields of a blob in place, and running every
// validation path on a fresh heap copy of exactly the blob's size (so ASan sees any over-read).
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <prt/format/blob_layout.h>
#include <prt/format/blob_reader.h>
#include <prt/prt.hpp>

namespace prt_test {

using Bytes = std::vector<uint8_t>;

inline Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string golden_path() {
  return std::string(PRT_GOLDEN_DIR) + "/1.0/tiny.prtk";
}

inline void put_u16(Bytes& b, size_t off, uint16_t v) {
  prt_le_store_u16(b.data() + off, v);
}
inline void put_u32(Bytes& b, size_t off, uint32_t v) {
  prt_le_store_u32(b.data() + off, v);
}
inline void put_u64(Bytes& b, size_t off, uint64_t v) {
  prt_le_store_u64(b.data() + off, v);
}
inline uint32_t get_u32(const Bytes& b, size_t off) {
  return prt_le_load_u32(b.data() + off);
}
inline uint64_t get_u64(const Bytes& b, size_t off) {
  return prt_le_load_u64(b.data() + off);
}

// Byte offset of table entry i (the table follows the 64-byte header in a canonical blob).
inline size_t entry(uint32_t i) {
  return PRT_BLOB_HEADER_SIZE + i * PRT_BLOB_SECTION_ENTRY_SIZE;
}

// Recomputes the header checksum (SPEC.md §Checksums) after an edit of the header or table.
inline void fix_header_checksum(Bytes& b) {
  const uint32_t header_size = get_u32(b, PRT_BLOB_OFF_HEADER_SIZE);
  const uint32_t count = get_u32(b, PRT_BLOB_OFF_SECTION_COUNT);
  put_u32(b, PRT_BLOB_OFF_CHECKSUM, 0);
  uint32_t crc = prt_crc32c(0, b.data(), header_size);
  crc = prt_crc32c(crc, b.data() + header_size, size_t{count} * PRT_BLOB_SECTION_ENTRY_SIZE);
  put_u32(b, PRT_BLOB_OFF_CHECKSUM, crc);
}

// Recomputes section i's checksum and then the header checksum.
inline void fix_section_checksum(Bytes& b, uint32_t i) {
  const uint64_t off = get_u64(b, entry(i) + PRT_BLOB_SEC_OFF_OFFSET);
  const uint64_t size = get_u64(b, entry(i) + PRT_BLOB_SEC_OFF_STORED_SIZE);
  put_u32(b, entry(i) + PRT_BLOB_SEC_OFF_CHECKSUM, prt_crc32c(0, b.data() + off, size));
  fix_header_checksum(b);
}

// A heap copy of exactly b.size() bytes (nothing readable past the end).
inline std::unique_ptr<uint8_t[]> exact_copy(const Bytes& b) {
  std::unique_ptr<uint8_t[]> p(new uint8_t[b.size() ? b.size() : 1]);
  if (!b.empty()) std::memcpy(p.get(), b.data(), b.size());
  return p;
}

// Outcome of prt_asset_validate on a fresh exact copy.
inline prt_result validate(prt_context* ctx, const Bytes& b, prt_validation level) {
  auto copy = exact_copy(b);
  char msg[256];
  return prt_asset_validate(ctx, copy.get(), b.size(), level, msg, sizeof msg);
}

// Outcome of prt_asset_load_memory on a fresh exact copy (the asset is destroyed again).
inline prt_result load(prt_context* ctx, const Bytes& b, prt_validation level) {
  auto copy = exact_copy(b);
  prt_asset* asset = nullptr;
  const prt_result r = prt_asset_load_memory(ctx, copy.get(), b.size(), level, &asset);
  prt_asset_destroy(asset);
  return r;
}

// A context with the defaults (which do not read the environment).
struct Context {
  prt::ContextPtr owner = prt::create_context().handle;
  prt_context* ctx = owner.get();
};

}  // namespace prt_test
