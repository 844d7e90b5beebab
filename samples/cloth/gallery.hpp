// SPDX-License-Identifier: MIT
// The fabric gallery of --gallery: one picture per fabric, each with its name under it, in a
// grid of about square shape, and a caption saying what they show.
#pragma once

#include <string>
#include <vector>

#include "prt/io/apng.hpp"
#include "prt/io/error.hpp"

namespace prt::cloth_app {

// Throws prt::io::Error naming the file when it cannot be written.
void write_gallery(const std::string& path, const std::vector<prt::io::Rgb8Image>& pictures,
                   const std::vector<std::string>& labels, const std::string& caption);

}  // namespace prt::cloth_app
