#pragma once
// One hash for the editor's integer keys (node lattice keys, sorted faces,
// proposals): FNV-style over the entries, then a final mix, since the
// multiplications leave the low bits (which index open-addressing tables)
// weakly mixed.
#include <cstddef>
#include <cstdint>

namespace curvetet::volume::edit {

struct IntegerHash {
  template <class Range>
  std::size_t operator()(const Range& values) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const auto x : values) h = (h ^ static_cast<std::uint64_t>(x)) * 0x100000001b3ull;
    h ^= h >> 29;
    h *= 0xbf58476d1ce4e5b9ull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

} // namespace curvetet::volume::edit
