// SPDX-License-Identifier: MIT
// prt-bake info BLOB: the container and section summary of a blob, read through the runtime
// exactly as a game would (so it also says why a blob is rejected).
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include <prt/prt.hpp>

#include "command.hpp"

namespace prt::bake::cli {
namespace {

std::string tag_text(std::uint32_t tag) {
  std::string text(4, ' ');
  for (int i = 0; i < 4; ++i) text[i] = static_cast<char>((tag >> (8 * i)) & 0xFF);
  return text;
}

std::string producer_text(const std::uint8_t (&producer)[16]) {
  std::string text;
  for (std::uint8_t byte : producer) {
    if (byte == 0) break;
    text += (byte >= 0x20 && byte < 0x7F) ? static_cast<char>(byte) : '?';
  }
  return text;
}

void print_blob(const std::string& path, const prt_asset* asset) {
  prt_asset_info info = prt::sized<prt_asset_info>();
  prt_asset_get_info(asset, &info);
  std::printf("blob: %s\n  format:   %u.%u\n  size:     %" PRIu64
              " bytes\n  flags:    0x%08X\n"
              "  producer: %s\n  sections: %u\n",
              path.c_str(), info.format_major, info.format_minor, info.total_size, info.flags,
              producer_text(info.producer).c_str(), info.section_count);
  std::printf("  %-4s  %-8s %-5s %6s %10s %12s %12s %12s  %s\n", "tag", "flags", "codec", "layout",
              "offset", "stored", "raw", "elements", "checksum");
  for (std::uint32_t i = 0; i < info.section_count; ++i) {
    prt_section_info section = prt::sized<prt_section_info>();
    prt_asset_get_section_info(asset, i, &section);
    std::printf("  %-4s  %-8s %-5s %6u %10" PRIu64 " %12" PRIu64 " %12" PRIu64 " %12" PRIu64
                "  0x%08X%s\n",
                tag_text(section.tag).c_str(),
                (section.flags & PRT_SECTION_FLAG_REQUIRED) ? "required" : "optional",
                section.codec == PRT_CODEC_ZSTD ? "zstd" : "none", section.layout_version,
                section.offset, section.stored_size, section.raw_size, section.element_count,
                section.checksum, section.known ? "" : "  (unknown to this runtime)");
  }
}

void run_info(const std::string& path, bool quick, CommandEnv& env) {
  const prt::ContextPtr context = prt::create_context().handle;
  if (!context) throw Error("cannot create a context");
  const auto [asset, result] = prt::load_asset_file(context.get(), path.c_str(),
                                                    quick ? PRT_VALIDATE_QUICK : PRT_VALIDATE_FULL);
  if (result != PRT_OK) {
    throw Error(path + ": " + prt_result_string(result) + ": " +
                prt_context_last_message(context.get()));
  }
  print_blob(path, asset.get());
  env.context().info(path + ": valid (" + (quick ? "quick" : "full") + " validation)");
}

}  // namespace

void add_info_command(CLI::App& app, CommandEnv& env) {
  auto* cmd = app.add_subcommand(
      "info", "Print a blob's container and section summary (validated through the runtime)");
  auto path = std::make_shared<std::string>();
  auto quick = std::make_shared<bool>(false);
  cmd->add_option("BLOB", *path, "Blob file (.prtk)")->required();
  cmd->add_flag("--quick", *quick, "Quick validation only (structure; no checksums or contents)");
  cmd->callback([&env, path, quick] { run_info(*path, *quick, env); });
}

}  // namespace prt::bake::cli
