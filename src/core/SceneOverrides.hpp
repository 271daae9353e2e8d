#pragma once
/// `--set dotted.key=value` overrides, applied to the parsed scene tree before validation.
/// `value` is TOML (`output.dir="run2"`, `domain.periodic=[true,false,false]`); arrays are
/// indexed by number (`material.0.density=2000`). Errors are InputErrors with file "--set",
/// line 0 and the dotted key as given.
#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include <toml.hpp>

#include "core/InputError.hpp"
#include "core/Utf8.hpp"

namespace gpudem {

namespace override_detail {

inline std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

inline bool is_index(const std::string& part) {
  return !part.empty() && part.size() < 10 &&
         std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c); });
}

/// Parses `text` as one TOML value; the result remembers "--set" as its origin.
inline toml::value parse_value(const std::string& key, const std::string& text) {
  if (first_invalid_utf8(text)) throw InputError("--set", 0, key, "the value is not UTF-8 text");
  std::istringstream in("value = " + text + "\n");
  toml::value parsed;
  try {
    parsed = toml::parse(in, "--set");
  } catch (const std::exception&) {
    throw InputError("--set", 0, key,
                     "cannot read '" + text +
                         "' as a TOML value (strings need quotes: "
                         "key=\"text\")");
  }
  if (parsed.as_table().size() != 1) {
    throw InputError("--set", 0, key, "expected a single TOML value, got '" + text + "'");
  }
  return parsed.as_table().at("value");
}

/// The dot-separated parts of `key`; none may be empty.
inline std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(key);
  while (std::getline(in, part, '.')) parts.push_back(part);
  if (key.empty() || key.back() == '.' ||
      std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    throw InputError("--set", 0, key, "expected a dotted key such as simulation.end_time");
  }
  return parts;
}

/// The element of array `node` at index `part` (which must exist).
inline toml::value& element(toml::value& node, const std::string& part, const std::string& key,
                            const std::string& array_key) {
  const auto size = node.as_array().size();
  if (!is_index(part) || std::stoul(part) >= size) {
    throw InputError("--set", 0, key,
                     "index '" + part + "' out of range: '" + array_key + "' has " +
                         std::to_string(size) + (size == 1 ? " entry" : " entries") +
                         ", numbered from 0");
  }
  return node.as_array()[std::stoul(part)];
}

/// Stores `value` at the path `parts` under `root`, creating missing plain tables.
inline void assign(toml::value& root, const std::vector<std::string>& parts,
                   const toml::value& value, const std::string& key) {
  toml::value* node = &root;
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    if (node->is_array()) {
      toml::value& next = element(*node, part, key, walked);
      if (last) next = value;
      node = &next;
    } else if (node->is_table()) {
      auto& table = node->as_table();
      if (last) {
        table[part] = value;
      } else if (table.count(part) == 0) {
        if (is_index(parts[i + 1])) {
          throw InputError(
              "--set", 0, key,
              "there is no array '" + walked + (walked.empty() ? "" : ".") + part + "' to index");
        }
        table.emplace(part, toml::table{});
      }
      node = &table[part];
    } else {
      throw InputError("--set", 0, key, "'" + walked + "' is a value, not a table");
    }
    walked += (walked.empty() ? "" : ".") + part;
  }
}

}  // namespace override_detail

/// Applies one `dotted.key=value` assignment to the scene tree `root`.
inline void apply_override(toml::value& root, const std::string& assignment) {
  using namespace override_detail;
  const auto equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw InputError("--set", 0, trim(assignment),
                     "expected dotted.key=value, got '" + assignment + "'");
  }
  const std::string key = trim(assignment.substr(0, equals));
  const std::vector<std::string> parts = split_key(key);
  assign(root, parts, parse_value(key, trim(assignment.substr(equals + 1))), key);
}

/// Applies `overrides` in order; a later one wins over an earlier one.
inline void apply_overrides(toml::value& root, const std::vector<std::string>& overrides) {
  for (const std::string& assignment : overrides) apply_override(root, assignment);
}

}  // namespace gpudem
