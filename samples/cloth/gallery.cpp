// SPDX-License-Identifier: MIT
#include "gallery.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace prt::cloth_app {
namespace {

constexpr int kGap = 4;  // black pixels between the tiles
const std::uint8_t kWhite[3] = {255, 255, 255};

// The picture with a strip below it holding `label`, centred, white on black.
prt::io::Rgb8Image labelled(const prt::io::Rgb8Image& picture, const std::string& label,
                            int scale) {
  const int strip = 12 * scale;
  prt::io::Rgb8Image out;
  out.width = picture.width, out.height = picture.height + strip;
  out.rgb.assign(std::size_t(out.width) * out.height * 3, 0);
  std::memcpy(out.rgb.data(), picture.rgb.data(), picture.rgb.size());
  const int x = std::max(0, (out.width - prt::io::text_width(label, scale)) / 2);
  prt::io::draw_text(out, x, picture.height + 3 * scale, scale, label, kWhite);
  return out;
}

}  // namespace

void write_gallery(const std::string& path, const std::vector<prt::io::Rgb8Image>& pictures,
                   const std::vector<std::string>& labels, const std::string& caption) {
  if (pictures.empty()) throw prt::io::Error(path + ": no pictures for the gallery");
  const int columns = int(std::ceil(std::sqrt(double(pictures.size()))));
  // One text size for every label, as large as the narrowest fit allows.
  int scale = std::max(1, pictures[0].height / 120);
  for (const std::string& label : labels)
    while (scale > 1 && prt::io::text_width(label, scale) > pictures[0].width - 4) --scale;
  std::vector<prt::io::Rgb8Image> tiles;
  for (std::size_t i = 0; i < pictures.size(); ++i)
    tiles.push_back(labelled(pictures[i], i < labels.size() ? labels[i] : "", scale));
  const prt::io::Rgb8Image grid = prt::io::tile_rgb8(tiles, columns, kGap);
  prt::io::Rgb8Image out = grid;
  const int strip = caption.empty() ? 0 : prt::io::text_height(caption, scale) + 6 * scale;
  out.height += strip;
  out.rgb.resize(std::size_t(out.width) * out.height * 3, 0);
  if (!caption.empty())
    prt::io::draw_text(out, 3 * scale, grid.height + 3 * scale, scale, caption, kWhite);
  prt::io::write_rgb8_png(path, out);
}

}  // namespace prt::cloth_app
