// SPDX-License-Identifier: MIT
// Running the project's command-line tools from a test, and reading what they wrote with code of
// the test's own (a CSV table, a float32 .npy array), so a test does not check a tool's output
// with the tool's code.
#pragma once

#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace prt_test {

// `text` as one shell word (single-quoted, embedded quotes escaped).
inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct CommandResult {
  int exit_code = -1;  // the process's exit status; -1 when it did not exit normally
  std::string output;  // what it wrote to stdout and stderr, interleaved
};

// Runs `executable` with `arguments` (shell words: quote paths with shell_quote) through the
// shell, after `environment` (e.g. "PRT_BACKEND=cpu", or ""), with stdout and stderr captured in
// the file `log`, which is kept for a failing test's output.
inline CommandResult run_command(const std::string& executable, const std::string& arguments,
                                 const std::filesystem::path& log,
                                 const std::string& environment = "") {
  const std::string command = environment + (environment.empty() ? "" : " ") +
                              shell_quote(executable) + " " + arguments + " > " +
                              shell_quote(log.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.output = read_text(log);
  return result;
}

// A CSV file with a header line, as rows of (column name -> field); quoted fields (RFC 4180)
// may hold commas.
using CsvTable = std::vector<std::map<std::string, std::string>>;

inline CsvTable read_csv(const std::filesystem::path& path) {
  // RFC 4180 within a line: a quoted field may hold commas and doubled quotes.
  auto split = [](const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        fields.emplace_back();
      } else {
        fields.back() += c;
      }
    }
    return fields;
  };
  std::ifstream in(path);
  std::string line;
  CsvTable rows;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> header = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size(); ++i)
      row[header[i]] = i < fields.size() ? fields[i] : "";
    if (fields.size() != header.size()) row["#fields"] = std::to_string(fields.size());
    rows.push_back(row);
  }
  return rows;
}

// A little-endian float32 .npy array (format 1.0 or 2.0, C order) of shape [rows, columns];
// `rows` is 0 and `values` empty when the file is not one.
struct NpyArray {
  std::size_t rows = 0, columns = 0;
  std::vector<float> values;
};

inline NpyArray read_npy_f32(const std::filesystem::path& path) {
  NpyArray array;
  const std::string bytes = read_text(path);
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) return array;
  const int major = static_cast<unsigned char>(bytes[6]);
  const std::size_t length_bytes = major == 1 ? 2 : 4, start = 8 + length_bytes;
  if (bytes.size() < start) return array;
  std::size_t header_length = 0;
  for (std::size_t i = 0; i < length_bytes; ++i)
    header_length |= std::size_t(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
  if (bytes.size() < start + header_length) return array;
  const std::string header = bytes.substr(start, header_length);
  const std::size_t shape = header.find("'shape': (");
  if (header.find("'descr': '<f4'") == std::string::npos ||
      header.find("'fortran_order': False") == std::string::npos || shape == std::string::npos)
    return array;
  std::size_t rows = 0, columns = 1;
  std::istringstream dims(header.substr(shape + 10));
  char comma = 0;
  if (!(dims >> rows)) return array;
  if (dims >> comma && comma == ',' && !(dims >> columns)) columns = 1;
  const std::size_t count = rows * columns, data = start + header_length;
  if (bytes.size() != data + 4 * count) return array;
  array.rows = rows;
  array.columns = columns;
  array.values.resize(count);
  std::memcpy(array.values.data(), bytes.data() + data, 4 * count);
  return array;
}

// The bytes of a float32 [rows, columns] .npy (format 1.0, little-endian, C order), written
// here from the format's definition rather than by the code under test.
inline std::string npy_f32_bytes(const std::vector<float>& values, std::size_t columns) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(values.size() / columns) + ", " + std::to_string(columns) +
                       "), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes = std::string("\x93NUMPY\x01\x00", 8);
  bytes += char(header.size() & 0xFF);
  bytes += char(header.size() >> 8);
  bytes += header;
  bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * 4);
  return bytes;
}

}  // namespace prt_test
