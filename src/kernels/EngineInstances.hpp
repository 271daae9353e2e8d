#pragma once
/// The step-engine factories of each backend and normal law, one translation unit each
/// (EngineFactory.hpp); make_host_engine / make_cuda_engine pick one by the scene's law.
#include <memory>

#include "kernels/StepEngine.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_host_hooke_engine(const EngineSetup& setup);
std::unique_ptr<StepEngine> make_host_hertz_engine(const EngineSetup& setup);
std::unique_ptr<StepEngine> make_cuda_hooke_engine(const EngineSetup& setup);
std::unique_ptr<StepEngine> make_cuda_hertz_engine(const EngineSetup& setup);

/// Throws std::invalid_argument naming the law when it is not one of valid_contact_models().
void require_valid_contact_model(const EngineSetup& setup);

}  // namespace gpudem
