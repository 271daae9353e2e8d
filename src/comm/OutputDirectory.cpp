#include "comm/OutputDirectory.hpp"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/InputError.hpp"

namespace gpudem {

void prepare_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw InputError("", 0, "output.dir",
                     "cannot create output directory '" + dir + "'" +
                         (ec ? ": " + ec.message() : std::string(": a file is in the way")));
  const fs::path probe = fs::path(dir) / ".gpudem-write-test";
  {
    std::ofstream out(probe);
    if (!out)
      throw InputError("", 0, "output.dir", "output directory '" + dir + "' is not writable");
  }
  fs::remove(probe, ec);
}

}  // namespace gpudem
