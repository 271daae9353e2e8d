#pragma once
// Runs a physics test once per backend: "host" always, "cuda" when compiled in and a device is
// visible (otherwise the test is skipped, not passed silently). Suites instantiated with
// GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS also run each backend in the mixed and float
// precision policies ("host-mixed", "cuda-mixed", "host-float", "cuda-float"), to the same
// tolerances.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "kernels/CudaMemory.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem::test {

inline bool is_cuda(const std::string& backend) { return backend.rfind("cuda", 0) == 0; }

inline bool ends_with(const std::string& text, const std::string& end) {
  return text.size() > end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

inline std::unique_ptr<StepEngine> engine_for(const std::string& backend, EngineSetup s) {
  if (ends_with(backend, "-mixed")) s.precision = Precision::Mixed;
  if (ends_with(backend, "-float")) s.precision = Precision::Float;
  return is_cuda(backend) ? make_cuda_engine(s) : make_host_engine(s);
}

inline bool backend_available(const std::string& backend) {
  return !is_cuda(backend) || (cuda::compiled_in() && cuda::device_count() > 0);
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

#define GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Suite) \
  INSTANTIATE_TEST_SUITE_P(                               \
      Backends, Suite,                                    \
      ::testing::Values("host", "cuda", "host-mixed", "cuda-mixed", "host-float", "cuda-float"))

}  // namespace gpudem::test
