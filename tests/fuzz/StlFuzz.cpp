/// Fuzz target: the STL reader and mesh builder (load_mesh) on arbitrary bytes, ASCII or binary.
#include "FuzzSupport.hpp"
#include "core/StlReader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = gpudem::fuzz::write_scratch_file("mesh.stl", data, size);
  gpudem::fuzz::reject_only_with_input_error([&] { gpudem::load_mesh(path, {}); });
  return 0;
}
