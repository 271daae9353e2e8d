# The list of contact-law slot combinations, shared by the scene loader and the engine factory,
# and the combinations this build compiles (GPUDEM_CONTACT_LAWS, CompiledContactLaws.hpp.in).

set(GPUDEM_CONTACT_LAWS "all" CACHE STRING
    "Contact laws to compile: 'all', or a list of normal/damping/tangential/rolling/cohesion patterns (each part a choice or *), e.g. 'hertz/restitution/mindlin/*/none'")

# One initializer {normal, damping, tangential, rolling, cohesion} per pattern, each the choice's
# index in its slot's list or -1 for *. The lists repeat the slots' keywords in enum order
# (core/contact/ContactSlots.hpp): configure time cannot read them from C++, so the generated
# header carries them (GPUDEM_CONTACT_LAW_CHOICES) and test_contact_law compares them with the
# slots' own.
set(slot_names normal damping tangential rolling cohesion)
set(normal_choices hooke hertz)
set(damping_choices none restitution viscoelastic)
set(tangential_choices none linear_history mindlin)
set(rolling_choices none constant_torque epsd)
set(cohesion_choices none sjkr jkr)
set(GPUDEM_CONTACT_LAW_CHOICES "")
foreach(slot IN LISTS slot_names)
  string(REPLACE ";" " " choices "${${slot}_choices}")
  string(APPEND GPUDEM_CONTACT_LAW_CHOICES "${choices}|")
endforeach()
set(GPUDEM_CONTACT_LAW_PATTERNS "")
set(patterns "${GPUDEM_CONTACT_LAWS}")
if("${patterns}" STREQUAL "")
  message(FATAL_ERROR "GPUDEM_CONTACT_LAWS is empty: give 'all' or at least one law pattern")
elseif("${patterns}" STREQUAL "all")
  set(patterns "*/*/*/*/*")
endif()
foreach(pattern IN LISTS patterns)
  string(REPLACE "/" ";" parts "${pattern}")
  list(LENGTH parts part_count)
  if(NOT part_count EQUAL 5)
    message(FATAL_ERROR "GPUDEM_CONTACT_LAWS: '${pattern}' is not normal/damping/tangential/rolling/cohesion")
  endif()
  set(indices "")
  foreach(slot IN ZIP_LISTS slot_names parts)
    if(slot_1 STREQUAL "*")
      list(APPEND indices -1)
    else()
      list(FIND ${slot_0}_choices "${slot_1}" index)
      if(index EQUAL -1)
        string(REPLACE ";" ", " known "${${slot_0}_choices}")
        message(FATAL_ERROR "GPUDEM_CONTACT_LAWS: '${slot_1}' in '${pattern}' is not a ${slot_0} law (${known} or *)")
      endif()
      list(APPEND indices ${index})
    endif()
  endforeach()
  string(REPLACE ";" ", " indices "${indices}")
  string(APPEND GPUDEM_CONTACT_LAW_PATTERNS "{{${indices}}}, ")
endforeach()
configure_file(core/CompiledContactLaws.hpp.in
               ${CMAKE_CURRENT_BINARY_DIR}/generated/core/CompiledContactLaws.hpp @ONLY)

add_library(gpudem_contact_model ${GPUDEM_LIBRARY_TYPE} core/ContactModel.cpp)
target_link_libraries(gpudem_contact_model PUBLIC gpudem_base)
# Every target may include core/ContactModel.hpp (through core/Scene.hpp), hence the header.
target_include_directories(gpudem_base INTERFACE ${CMAKE_CURRENT_BINARY_DIR}/generated)
