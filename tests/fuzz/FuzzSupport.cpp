#include "FuzzSupport.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace gpudem::fuzz {
namespace {

namespace fs = std::filesystem;

/// A folder made in $TMPDIR (or /tmp) that is removed with everything in it when the object
/// is destroyed.
class ScratchFolder {
 public:
  ScratchFolder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/gpudem-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make " + pattern);
    path_ = pattern;
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The scratch folder, made on first use and removed when the program exits.
const fs::path& scratch_folder() {
  static const ScratchFolder folder;
  return folder.path();
}

}  // namespace

std::string write_scratch_file(const std::string& name, const std::uint8_t* data,
                               std::size_t size) {
  const fs::path path = scratch_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
  return path.string();
}

std::string two_material_scene() {
  return R"([simulation]
end_time = 1.0
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
periodic = [true, false, false]
[[material]]
name = "soil"
density = 1850
young = 2e6
[[material]]
name = "steel"
density = 7800
young = 2e11
)";
}

std::string write_scratch_file(const std::string& name, const std::string& text) {
  return write_scratch_file(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

}  // namespace gpudem::fuzz
