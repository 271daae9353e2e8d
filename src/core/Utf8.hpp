#pragma once
/// UTF-8 validity (RFC 3629), checked before text goes to the TOML parser: a TOML document must
/// be UTF-8, and toml11 3.7 reads past its buffer when it reports invalid UTF-8 in a string.
#include <cstddef>
#include <optional>
#include <string>

namespace gpudem {

/// The number of continuation bytes after lead byte `b`, -1 when `b` cannot start a character.
/// `lo`..`hi` is the range the first continuation byte must lie in (it rules out overlong
/// forms, surrogates and code points past U+10FFFF).
inline int utf8_continuations(unsigned char b, unsigned char& lo, unsigned char& hi) {
  lo = 0x80;
  hi = 0xBF;
  if (b < 0x80) return 0;
  if (b >= 0xC2 && b <= 0xDF) return 1;
  if (b >= 0xE0 && b <= 0xEF) {
    if (b == 0xE0) lo = 0xA0;
    if (b == 0xED) hi = 0x9F;
    return 2;
  }
  if (b >= 0xF0 && b <= 0xF4) {
    if (b == 0xF0) lo = 0x90;
    if (b == 0xF4) hi = 0x8F;
    return 3;
  }
  return -1;
}

/// The offset of the first byte of `text` where a valid UTF-8 sequence breaks; none when all of
/// it is valid.
inline std::optional<std::size_t> first_invalid_utf8(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size()) {
    unsigned char lo = 0, hi = 0;
    const int more = utf8_continuations(static_cast<unsigned char>(text[i]), lo, hi);
    if (more < 0) return i;
    for (int k = 1; k <= more; ++k) {
      if (i + k >= text.size()) return i;
      const auto c = static_cast<unsigned char>(text[i + k]);
      if (c < (k == 1 ? lo : 0x80) || c > (k == 1 ? hi : 0xBF)) return i;
    }
    i += static_cast<std::size_t>(more) + 1;
  }
  return std::nullopt;
}

}  // namespace gpudem
