#pragma once
/// CSV time series written by rank 0: a header line of column names, then one row per call.
#include <fstream>
#include <string>
#include <vector>

namespace gpudem {

class TimeSeriesWriter {
 public:
  /// Opens (truncates) `path` and writes the header; `write_rank` tells whether this rank writes.
  TimeSeriesWriter(const std::string& path, std::vector<std::string> columns, bool write_rank);
  /// Appends one row; values.size() must equal the number of columns. Flushed at once.
  void append(const std::vector<double>& values);

 private:
  std::size_t columns_;
  std::ofstream out_;
};

}  // namespace gpudem
