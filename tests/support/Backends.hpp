#pragma once
// Runs a physics test once per backend: "host" always, "cuda" when compiled in and a device is
// visible (otherwise the test is skipped, not passed silently).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "kernels/CudaMemory.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem::test {

inline std::unique_ptr<StepEngine> engine_for(const std::string& backend, const EngineSetup& s) {
  return backend == "cuda" ? make_cuda_engine(s) : make_host_engine(s);
}

inline bool backend_available(const std::string& backend) {
  return backend == "host" || (cuda::compiled_in() && cuda::device_count() > 0);
}

class BackendTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!backend_available(GetParam())) GTEST_SKIP() << "no CUDA device on this machine";
  }
  std::unique_ptr<StepEngine> make_engine(const EngineSetup& s) const {
    return engine_for(GetParam(), s);
  }
};

#define GPUDEM_INSTANTIATE_BACKENDS(Suite) \
  INSTANTIATE_TEST_SUITE_P(Backends, Suite, ::testing::Values("host", "cuda"))

}  // namespace gpudem::test
