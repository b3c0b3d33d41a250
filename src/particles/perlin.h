// Ken Perlin's improved gradient noise (Perlin 2002) in three and four dimensions, seeded by a
// permutation of 0..255: the shape source of the particle clouds (seed 003, 3.3.3), where the
// fourth coordinate is time.
#pragma once

#include <array>
#include <cstdint>

namespace nephele::particles {

class PerlinNoise {
 public:
  explicit PerlinNoise(uint32_t seed);
  // Values in about [-1, 1], 0 at every lattice point; period 256 on every axis.
  float noise3(float x, float y, float z) const;
  float noise4(float x, float y, float z, float w) const;

 private:
  std::array<uint8_t, 512> perm_{};  // the permutation, twice, so indices need no wrap
  int hash(int i) const { return perm_[i & 511]; }
};

}  // namespace nephele::particles
