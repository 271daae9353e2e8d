#pragma once
/// What the fuzz targets share. Each target defines LLVMFuzzerTestOneInput, which libFuzzer
/// calls with generated inputs (scripts/fuzz.sh) and ReplayMain.cpp calls with the files of the
/// target's corpus (the ctests fuzz_corpus_*). A reader passes when it accepts an input or
/// rejects it with InputError; any other exception, a crash, a sanitizer report or a hang fails.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/InputError.hpp"

namespace gpudem::fuzz {

/// Writes `size` bytes to the file `name` of this process's scratch folder (made on first use
/// in $TMPDIR or /tmp, removed at exit) and returns its path.
std::string write_scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size);

/// write_scratch_file of the characters of `text`.
std::string write_scratch_file(const std::string& name, const std::string& text);

/// The scene around the CSV and bed inputs: a unit box periodic along x and two materials,
/// "soil" (0) and "steel" (1); each target appends its contact law and source.
std::string two_material_scene();

/// Runs `read` on bad input: an InputError is the answer expected of it, so it is swallowed;
/// every other exception escapes and ends the program (a finding).
template <class Read>
void reject_only_with_input_error(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace gpudem::fuzz
