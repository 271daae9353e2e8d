# scripts/peers/particles.py (the particle files and observables of scripts/peers/compare.sh)
# on a lattice whose observables are computed by hand.
add_test(NAME peer_particles
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_peer_particles.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/peer_particles)
set_tests_properties(peer_particles PROPERTIES LABELS unit TIMEOUT 60)
