/// Fuzz target: the scene reader (load_scene) on arbitrary TOML text.
#include "FuzzSupport.hpp"
#include "core/SceneLoader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = gpudem::fuzz::write_scratch_file("scene.toml", data, size);
  gpudem::fuzz::reject_only_with_input_error([&] { gpudem::load_scene(path); });
  return 0;
}
