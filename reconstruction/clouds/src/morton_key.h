#pragma once
// Private to reconstruction/clouds: Z-order (Morton) keys, which sort cells or points so that
// neighbours in space lie near each other in memory.

#include <array>
#include <cstdint>

namespace interlin::detail {

// The low `bits` (<= 21) bits of v[0], v[1], v[2] interleaved: bit b of v[a] at bit 3 b + a.
inline std::uint64_t morton_key(const std::array<std::uint64_t, 3>& v, int bits) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < bits; ++b)
      key |= ((v[size_t(a)] >> b) & 1u) << (3 * b + a);
  return key;
}

} // namespace interlin::detail
