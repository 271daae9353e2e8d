#include "core/StlReader.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/InputError.hpp"
#include "core/Rotation.hpp"

namespace gpudem {
namespace {

using Soup = std::vector<std::array<Vec3, 3>>;

constexpr std::size_t binary_header_bytes = 80;
constexpr std::size_t binary_preamble_bytes = binary_header_bytes + 4;  // header + count
constexpr std::size_t binary_record_bytes = 50;  // normal, 3 corners, attribute
constexpr std::size_t binary_first_corner = 12;  // skips the normal
/// Longest piece of an unexpected ASCII token quoted in an error message.
constexpr std::size_t quoted_token_chars = 40;

// ---- file access -------------------------------------------------------------------------

std::string read_bytes(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path, 0, "", "STL file not found");
  if (fs::is_directory(status)) throw InputError(path, 0, "", "is a directory, not an STL file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, 0, "", "cannot open STL file for reading");
  std::string bytes(static_cast<std::size_t>(in.tellg()), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
    throw InputError(path, 0, "", "error while reading STL file");
  return bytes;
}

std::uint32_t little_endian_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
         static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

double little_endian_f32(const char* p) {
  const std::uint32_t bits = little_endian_u32(p);
  float value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string describe(const Vec3& p) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

// ---- format detection and binary STL -----------------------------------------------------

std::size_t binary_size(std::uint64_t count) {
  return binary_preamble_bytes + binary_record_bytes * count;
}

bool has_binary_size(const std::string& bytes) {
  return bytes.size() >= binary_preamble_bytes &&
         bytes.size() == binary_size(little_endian_u32(bytes.data() + binary_header_bytes));
}

/// True for a file to be parsed as ASCII: not of binary size, starts with "solid" and holds no
/// NUL byte (text never does; binary float data nearly always does).
bool is_ascii(const std::string& bytes) {
  if (has_binary_size(bytes)) return false;
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  return first != std::string::npos &&
         equals_ignoring_case(std::string_view(bytes).substr(first, 5), "solid") &&
         bytes.find('\0') == std::string::npos;
}

/// Throws the error that says why `bytes` is not a binary STL of the right size.
[[noreturn]] void throw_binary_size_error(const std::string& path, const std::string& bytes) {
  const std::string actual = std::to_string(bytes.size()) + " bytes";
  const std::string text_hint = bytes.find('\0') == std::string::npos
                                    ? " (the file looks like text, but ASCII STL starts with "
                                      "'solid')"
                                    : "";
  if (bytes.size() < binary_preamble_bytes)
    throw InputError(path, 0, "",
                     "not an STL file: only " + actual +
                         ", less than the 84-byte header of a binary STL" + text_hint);
  const std::uint32_t count = little_endian_u32(bytes.data() + binary_header_bytes);
  const std::string declared = "the header declares " + std::to_string(count) +
                               " triangles, which need 84 + 50 × " + std::to_string(count) + " = " +
                               std::to_string(binary_size(count)) + " bytes, but the file has " +
                               actual + text_hint;
  if (bytes.size() < binary_size(count))
    throw InputError(path, 0, "", "truncated binary STL: " + declared);
  throw InputError(path, 0, "",
                   "binary STL with " + std::to_string(bytes.size() - binary_size(count)) +
                       " trailing bytes: " + declared);
}

Soup parse_binary(const std::string& path, const std::string& bytes) {
  if (!has_binary_size(bytes)) throw_binary_size_error(path, bytes);
  const std::uint32_t count = little_endian_u32(bytes.data() + binary_header_bytes);
  Soup soup(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + binary_size(t) + binary_first_corner;
    for (int k = 0; k < 3; ++k) {
      const char* corner = record + 12 * k;
      const Vec3 p{little_endian_f32(corner), little_endian_f32(corner + 4),
                   little_endian_f32(corner + 8)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError(path, 0, "",
                         "triangle " + std::to_string(t + 1) + " of " + std::to_string(count) +
                             ": corner " + std::to_string(k + 1) + " has a non-finite coordinate " +
                             describe(p));
      soup[t][k] = p;
    }
  }
  return soup;
}

// ---- ASCII STL ---------------------------------------------------------------------------

enum class NumberStatus { ok, not_a_number, out_of_range };

/// The whole of `token` as a double (an optional leading '+' allowed), independent of locale.
NumberStatus parse_number(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  if (error == std::errc::invalid_argument || stop != end) return NumberStatus::not_a_number;
  if (error == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  return NumberStatus::ok;
}

/// Recursive-descent parser of the ASCII grammar in StlReader.hpp; tracks 1-based lines.
class AsciiParser {
 public:
  AsciiParser(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  Soup parse() {
    expect("solid");
    skip_rest_of_line();
    for (;;) {
      const std::string_view token = next_token();
      if (equals_ignoring_case(token, "facet")) {
        parse_facet();
      } else if (equals_ignoring_case(token, "endsolid")) {
        skip_rest_of_line();
        if (!parse_next_solid()) return std::move(soup_);
      } else {
        fail("expected 'facet' or 'endsolid' but found " + quote(token));
      }
    }
  }

 private:
  /// After an 'endsolid': true when another solid follows, false at the end of the file.
  bool parse_next_solid() {
    const std::string_view token = next_token();
    if (token.empty()) return false;
    if (!equals_ignoring_case(token, "solid"))
      fail("expected 'solid' or the end of the file after 'endsolid' but found " + quote(token));
    skip_rest_of_line();
    return true;
  }

  void parse_facet() {
    const std::string label = "triangle " + std::to_string(soup_.size() + 1);
    expect("normal");
    for (int k = 0; k < 3; ++k) {
      double ignored = 0;
      const std::string_view token = next_token();
      if (parse_number(token, ignored) == NumberStatus::not_a_number)
        fail(label + ": normal component " + quote(token) + " is not a number");
    }
    expect("outer");
    expect("loop");
    std::array<Vec3, 3> corners;
    for (int k = 0; k < 3; ++k) {
      expect("vertex");
      const std::string corner = label + ": corner " + std::to_string(k + 1);
      for (int axis_index = 0; axis_index < 3; ++axis_index)
        axis(corners[k], axis_index) = finite_number(corner);
    }
    expect("endloop");
    expect("endfacet");
    soup_.push_back(corners);
  }

  double finite_number(const std::string& what) {
    const std::string_view token = next_token();
    double value = 0;
    const NumberStatus status = parse_number(token, value);
    if (status == NumberStatus::not_a_number)
      fail(what + ": expected a coordinate but found " + quote(token));
    if (status == NumberStatus::out_of_range || !std::isfinite(value))
      fail(what + ": coordinate " + quote(token) + " is not a finite number");
    return value;
  }

  void expect(std::string_view keyword) {
    const std::string_view token = next_token();
    if (!equals_ignoring_case(token, keyword))
      fail("expected '" + std::string(keyword) + "' but found " + quote(token));
  }

  /// The next white-space separated token; empty at the end of the text.
  std::string_view next_token() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(begin, pos_ - begin);
  }

  void skip_rest_of_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }

  static std::string quote(std::string_view token) {
    if (token.empty()) return "the end of the file";
    if (token.size() > quoted_token_chars)
      return "'" + std::string(token.substr(0, quoted_token_chars)) + "...'";
    return "'" + std::string(token) + "'";
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, line_, "", what);
  }

  const std::string& path_;
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  Soup soup_;
};

// ---- placement ---------------------------------------------------------------------------

bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void require_valid(const MeshPlacement& placement, const std::string& path) {
  auto reject = [&path](const std::string& what) {
    throw InputError(path, 0, "", "mesh placement: " + what);
  };
  if (!(std::isfinite(placement.scale) && placement.scale > 0))
    reject("scale must be positive and finite");
  if (!is_finite(placement.rotation_axis) || norm(placement.rotation_axis) == 0)
    reject("rotation axis must be a finite non-zero vector");
  if (!std::isfinite(placement.rotation_angle)) reject("rotation angle must be finite");
  if (!is_finite(placement.offset)) reject("offset must be finite");
}

/// p' = R (scale · p) + offset for every corner; equal corners stay bit-identical.
void place(Soup& soup, const MeshPlacement& placement, const std::string& path) {
  const Rotation rotation = rotation_about(placement.rotation_axis, placement.rotation_angle);
  for (std::size_t t = 0; t < soup.size(); ++t)
    for (Vec3& p : soup[t]) {
      const Vec3 scaled = placement.scale * p;
      p = rotation.apply(scaled) + placement.offset;
      if (!is_finite(p))
        throw InputError(path, 0, "",
                         "triangle " + std::to_string(t + 1) +
                             ": a placed coordinate overflows the range of double");
    }
}

}  // namespace

Soup read_stl(const std::string& path) {
  const std::string bytes = read_bytes(path);
  Soup soup = is_ascii(bytes) ? AsciiParser(path, bytes).parse() : parse_binary(path, bytes);
  if (soup.empty()) throw InputError(path, 0, "", "STL file contains no triangles");
  return soup;
}

TriangleMesh load_mesh(const std::string& path, const MeshPlacement& placement) {
  require_valid(placement, path);
  Soup soup = read_stl(path);
  place(soup, placement, path);
  TriangleMesh mesh = build_mesh(soup);
  if (mesh.triangles.empty())
    throw InputError(path, 0, "",
                     "all " + std::to_string(soup.size()) + " triangles have zero area");
  return mesh;
}

}  // namespace gpudem
