// SPDX-License-Identifier: MIT
// 2-D Haar transform (prt_wavelet.h): values computed by hand from the definition, the basis's
// properties (orthonormality: Parseval and inverse = transpose), and the documented layout.
#include <gtest/gtest.h>
#include <prt/prt_wavelet.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

std::vector<float> random_face(uint32_t size, uint32_t channels, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> face(size_t(size) * size * channels);
  for (float& f : face) f = unit(rng);
  return face;
}

double sum_of_squares(const std::vector<float>& v) {
  double s = 0.0;
  for (float f : v) s += double(f) * f;
  return s;
}

TEST(Haar, TwoByTwoIsTheDocumentedBlock) {
  // [a b; c d] = [1 2; 3 4]: scaling 5, along x (1-2+3-4)/2 = -1, along y (1+2-3-4)/2 = -2,
  // diagonal (1-2-3+4)/2 = 0.
  std::vector<float> face = {1, 2, 3, 4};
  ASSERT_EQ(prt_haar_forward(2, 1, face.data()), PRT_OK);
  EXPECT_FLOAT_EQ(face[0], 5.0f);
  EXPECT_FLOAT_EQ(face[1], -1.0f);
  EXPECT_FLOAT_EQ(face[2], -2.0f);
  EXPECT_NEAR(face[3], 0.0f, 1e-6f);
}

TEST(Haar, FourByFourByHand) {
  // Rows of 4: one bright texel at (x=1, y=2), value 8. Level 1 (2x2 blocks): the block at
  // (0..1, 2..3) is [0 8; 0 0] -> scaling 4, along x -4, along y 4, diagonal -4, placed at
  // block position (0, 1) of each quadrant. Level 0 on the 2x2 scaling block [0 0; 4 0]:
  // scaling 2, along x 2, along y -2, diagonal -2.
  std::vector<float> face(16, 0.0f);
  face[2 * 4 + 1] = 8.0f;
  ASSERT_EQ(prt_haar_forward(4, 1, face.data()), PRT_OK);
  std::vector<float> expected(16, 0.0f);
  expected[0 * 4 + 0] = 2.0f;   // scaling
  expected[0 * 4 + 1] = 2.0f;   // level 0, along x
  expected[1 * 4 + 0] = -2.0f;  // level 0, along y
  expected[1 * 4 + 1] = -2.0f;  // level 0, diagonal
  expected[1 * 4 + 2] = -4.0f;  // level 1, along x: top-right quadrant, block (0, 1)
  expected[3 * 4 + 0] = 4.0f;   // level 1, along y: bottom-left quadrant, block (0, 1)
  expected[3 * 4 + 2] = -4.0f;  // level 1, diagonal: bottom-right quadrant, block (0, 1)
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(face[i], expected[i], 1e-5f) << "index " << i;
}

TEST(Haar, ConstantFaceHasOnlyTheScalingCoefficient) {
  for (uint32_t size : {1u, 2u, 16u, 128u}) {
    std::vector<float> face(size_t(size) * size * 3);
    for (size_t i = 0; i < face.size(); ++i) face[i] = float(1 + i % 3);  // RGB = (1, 2, 3)
    ASSERT_EQ(prt_haar_forward(size, 3, face.data()), PRT_OK);
    for (uint32_t c = 0; c < 3; ++c) {
      // Orthonormal: the scaling function is 1/size on every texel, so <f, phi> = size * value.
      EXPECT_NEAR(face[c], float(size) * float(c + 1), 1e-4f * size) << size;
    }
    for (size_t i = 3; i < face.size(); ++i) ASSERT_NEAR(face[i], 0.0f, 1e-5f) << size << " " << i;
  }
}

TEST(Haar, InverseUndoesForwardForEveryChannelCount) {
  for (uint32_t channels = 1; channels <= PRT_HAAR_MAX_CHANNELS; ++channels) {
    for (uint32_t size : {1u, 2u, 8u, 64u}) {
      const std::vector<float> original = random_face(size, channels, size * 10 + channels);
      std::vector<float> face = original;
      ASSERT_EQ(prt_haar_forward(size, channels, face.data()), PRT_OK);
      ASSERT_EQ(prt_haar_inverse(size, channels, face.data()), PRT_OK);
      for (size_t i = 0; i < face.size(); ++i) ASSERT_NEAR(face[i], original[i], 1e-5f);
    }
  }
}

TEST(Haar, ParsevalAndDotProductsArePreserved) {
  const uint32_t size = 32;
  std::vector<float> f = random_face(size, 1, 1), g = random_face(size, 1, 2);
  double dot = 0.0;
  for (size_t i = 0; i < f.size(); ++i) dot += double(f[i]) * g[i];
  const double energy = sum_of_squares(f);
  ASSERT_EQ(prt_haar_forward(size, 1, f.data()), PRT_OK);
  ASSERT_EQ(prt_haar_forward(size, 1, g.data()), PRT_OK);
  double dot_coefficients = 0.0;
  for (size_t i = 0; i < f.size(); ++i) dot_coefficients += double(f[i]) * g[i];
  EXPECT_NEAR(sum_of_squares(f), energy, 1e-4 * energy);
  EXPECT_NEAR(dot_coefficients, dot, 1e-4 * std::sqrt(energy * sum_of_squares(g)));
}

TEST(Haar, EachCoefficientIsItsBasisFunction) {
  // The inverse of a unit coefficient is its basis function: unit norm, and supported on a
  // square of (size >> level) texels, as prt_haar_level says.
  const uint32_t size = 16;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      std::vector<float> face(size_t(size) * size, 0.0f);
      face[y * size + x] = 1.0f;
      ASSERT_EQ(prt_haar_inverse(size, 1, face.data()), PRT_OK);
      EXPECT_NEAR(sum_of_squares(face), 1.0, 1e-5);
      const int level = prt_haar_level(size, x, y);
      const uint32_t support = level < 0 ? size : size >> level;
      size_t nonzero = 0;
      for (float v : face) nonzero += std::fabs(v) > 1e-7f;
      EXPECT_EQ(nonzero, size_t(support) * support) << x << "," << y;
    }
  }
}

TEST(Haar, Levels) {
  EXPECT_EQ(prt_haar_level(8, 0, 0), -1);
  EXPECT_EQ(prt_haar_level(8, 1, 0), 0);
  EXPECT_EQ(prt_haar_level(8, 1, 1), 0);
  EXPECT_EQ(prt_haar_level(8, 0, 3), 1);
  EXPECT_EQ(prt_haar_level(8, 7, 4), 2);
  EXPECT_EQ(prt_haar_level(8, 8, 0), -2);
  EXPECT_EQ(prt_haar_level(6, 1, 1), -2);
}

TEST(Haar, RejectsBadArguments) {
  float face[16] = {};
  EXPECT_EQ(prt_haar_forward(0, 1, face), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_forward(3, 1, face), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_forward(2 * PRT_HAAR_MAX_SIZE, 1, face), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_forward(4, 0, face), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_forward(4, PRT_HAAR_MAX_CHANNELS + 1, face), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_forward(4, 1, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_haar_inverse(3, 1, face), PRT_ERROR_INVALID_ARGUMENT);
}

TEST(Haar, LargestFaceWorks) {
  std::vector<float> face(size_t(PRT_HAAR_MAX_SIZE) * PRT_HAAR_MAX_SIZE, 0.25f);
  ASSERT_EQ(prt_haar_forward(PRT_HAAR_MAX_SIZE, 1, face.data()), PRT_OK);
  EXPECT_NEAR(face[0], 0.25f * PRT_HAAR_MAX_SIZE, 1e-2f);
  ASSERT_EQ(prt_haar_inverse(PRT_HAAR_MAX_SIZE, 1, face.data()), PRT_OK);
  EXPECT_NEAR(face[12345], 0.25f, 1e-5f);
}

}  // namespace
