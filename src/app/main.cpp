// gpudem-mpi: command line entry point (CLI11). Thin: parse, run, map errors to exit codes.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <map>

#include "app/Runner.hpp"
#include "comm/MpiContext.hpp"
#include "core/InputError.hpp"

namespace {

void print_error(const gpudem::MpiContext& mpi, const std::string& message) {
  if (mpi.is_root()) std::fprintf(stderr, "gpudem-mpi: error: %s\n", message.c_str());
}

/// The command line's options, bound to `options`.
void add_options(CLI::App& app, gpudem::RunOptions& options) {
  app.set_version_flag("--version", std::string("gpudem-mpi ") + GPUDEM_VERSION);
  app.add_option("scene", options.scene_file, "scene file (TOML)")->required();
  CLI::Option* check = app.add_flag("--check", options.check_only, "validate the scene and exit");
  CLI::Option* preview =
      app.add_flag("--preview", options.preview,
                   "validate the scene, write it at t = 0 (preview.xmf, preview.h5, preview.png "
                   "in the output directory) and exit without a step")
          ->excludes(check);
  app.add_option("--set", options.overrides,
                 "override a scene key, e.g. --set simulation.end_time=0.5 (repeatable)")
      ->type_name("KEY=VALUE");
  app.add_option("--output-dir", options.output_dir, "output directory (overrides output.dir)");
  CLI::Option* restart =
      app.add_option("--restart", options.restart_file,
                     "continue from a checkpoint: particles, contact history and time come from "
                     "FILE, everything else from the scene")
          ->type_name("FILE")
          ->excludes(preview);
  app.add_flag("--resume", options.resume,
               "continue from the output directory's checkpoint.h5 when there is one (and do "
               "nothing when it has reached end_time), otherwise start the scene anew: the "
               "same command line for every job of a batch chain")
      ->excludes(restart)
      ->excludes(preview);
  const std::map<std::string, gpudem::BackendChoice> backends{
      {"auto", gpudem::BackendChoice::Auto},
      {"host", gpudem::BackendChoice::Host},
      {"cuda", gpudem::BackendChoice::Cuda}};
  app.add_option("--backend", options.backend, "compute backend: host, cuda or auto")
      ->transform(CLI::CheckedTransformer(backends, CLI::ignore_case));
  const std::map<std::string, gpudem::GpuAwareChoice> gpu_aware{
      {"auto", gpudem::GpuAwareChoice::Auto},
      {"on", gpudem::GpuAwareChoice::On},
      {"off", gpudem::GpuAwareChoice::Off}};
  app.add_option("--gpu-aware-mpi", options.gpu_aware_mpi,
                 "hand device buffers to MPI: auto (ask the MPI library), on, or off (stage "
                 "through host memory)")
      ->transform(CLI::CheckedTransformer(gpu_aware, CLI::ignore_case));
  CLI::Option* quiet = app.add_flag("--quiet", options.quiet, "no banner and no progress lines");
  app.add_flag("--verbose", options.verbose,
               "also print the engine's memory by array (bytes per particle) at start-up")
      ->excludes(quiet);
  app.add_flag("--exact-time-split", options.exact_time_split,
               "wait for the GPU at the end of each part of a step, so that the time split "
               "printed at the end holds each part's own kernels (slows CUDA runs a little)");
}

}  // namespace

int main(int argc, char** argv) {
  gpudem::MpiContext mpi(argc, argv);
  gpudem::RunOptions options;

  CLI::App app{"gpudem-mpi: GPU discrete element solver for granular media (one MPI rank per GPU)"};
  add_options(app, options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return mpi.is_root() ? app.exit(e) : 0;
  } catch (const CLI::CallForVersion& e) {
    return mpi.is_root() ? app.exit(e) : 0;
  } catch (const CLI::ParseError& e) {
    print_error(mpi, std::string(e.what()) + " (see --help)");
    return gpudem::kExitBadInput;
  }

  try {
    return gpudem::run_scene(options, mpi);
  } catch (const gpudem::InputError& e) {
    print_error(mpi, e.what());
    return gpudem::kExitBadInput;
  } catch (const std::exception& e) {
    print_error(mpi, e.what());
    return gpudem::kExitFailure;
  }
}
