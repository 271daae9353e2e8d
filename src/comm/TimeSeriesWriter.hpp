#pragma once
/// CSV time series written by rank 0: a header line of column names, then one row per call.
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace gpudem {

/// Where a restarted run picks up an existing series: rows whose value in `column` is above
/// `last` were written after the checkpoint and are dropped.
struct SeriesResume {
  std::string column;
  double last = 0;
};

class TimeSeriesWriter {
 public:
  /// Opens (truncates) `path` and writes the header; `write_rank` tells whether this rank writes.
  /// With `resume`, an existing file with the same header keeps its rows up to resume->last
  /// (rewritten through a temporary file and a rename) and new rows follow them.
  TimeSeriesWriter(const std::string& path, std::vector<std::string> columns, bool write_rank,
                   const std::optional<SeriesResume>& resume = std::nullopt);
  /// Appends one row; values.size() must equal the number of columns. Flushed at once.
  void append(const std::vector<double>& values);

 private:
  std::size_t columns_;
  std::ofstream out_;
};

}  // namespace gpudem
