gpudem_add_test(test_particle_sources
  SOURCES unit/ParticleSourcesTest.cpp
  LIBS gpudem_particles
  LABELS unit)

gpudem_add_test(test_tiled_insertion
  SOURCES unit/TiledInsertionTest.cpp
  LIBS gpudem_particles
  LABELS unit)

gpudem_add_test(test_periodic_images
  SOURCES unit/PeriodicImagesTest.cpp
  LIBS gpudem_particles
  LABELS unit)
