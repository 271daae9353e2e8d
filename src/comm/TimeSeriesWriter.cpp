#include "comm/TimeSeriesWriter.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace gpudem {
namespace {

std::string header_line(const std::vector<std::string>& columns) {
  std::string line;
  for (std::size_t c = 0; c < columns.size(); ++c) line += (c ? "," : "") + columns[c];
  return line;
}

/// Field `index` of a CSV row, as a number (NaN when missing).
double field_value(const std::string& row, std::size_t index) {
  std::istringstream fields(row);
  std::string field;
  for (std::size_t k = 0; k <= index; ++k)
    if (!std::getline(fields, field, ',')) return std::numeric_limits<double>::quiet_NaN();
  return std::strtod(field.c_str(), nullptr);
}

/// The existing file's rows up to `resume.last`, or nothing when the file is missing or has
/// another header. Whether anything was kept is returned.
bool keep_rows(const std::string& path, const std::vector<std::string>& columns,
               const SeriesResume& resume) {
  const auto column = std::find(columns.begin(), columns.end(), resume.column);
  if (column == columns.end()) throw std::logic_error("time series has no column " + resume.column);
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line) || line != header_line(columns)) return false;
  const std::string temporary = path + ".tmp";
  std::ofstream out(temporary, std::ios::trunc);
  out << line << '\n';
  const auto index = static_cast<std::size_t>(column - columns.begin());
  while (std::getline(in, line))
    if (field_value(line, index) <= resume.last) out << line << '\n';
  out.close();
  std::error_code ec;
  if (out) std::filesystem::rename(temporary, path, ec);
  if (!out || ec) throw std::runtime_error("cannot rewrite time series file '" + path + "'");
  return true;
}

}  // namespace

TimeSeriesWriter::TimeSeriesWriter(const std::string& path, std::vector<std::string> columns,
                                   bool write_rank, const std::optional<SeriesResume>& resume)
    : columns_(columns.size()) {
  if (!write_rank) return;
  const bool kept = resume && keep_rows(path, columns, *resume);
  out_.open(path, kept ? std::ios::app : std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot open time series file '" + path + "'");
  if (!kept) out_ << header_line(columns) << '\n';
  out_ << std::setprecision(10);
  out_.flush();
}

void TimeSeriesWriter::append(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw std::logic_error("time series row has the wrong number of columns");
  if (!out_.is_open()) return;
  for (std::size_t c = 0; c < values.size(); ++c) out_ << (c ? "," : "") << values[c];
  out_ << '\n';
  out_.flush();
}

}  // namespace gpudem
