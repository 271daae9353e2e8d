#include "comm/TimeSeriesWriter.hpp"

#include <iomanip>
#include <stdexcept>

namespace gpudem {

TimeSeriesWriter::TimeSeriesWriter(const std::string& path, std::vector<std::string> columns,
                                   bool write_rank)
    : columns_(columns.size()) {
  if (!write_rank) return;
  out_.open(path, std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot open time series file '" + path + "'");
  for (std::size_t c = 0; c < columns.size(); ++c) out_ << (c ? "," : "") << columns[c];
  out_ << '\n' << std::setprecision(10);
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
