# Fuzz targets of the input readers: scene (TOML), STL, CSV and checkpoint/bed files. Each
# target's LLVMFuzzerTestOneInput is built twice:
# - in every build, with ReplayMain.cpp, as the ctest fuzz_corpus_<reader>, which runs it on each
#   file of tests/fuzz/corpus/<reader>/ (the corpus scripts/fuzz.sh grew, and the inputs that
#   once made a finding);
# - with -DGPUDEM_FUZZ=ON (clang, scripts/fuzz.sh) as libFuzzer executables (target fuzz_targets).
set(GPUDEM_FUZZ_READERS scene stl csv checkpoint)
set(GPUDEM_FUZZ_SOURCE_scene SceneFuzz.cpp)
set(GPUDEM_FUZZ_LIBS_scene gpudem_scene)
set(GPUDEM_FUZZ_SOURCE_stl StlFuzz.cpp)
set(GPUDEM_FUZZ_LIBS_stl gpudem_mesh)
set(GPUDEM_FUZZ_SOURCE_csv CsvFuzz.cpp)
set(GPUDEM_FUZZ_LIBS_csv gpudem_scene gpudem_particles)
set(GPUDEM_FUZZ_SOURCE_checkpoint CheckpointFuzz.cpp)
set(GPUDEM_FUZZ_LIBS_checkpoint gpudem_comm gpudem_scene gpudem_particles)

if(GPUDEM_FUZZ)
  add_custom_target(fuzz_targets)
endif()
foreach(reader ${GPUDEM_FUZZ_READERS})
  set(sources ${CMAKE_CURRENT_LIST_DIR}/${GPUDEM_FUZZ_SOURCE_${reader}}
              ${CMAKE_CURRENT_LIST_DIR}/FuzzSupport.cpp)
  if(GPUDEM_FUZZ)
    add_executable(fuzz_${reader} EXCLUDE_FROM_ALL ${sources})
    target_link_options(fuzz_${reader} PRIVATE -fsanitize=fuzzer)
    add_dependencies(fuzz_targets fuzz_${reader})
  else()
    add_executable(fuzz_${reader} EXCLUDE_FROM_ALL ${sources}
                   ${CMAKE_CURRENT_LIST_DIR}/ReplayMain.cpp)
    add_dependencies(gpudem_tests fuzz_${reader})
    add_test(NAME fuzz_corpus_${reader}
             COMMAND fuzz_${reader} ${CMAKE_CURRENT_LIST_DIR}/corpus/${reader})
    set_tests_properties(fuzz_corpus_${reader} PROPERTIES LABELS "unit;fuzz" TIMEOUT 300)
  endif()
  target_link_libraries(fuzz_${reader} PRIVATE ${GPUDEM_FUZZ_LIBS_${reader}})
  target_include_directories(fuzz_${reader} PRIVATE ${CMAKE_CURRENT_LIST_DIR})
endforeach()
