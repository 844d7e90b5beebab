// SPDX-License-Identifier: MIT
// Reading a whole input file, for every reader of prt_io and the baker: one place that says why a
// file cannot be read (absent, a directory, no permission) in an Error naming the path.
#pragma once

#include <string>
#include <vector>

namespace prt::io {

std::vector<unsigned char> read_file(const std::string& path);

}  // namespace prt::io
