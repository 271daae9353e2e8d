/// Fuzz target: the CSV particle reader (import_csv_part, whole file and a rank's part) on
/// arbitrary text, as a CSV source of a scene with two materials and a periodic axis.
#include "FuzzSupport.hpp"
#include "core/ParticleSources.hpp"
#include "core/SceneLoader.hpp"

namespace {

/// The contact law and the source, after two_material_scene().
const char* const kCsvSceneTail = R"([contact]
stiffness = 1e4
[[insert]]
csv = "particles.csv"
material = "soil"
)";

/// The scene whose CSV source reads the scratch file particles.csv.
const gpudem::Scene& csv_scene() {
  static const gpudem::Scene scene = gpudem::load_scene(gpudem::fuzz::write_scratch_file(
      "csv_scene.toml", gpudem::fuzz::two_material_scene() + kCsvSceneTail));
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gpudem::Scene& scene = csv_scene();
  gpudem::fuzz::write_scratch_file("particles.csv", data, size);
  for (const gpudem::FilePart part : {gpudem::FilePart{}, gpudem::FilePart{1, 3}}) {
    gpudem::fuzz::reject_only_with_input_error([&] {
      gpudem::ParticleStore particles;
      gpudem::import_csv_part(scene, 0, part, particles, 0);
    });
  }
  return 0;
}
