/// Fuzz target: the CSV particle reader (import_csv_part, whole file and a rank's part) on
/// arbitrary text, as a CSV source of a scene with two materials and a periodic axis.
#include "FuzzSupport.hpp"
#include "core/ParticleSources.hpp"
#include "core/SceneLoader.hpp"

namespace {

const char* const kCsvScene = R"([simulation]
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
[contact]
stiffness = 1e4
[[insert]]
csv = "particles.csv"
material = "soil"
)";

/// The scene whose CSV source reads the scratch file particles.csv.
const gpudem::Scene& csv_scene() {
  static const gpudem::Scene scene =
      gpudem::load_scene(gpudem::fuzz::write_scratch_file("csv_scene.toml", kCsvScene));
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
