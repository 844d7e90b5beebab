// SPDX-License-Identifier: MIT
#include "pose_ground_truth.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace prt::bake {
namespace {

// .npy 1.0: magic, version, header length, a Python dict padded with spaces to a multiple of
// 64 bytes (ending in a newline), then the data. Little-endian hosts only, as the baker is.
void write_npy(const std::string& path, const std::vector<std::size_t>& shape, const float* data) {
  std::string dims;
  std::size_t count = 1;
  for (std::size_t d : shape) {
    dims += std::to_string(d) + ",";
    count *= d;
  }
  if (shape.size() > 1) dims.pop_back();
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + dims + "), }";
  const std::size_t prefix = 10;
  header.append(64 - (prefix + header.size() + 1) % 64, ' ');
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  const std::uint16_t length = static_cast<std::uint16_t>(header.size());
  out.write("\x93NUMPY\x01\x00", 8);
  out.put(static_cast<char>(length & 0xff));
  out.put(static_cast<char>(length >> 8));
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(data),
            static_cast<std::streamsize>(count * sizeof(float)));
  if (!out) throw Error(path + ": cannot write the ground truth");
}

}  // namespace

void write_pose_ground_truth(const std::string& prefix, const PoseTrainingSet& training) {
  const std::size_t frames = training.frames.size(), joints = training.joint_count();
  write_npy(prefix + ".transfer.npy", {frames, training.vertex_count, training.coefficient_count()},
            training.transfer.data());
  std::vector<float> rotations, times;
  rotations.reserve(frames * joints * 4);
  for (const PoseFrame& frame : training.frames) {
    for (const glm::quat& q : frame.rotations)
      rotations.insert(rotations.end(), {q.x, q.y, q.z, q.w});
    times.insert(times.end(), {static_cast<float>(frame.clip), frame.time});
  }
  write_npy(prefix + ".rotations.npy", {frames, joints, 4}, rotations.data());
  write_npy(prefix + ".times.npy", {frames, 2}, times.data());
}

}  // namespace prt::bake
