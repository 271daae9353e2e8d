#pragma once
/// Checked reading of the tables of a scene file (toml11). Every error is an InputError naming
/// the scene file, the 1-based line of the offending value (of its table when the key is
/// missing; 0 for values given with --set or of unknown origin) and the dotted key, and says
/// what was expected and what was found.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <toml.hpp>

#include "core/InputError.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Edit distance between two words: the least number of single-character insertions,
/// deletions and substitutions turning one into the other (Levenshtein, 1966).
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitution});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// "did you mean 'x'?" for the closest of `candidates` when it is close to `word` (at most two
/// edits, or a third of its length), otherwise the list of valid `what` ("keys", "materials").
inline std::string suggest(const std::string& word, const std::vector<std::string>& candidates,
                           const std::string& what) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  if (!best.empty() && best_distance <= std::max<std::size_t>(2, best.size() / 3)) {
    return "did you mean '" + best + "'?";
  }
  std::string list;
  for (const std::string& candidate : candidates) {
    list += (list.empty() ? "" : ", ") + candidate;
  }
  return "valid " + what + " are: " + list;
}

/// Shortest decimal text of `x` that reads back as the same double ("0.1", "-3", "2e+06").
inline std::string format_number(double x) {
  std::ostringstream out;
  for (int digits = 6; digits <= 17; ++digits) {
    out.str("");
    out.precision(digits);
    out << x;
    if (!std::isfinite(x) || std::strtod(out.str().c_str(), nullptr) == x) break;
  }
  return out.str();
}

inline std::string describe(const toml::value& v);

/// `[1, 0.5, true]` for a short array of numbers and booleans, else its size.
inline std::string describe_array(const toml::array& elements) {
  const bool plain = elements.size() <= 6 &&
                     std::all_of(elements.begin(), elements.end(), [](const toml::value& e) {
                       return e.is_boolean() || e.is_integer() || e.is_floating();
                     });
  if (!plain) return "an array of " + std::to_string(elements.size()) + " elements";
  std::string text;
  for (const toml::value& e : elements) text += (text.empty() ? "" : ", ") + describe(e);
  return "[" + text + "]";
}

/// How an error message shows a value that was found: `-3`, `2.0`, `the string "abc"`.
inline std::string describe(const toml::value& v) {
  switch (v.type()) {
    case toml::value_t::boolean:
      return v.as_boolean() ? "true" : "false";
    case toml::value_t::integer:
      return std::to_string(v.as_integer());
    case toml::value_t::floating: {
      const double x = v.as_floating();
      const bool integral = std::isfinite(x) && x == std::floor(x) && std::abs(x) < 1e15;
      return format_number(x) + (integral ? ".0" : "");
    }
    case toml::value_t::string:
      return "the string \"" + v.as_string().str + "\"";
    case toml::value_t::array:
      return describe_array(v.as_array());
    case toml::value_t::table:
      return "a table";
    default:
      return "a date or time";
  }
}

/// Allowed range of a number and its unit, as error messages state them.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  std::string unit;  ///< shown as " [unit]"; empty for dimensionless values

  bool contains(double x) const {
    const bool above = lo_open ? x > lo : x >= lo;
    const bool below = hi_open ? x < hi : x <= hi;
    return above && below;
  }
  /// `noun` followed by the bounds and the unit: "a number in (-1, 0.5)", "a number > 0 [m]".
  std::string text(const std::string& noun) const {
    std::string s = noun;
    const bool has_lo = std::isfinite(lo);
    const bool has_hi = std::isfinite(hi);
    if (has_lo && has_hi) {
      s += std::string(" in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " +
           format_number(hi) + (hi_open ? ")" : "]");
    } else if (has_lo) {
      s += (lo_open ? " > " : " >= ") + format_number(lo);
    } else if (has_hi) {
      s += (hi_open ? " < " : " <= ") + format_number(hi);
    }
    return unit.empty() ? s : s + " [" + unit + "]";
  }
};

/// Any finite number.
inline Range any_value(std::string unit = "") {
  return Range{-INFINITY, INFINITY, false, false, std::move(unit)};
}
/// x > 0.
inline Range positive(std::string unit = "") {
  return Range{0, INFINITY, true, false, std::move(unit)};
}
/// x >= 0.
inline Range non_negative(std::string unit = "") {
  return Range{0, INFINITY, false, false, std::move(unit)};
}
/// (lo, hi) when both ends are open, (lo, hi] when only `lo_open`, and so on.
inline Range interval(double lo, bool lo_open, double hi, bool hi_open, std::string unit = "") {
  return Range{lo, hi, lo_open, hi_open, std::move(unit)};
}

/// The value of `v` when it is a finite number (integer or float), else nothing.
inline std::optional<double> finite_number(const toml::value& v) {
  if (v.is_integer()) return static_cast<double>(v.as_integer());
  if (v.is_floating() && std::isfinite(v.as_floating())) return v.as_floating();
  return std::nullopt;
}

/// Line of `v` in `file`; 0 when it came from elsewhere (--set) or has no recorded place.
inline int line_in(const toml::value& v, const std::string& file) {
  const toml::source_location where = v.location();
  return where.file_name() == file ? static_cast<int>(where.line()) : 0;
}

/// Read access to one table of the scene. Holds a pointer into the parsed tree, which must
/// outlive the reader.
class TableReader {
 public:
  /// `key` is the table's dotted key ("" for the whole file, "material[1]"), `title` how
  /// messages name it ("[simulation]", "[[material]]").
  TableReader(const toml::value& table, std::string file, std::string key, std::string title)
      : table_(&table), file_(std::move(file)), key_(std::move(key)), title_(std::move(title)) {}

  /// Dotted key of `key` inside this table ("material[1].density").
  std::string path(const std::string& key) const { return key_.empty() ? key : key_ + "." + key; }
  /// Line of `key`'s value, or of this table when `key` is absent (0 for the whole file).
  int line(const std::string& key) const {
    if (has(key)) return line_in(table_->as_table().at(key), file_);
    return key_.empty() ? 0 : line_in(*table_, file_);
  }
  bool has(const std::string& key) const { return table_->as_table().count(key) != 0; }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(file_, line(key), path(key), what);
  }
  [[noreturn]] void fail_found(const std::string& key, const std::string& expected) const {
    fail(key, "expected " + expected + ", got " + describe(value(key)));
  }

  /// Rejects every key not in `valid`, with the nearest valid key as a suggestion. Checked
  /// before any value so that a misspelt key is reported as such, not as a missing one.
  void allow_only(const std::vector<std::string>& valid) const {
    std::vector<std::string> unknown;
    for (const auto& entry : table_->as_table()) {
      if (std::find(valid.begin(), valid.end(), entry.first) == valid.end()) {
        unknown.push_back(entry.first);
      }
    }
    if (unknown.empty()) return;
    const auto first = std::min_element(
        unknown.begin(), unknown.end(), [this](const std::string& a, const std::string& b) {
          return std::make_pair(line(a), a) < std::make_pair(line(b), b);
        });
    const std::string noun = key_.empty() ? "table" : "key";
    const std::string where = title_.empty() ? "" : " in " + title_;
    fail(*first, "unknown " + noun + " '" + *first + "'" + where + "; " +
                     suggest(*first, valid, noun + "s"));
  }

  /// The value of a required key.
  const toml::value& value(const std::string& key) const {
    if (!has(key)) fail(key, "missing required key '" + key + "' in " + title_);
    return table_->as_table().at(key);
  }

  /// A finite number in `range` (integers accepted).
  double number(const std::string& key, const Range& range) const {
    const std::optional<double> x = finite_number(value(key));
    if (!x || !range.contains(*x)) fail_found(key, range.text("a number"));
    return *x;
  }
  double number(const std::string& key, const Range& range, double fallback) const {
    return has(key) ? number(key, range) : fallback;
  }

  std::int64_t integer(const std::string& key, const Range& range) const {
    const toml::value& v = value(key);
    if (!v.is_integer() || !range.contains(static_cast<double>(v.as_integer()))) {
      fail_found(key, range.text("an integer"));
    }
    return v.as_integer();
  }
  std::int64_t integer(const std::string& key, const Range& range, std::int64_t fallback) const {
    return has(key) ? integer(key, range) : fallback;
  }

  /// A non-empty string.
  std::string string(const std::string& key) const {
    const toml::value& v = value(key);
    if (!v.is_string() || v.as_string().str.empty()) fail_found(key, "a non-empty string");
    return v.as_string().str;
  }
  std::string string(const std::string& key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
  }

  /// `true` or `false`, or `fallback` when absent.
  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const toml::value& v = value(key);
    if (!v.is_boolean()) fail_found(key, "true or false");
    return v.as_boolean();
  }

  /// Exactly `size` non-empty strings.
  std::vector<std::string> strings(const std::string& key, std::size_t size) const {
    const toml::value& v = value(key);
    const std::string expected = "an array of " + std::to_string(size) + " non-empty strings";
    if (!v.is_array() || v.as_array().size() != size) fail_found(key, expected);
    std::vector<std::string> result;
    for (const toml::value& e : v.as_array()) {
      if (!e.is_string() || e.as_string().str.empty()) fail_found(key, expected);
      result.push_back(e.as_string().str);
    }
    return result;
  }

  /// One or more distinct non-empty strings.
  std::vector<std::string> names(const std::string& key) const {
    const toml::value& v = value(key);
    const std::string expected = "an array of one or more distinct non-empty strings";
    if (!v.is_array() || v.as_array().empty()) fail_found(key, expected);
    std::vector<std::string> result;
    for (const toml::value& e : v.as_array()) {
      if (!e.is_string() || e.as_string().str.empty()) fail_found(key, expected);
      if (std::find(result.begin(), result.end(), e.as_string().str) != result.end())
        fail_found(key, expected);
      result.push_back(e.as_string().str);
    }
    return result;
  }

  /// One of `options` (strings), or `fallback` when absent.
  std::string choice(const std::string& key, const std::vector<std::string>& options,
                     const std::string& fallback) const {
    if (!has(key)) return fallback;
    const toml::value& v = value(key);
    if (v.is_string() &&
        std::find(options.begin(), options.end(), v.as_string().str) != options.end()) {
      return v.as_string().str;
    }
    fail_found(key, "one of " + quoted_list(options));
  }

  /// Distinct strings, each one of `options`, as a set: bit k for options[k] (an empty array
  /// is the empty set).
  std::uint32_t subset(const std::string& key, const std::vector<std::string>& options) const {
    const toml::value& v = value(key);
    const std::string expected = "an array of distinct names out of " + quoted_list(options);
    if (!v.is_array()) fail_found(key, expected);
    std::uint32_t set = 0;
    const auto& elements = v.as_array();
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const auto at = elements[i].is_string()
                          ? std::find(options.begin(), options.end(), elements[i].as_string().str)
                          : options.end();
      const bool known = at != options.end();
      const std::uint32_t bit = known ? std::uint32_t(1) << (at - options.begin()) : 0;
      if (!known || (set & bit) != 0)
        fail(key, "expected " + expected + ", got " + describe(elements[i]) + " at index " +
                      std::to_string(i) + (known ? " a second time" : ""));
      set |= bit;
    }
    return set;
  }

  /// Numbers in `range`; `size` > 0 demands exactly that many, 0 any non-zero count.
  std::vector<double> numbers(const std::string& key, const Range& range,
                              std::size_t size = 0) const {
    const toml::value& v = value(key);
    const std::string count = size ? std::to_string(size) + " " : "";
    const std::string expected = range.text("an array of " + count + "numbers");
    if (!v.is_array()) fail_found(key, expected);
    const auto& elements = v.as_array();
    if (size ? elements.size() != size : elements.empty()) fail_found(key, expected);
    std::vector<double> result;
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const std::optional<double> x = finite_number(elements[i]);
      if (!x || !range.contains(*x)) {
        fail(key, "expected " + expected + ", got " + describe(elements[i]) + " at index " +
                      std::to_string(i));
      }
      result.push_back(*x);
    }
    return result;
  }

  Vec3 vec3(const std::string& key, const std::string& unit) const {
    const std::vector<double> xyz = numbers(key, any_value(unit), 3);
    return Vec3{xyz[0], xyz[1], xyz[2]};
  }
  Vec3 vec3(const std::string& key, const std::string& unit, Vec3 fallback) const {
    return has(key) ? vec3(key, unit) : fallback;
  }

  /// An array of `size` 3-vectors, e.g. [[0.7, 0, 0], [0.7, 0, 0]].
  std::vector<Vec3> vec3s(const std::string& key, const std::string& unit, std::size_t size) const {
    const toml::value& v = value(key);
    const std::string expected = "an array of " + std::to_string(size) + " vectors [x, y, z]" +
                                 (unit.empty() ? "" : " in " + unit);
    if (!v.is_array() || v.as_array().size() != size) fail_found(key, expected);
    std::vector<Vec3> result;
    for (std::size_t i = 0; i < size; ++i) {
      const toml::value& e = v.as_array()[i];
      std::optional<double> x[3];
      const bool triple = e.is_array() && e.as_array().size() == 3;
      for (int k = 0; k < 3 && triple; ++k) x[k] = finite_number(e.as_array()[k]);
      if (!triple || !x[0] || !x[1] || !x[2])
        fail(key,
             "expected " + expected + ", got " + describe(e) + " at index " + std::to_string(i));
      result.push_back(Vec3{*x[0], *x[1], *x[2]});
    }
    return result;
  }

  std::array<bool, 3> bool3(const std::string& key, std::array<bool, 3> fallback) const {
    if (!has(key)) return fallback;
    const toml::value& v = value(key);
    const bool ok = v.is_array() && v.as_array().size() == 3 &&
                    std::all_of(v.as_array().begin(), v.as_array().end(),
                                [](const toml::value& e) { return e.is_boolean(); });
    if (!ok) fail_found(key, "an array of 3 booleans");
    const auto& e = v.as_array();
    return {e[0].as_boolean(), e[1].as_boolean(), e[2].as_boolean()};
  }

  /// A required sub-table; `[key]` in messages.
  TableReader table(const std::string& key) const {
    if (!has(key)) fail(key, "missing required table [" + path(key) + "]");
    const toml::value& v = value(key);
    if (!v.is_table()) fail_found(key, "a table " + table_title(key));
    return TableReader(v, file_, path(key), table_title(key));
  }
  /// A sub-table, or an empty one when absent (so its keys take their defaults).
  TableReader optional_table(const std::string& key) const {
    static const toml::value empty(toml::table{});
    return has(key) ? table(key) : TableReader(empty, file_, path(key), table_title(key));
  }
  /// The entries of an array of tables `[[key]]`, each keyed `key[i]`; empty when absent.
  std::vector<TableReader> array_of_tables(const std::string& key) const {
    std::vector<TableReader> entries;
    if (!has(key)) return entries;
    const toml::value& v = value(key);
    const std::string expected = "an array of tables [[" + path(key) + "]]";
    if (!v.is_array()) fail_found(key, expected);
    const auto& elements = v.as_array();
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const std::string element_key = path(key) + "[" + std::to_string(i) + "]";
      if (!elements[i].is_table()) {
        throw InputError(file_, line_in(elements[i], file_), element_key,
                         "expected a table in " + expected + ", got " + describe(elements[i]));
      }
      entries.emplace_back(elements[i], file_, element_key, "[[" + path(key) + "]]");
    }
    return entries;
  }

 private:
  /// `options` quoted and separated by commas: "a", "b", "c".
  static std::string quoted_list(const std::vector<std::string>& options) {
    std::string list;
    for (const std::string& option : options)
      list += (list.empty() ? "\"" : ", \"") + option + "\"";
    return list;
  }

  /// "[simulation]" for a table header, "insert[0].region" inside an array of tables.
  std::string table_title(const std::string& key) const {
    const std::string p = path(key);
    return p.find('[') == std::string::npos ? "[" + p + "]" : p;
  }

  const toml::value* table_;
  std::string file_;
  std::string key_;
  std::string title_;
};

}  // namespace gpudem
