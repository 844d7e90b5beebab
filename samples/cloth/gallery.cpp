// SPDX-License-Identifier: MIT
#include "gallery.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace prt::cloth_app {
namespace {

constexpr int kGap = 4;  // black pixels between the tiles
const std::uint8_t kWhite[3] = {255, 255, 255};

// `text` broken into lines no wider than `width` at `scale`, after a space or an underscore
// (a word wider than that stays whole).
std::string wrapped(const std::string& text, int width, int scale) {
  std::string out, line;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find_first_of(" _", at);
    end = end == std::string::npos ? text.size() : end + 1;
    const std::string word = text.substr(at, end - at);
    if (!line.empty() && prt::io::text_width(line + word, scale) > width) {
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out += line + "\n";
      line.clear();
    }
    line += word;
    at = end;
  }
  return out + line;
}

// The picture with a strip below it holding `label`, centred, white on black; `lines` lines
// high, so that the tiles line up.
prt::io::Rgb8Image labelled(const prt::io::Rgb8Image& picture, const std::string& label, int scale,
                            int lines) {
  const int strip = (10 * lines + 2) * scale;
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
  std::vector<std::string> texts;
  int lines = 1;
  for (std::size_t i = 0; i < pictures.size(); ++i) {
    texts.push_back(wrapped(i < labels.size() ? labels[i] : "", pictures[i].width - 4, scale));
    lines = std::max(lines, int(std::count(texts.back().begin(), texts.back().end(), '\n')) + 1);
  }
  std::vector<prt::io::Rgb8Image> tiles;
  for (std::size_t i = 0; i < pictures.size(); ++i)
    tiles.push_back(labelled(pictures[i], texts[i], scale, lines));
  const prt::io::Rgb8Image grid = prt::io::tile_rgb8(tiles, columns, kGap);
  prt::io::Rgb8Image out = grid;
  const std::string caption_lines = wrapped(caption, grid.width - 6 * scale, scale);
  const int strip = caption.empty() ? 0 : prt::io::text_height(caption_lines, scale) + 6 * scale;
  out.height += strip;
  out.rgb.resize(std::size_t(out.width) * out.height * 3, 0);
  if (!caption.empty())
    prt::io::draw_text(out, 3 * scale, grid.height + 3 * scale, scale, caption_lines, kWhite);
  prt::io::write_rgb8_png(path, out);
}

}  // namespace prt::cloth_app
