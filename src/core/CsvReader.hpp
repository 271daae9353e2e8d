#pragma once
/// Streaming reader of simple comma-separated files: a header line naming the columns, then
/// one row per line. Fields are trimmed of spaces and tabs; quoting is not supported; blank
/// lines after the header are skipped. Every problem is an InputError naming file and line.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/InputError.hpp"

namespace gpudem {

class CsvReader {
 public:
  /// Opens `path` and reads its header line.
  explicit CsvReader(std::string path) : path_(std::move(path)), in_(path_) {
    if (!in_) throw InputError(path_, 0, "", "cannot open CSV file");
    std::string text;
    if (!read_line(text) || is_blank(text))
      throw InputError(path_, 1, "", "missing header: the first line must name the columns");
    header_ = split(text);
  }

  const std::string& path() const { return path_; }
  const std::vector<std::string>& header() const { return header_; }
  /// 1-based number of the line read last.
  int line() const { return line_; }

  /// Reads the next non-blank row into `fields`; false at the end of the file. Throws when
  /// the row does not have one field per header column.
  bool next(std::vector<std::string>& fields) {
    std::string text;
    do {
      if (!read_line(text)) return false;
    } while (is_blank(text));
    fields = split(text);
    if (fields.size() != header_.size())
      throw InputError(path_, line_, "",
                       "row has " + std::to_string(fields.size()) +
                           " fields but the header names " + std::to_string(header_.size()) +
                           " columns");
    return true;
  }

  /// Passes over the next non-blank row unread; false at the end of the file.
  bool skip() {
    std::string text;
    do {
      if (!read_line(text)) return false;
    } while (is_blank(text));
    return true;
  }

  /// The whole of `field` (in column `column` of the line read last) as a finite number.
  double number(const std::string& field, const std::string& column) const {
    const char* begin = field.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    if (field.empty() || end != begin + field.size())
      throw InputError(path_, line_, column, "'" + field + "' is not a number");
    if (errno == ERANGE || !std::isfinite(value))
      throw InputError(path_, line_, column, "'" + field + "' is not a finite number in range");
    return value;
  }

 private:
  bool read_line(std::string& text) {
    if (!std::getline(in_, text)) return false;
    ++line_;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return true;
  }

  static bool is_blank(const std::string& text) {
    return text.find_first_not_of(" \t") == std::string::npos;
  }

  static std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
  }

  static std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
      const auto comma = text.find(',', start);
      fields.push_back(trim(text.substr(start, comma - start)));
      if (comma == std::string::npos) return fields;
      start = comma + 1;
    }
  }

  std::string path_;
  std::ifstream in_;
  std::vector<std::string> header_;
  int line_ = 0;
};

}  // namespace gpudem
