// SPDX-License-Identifier: MIT
// Internal: a bounds-checked walk over a Radiance RGBE file before stb decodes it. stb_image
// (2.27) spins forever on a run-length-encoded file cut short, because at the end of its input
// it keeps reading zero-length runs; this walk mirrors stb's decoder and stops at the end.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace prt::io::detail {

// True when the bytes start with a Radiance signature ("#?RADIANCE" or "#?RGBE").
bool has_radiance_signature(const std::vector<unsigned char>& bytes);

// What the walk saw of the pixel data.
struct RadianceStreamSummary {
  // Texels whose shared exponent is 255, the largest RGBE has: channels of 2^119 to 2^127.
  std::size_t top_exponent_texels = 0;
};

// Throws Error("<path>: ...") when the header is not one stb reads (FORMAT=32-bit_rle_rgbe,
// "-Y H +X W") or the pixel stream, flat or run-length encoded, ends before W x H texels.
RadianceStreamSummary check_radiance_stream(const std::string& path,
                                            const std::vector<unsigned char>& bytes);

}  // namespace prt::io::detail
