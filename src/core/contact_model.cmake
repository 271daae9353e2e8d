# The list of contact-law slot combinations, shared by the scene loader and the engine factory.
add_library(gpudem_contact_model ${GPUDEM_LIBRARY_TYPE} core/ContactModel.cpp)
target_link_libraries(gpudem_contact_model PUBLIC gpudem_base)
