#pragma once
/// `--preview`: the scene at t = 0, without a step, as an XDMF pair and a PNG in the output
/// directory. preview.h5 holds the particles (or the bed) as every rank has them, each mesh at
/// its start and end pose, each plane wall as the polygon it cuts from the domain box and each
/// mesh's centre path over the run; preview.xmf shows them in ParaView as one spatial
/// collection; preview.png is rendered from the same data (PreviewImage.hpp), from at most
/// kPreviewImageParticles particles (every k-th of each rank beyond that).
#include "comm/MpiContext.hpp"
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

constexpr std::uint64_t kPreviewImageParticles = 1000000;

/// Writes preview.h5, preview.xmf and preview.png into scene.output.dir. Collective.
void write_preview(const Scene& scene, const EngineSetup& setup, const ParticleStore& share,
                   const MpiContext& mpi);

}  // namespace gpudem
