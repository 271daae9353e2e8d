#pragma once
// Runs a physics test once per backend, a typed parameter (EngineChoice): the host always, CUDA
// when compiled in and a device is visible (otherwise the test is skipped, not passed silently).
// Suites instantiated with GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS also run each backend in
// the mixed and float precision policies, to the same tolerances. Instances are named host,
// cuda, host_mixed, cuda_mixed, host_float, cuda_float.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/CudaMemory.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem::test {

enum class Backend { Host, Cuda };

/// What one instance of a physics test runs on: a backend, and the precision policy it imposes
/// (none: the setup's own).
struct EngineChoice {
  Backend backend = Backend::Host;
  std::optional<Precision> precision;
};

/// The instance's name: "host", "cuda", "host_mixed", "cuda_float", ...
inline std::string choice_name(const EngineChoice& c) {
  std::string name = c.backend == Backend::Cuda ? "cuda" : "host";
  if (c.precision == Precision::Mixed) name += "_mixed";
  if (c.precision == Precision::Float) name += "_float";
  if (c.precision == Precision::Double) name += "_double";
  return name;
}

inline std::unique_ptr<StepEngine> engine_for(const EngineChoice& c, EngineSetup s) {
  if (c.precision) s.precision = *c.precision;
  return c.backend == Backend::Cuda ? make_cuda_engine(s) : make_host_engine(s);
}

inline bool backend_available(const EngineChoice& c) {
  return c.backend == Backend::Host || (cuda::compiled_in() && cuda::device_count() > 0);
}

class BackendTest : public ::testing::TestWithParam<EngineChoice> {
 protected:
  void SetUp() override {
    if (!backend_available(GetParam())) GTEST_SKIP() << "no CUDA device on this machine";
  }
  std::unique_ptr<StepEngine> make_engine(const EngineSetup& s) const {
    return engine_for(GetParam(), s);
  }
};

/// gtest's instance name of an EngineChoice parameter.
struct ChoiceName {
  std::string operator()(const ::testing::TestParamInfo<EngineChoice>& info) const {
    return choice_name(info.param);
  }
};

#define GPUDEM_INSTANTIATE_BACKENDS(Suite)                                                \
  INSTANTIATE_TEST_SUITE_P(                                                               \
      Backends, Suite,                                                                    \
      ::testing::Values(::gpudem::test::EngineChoice{::gpudem::test::Backend::Host, {}},  \
                        ::gpudem::test::EngineChoice{::gpudem::test::Backend::Cuda, {}}), \
      ::gpudem::test::ChoiceName{})

#define GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Suite)                              \
  INSTANTIATE_TEST_SUITE_P(Backends, Suite,                                            \
                           ::testing::ValuesIn(::gpudem::test::every_engine_choice()), \
                           ::gpudem::test::ChoiceName{})

/// Both backends in the setup's precision, then in the mixed and float policies.
inline std::vector<EngineChoice> every_engine_choice() {
  std::vector<EngineChoice> choices;
  for (const std::optional<Precision> p :
       {std::optional<Precision>{}, std::optional<Precision>{Precision::Mixed},
        std::optional<Precision>{Precision::Float}})
    for (const Backend b : {Backend::Host, Backend::Cuda}) choices.push_back({b, p});
  return choices;
}

}  // namespace gpudem::test
