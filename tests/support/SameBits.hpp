#pragma once
// Whether two arrays hold the same bytes, as the tests of bit-for-bit reproducibility compare
// them (values that compare equal, +0 and -0, differ here; a NaN equals its own copy).
#include <cstring>
#include <vector>

namespace gpudem::test {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  // memcmp must not get an empty vector's data(), which may be null
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace gpudem::test
