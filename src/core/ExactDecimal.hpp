#pragma once
/// The shortest decimal text that reads back to exactly the same double (std::to_chars), for
/// values a user or a reader must get back bit for bit: XDMF times, time steps in messages.
#include <charconv>
#include <string>

namespace gpudem {

inline std::string exact_decimal(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  if (result.ec != std::errc()) return std::to_string(value);
  return std::string(text, result.ptr);
}

}  // namespace gpudem
