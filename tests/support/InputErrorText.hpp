#pragma once
// The message of the InputError an action throws, for tests that compare the failure each rank
// reports with the one a single rank gives.
#include <string>

#include "core/InputError.hpp"

namespace gpudem::test {

/// The message of the InputError `action()` throws; empty when it throws none.
template <class Action>
std::string input_error_text(Action&& action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace gpudem::test
