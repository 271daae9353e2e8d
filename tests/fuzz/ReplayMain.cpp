/// Runs a fuzz target on every file of the folders and files named on the command line (its
/// corpus and the inputs that once failed), as libFuzzer would run it on each: the ctests
/// fuzz_corpus_* replay the corpora in every build, without libFuzzer.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

/// The bytes of the file `path`.
std::vector<std::uint8_t> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::size_t inputs = 0;
  for (int a = 1; a < argc; ++a) {
    std::vector<fs::path> files;
    if (fs::is_directory(argv[a])) {
      for (const auto& entry : fs::recursive_directory_iterator(argv[a]))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (fs::is_regular_file(argv[a])) {
      files.emplace_back(argv[a]);
    } else {
      std::fprintf(stderr, "replay: no such file or folder: %s\n", argv[a]);
      return 2;
    }
    for (const fs::path& file : files) {
      const std::vector<std::uint8_t> bytes = file_bytes(file);
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      ++inputs;
    }
  }
  std::printf("replay: %zu input(s) read without a finding\n", inputs);
  return inputs > 0 ? 0 : 1;
}
