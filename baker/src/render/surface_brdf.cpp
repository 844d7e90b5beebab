// SPDX-License-Identifier: MIT
// The surface BRDF's text form (prt-bake reference --brdf).
#include <cmath>
#include <sstream>
#include <vector>

#include "prt/baker/reference.hpp"
#include "prt/baker/text.hpp"

namespace prt::bake {
namespace {

// "a,b,c" as numbers; false on anything else.
bool parse_numbers(const std::string& text, std::vector<double>* numbers) {
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      return false;
    }
    if (used != item.size() || !std::isfinite(value)) return false;
    numbers->push_back(value);
  }
  return !numbers->empty() && text.back() != ',';
}

}  // namespace

SurfaceBrdf parse_surface_brdf(const std::string& text) {
  if (text == "lambert") return SurfaceBrdf::lambert();
  const std::size_t colon = text.find(':');
  const std::string model = text.substr(0, colon);
  std::vector<double> numbers;
  const bool parsed = colon != std::string::npos && parse_numbers(text.substr(colon + 1), &numbers);
  if (model == "phong" && parsed && numbers.size() <= 3) {
    PhongBrdf phong;
    phong.exponent = numbers[0];
    if (numbers.size() > 1) phong.specular = numbers[1];
    if (numbers.size() > 2) phong.diffuse = numbers[2];
    check_brdf(phong);
    return SurfaceBrdf::of(phong);
  }
  if (model == "ggx" && parsed && numbers.size() <= 2) {
    GgxBrdf ggx;
    ggx.alpha = numbers[0];
    if (numbers.size() > 1) ggx.f0 = numbers[1];
    check_brdf(ggx);
    return SurfaceBrdf::of(ggx);
  }
  throw Error("--brdf: expected lambert, phong:N[,specular[,diffuse]] or ggx:ALPHA[,F0], got '" +
              text + "'");
}

std::string surface_brdf_name(const SurfaceBrdf& brdf) {
  switch (brdf.model) {
    case SurfaceBrdf::Model::Phong:
      return format("phong:%g,%g,%g", brdf.phong.exponent, brdf.phong.specular, brdf.phong.diffuse);
    case SurfaceBrdf::Model::Ggx:
      return format("ggx:%g,%g", brdf.ggx.alpha, brdf.ggx.f0);
    case SurfaceBrdf::Model::Lambert:
      break;
  }
  return "lambert";
}

}  // namespace prt::bake
