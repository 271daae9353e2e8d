#pragma once
// Number formatting for values tests record with RecordProperty (read by
// scripts/validation_report.sh): 5 significant digits, exponent when needed.
#include <cstdio>
#include <string>

namespace gpudem::test {

inline std::string significant(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5g", value);
  return text;
}

}  // namespace gpudem::test
