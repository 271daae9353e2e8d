# Particle snapshots (HDF5 + XDMF): the C++ read-back test (of the writer and of the queue that
# writes on a thread of its own), which also leaves an output folder
# behind, then tests/scripts/check_snapshot.py on that folder (and its own check that it
# catches broken documents). Python is Debian's, which has h5py and numpy.
set(GPUDEM_SNAPSHOT_FIXTURE_DIR ${CMAKE_CURRENT_BINARY_DIR}/snapshot_fixture)
set(GPUDEM_CHECK_SNAPSHOT ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_snapshot.py)

gpudem_add_test(test_snapshot_writer
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/SnapshotWriterTest.cpp
          ${CMAKE_CURRENT_LIST_DIR}/SnapshotQueueTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 60)
target_compile_definitions(test_snapshot_writer PRIVATE
  GPUDEM_SNAPSHOT_FIXTURE_DIR="${GPUDEM_SNAPSHOT_FIXTURE_DIR}")
set_tests_properties(test_snapshot_writer PROPERTIES FIXTURES_SETUP snapshot_fixture)

add_test(NAME check_snapshot_xdmf
  COMMAND /usr/bin/python3 ${GPUDEM_CHECK_SNAPSHOT} ${GPUDEM_SNAPSHOT_FIXTURE_DIR})
add_test(NAME check_snapshot_xdmf_catches_errors
  COMMAND /usr/bin/python3 ${GPUDEM_CHECK_SNAPSHOT} --self-test ${GPUDEM_SNAPSHOT_FIXTURE_DIR})
set_tests_properties(check_snapshot_xdmf check_snapshot_xdmf_catches_errors PROPERTIES
  DEPENDS test_snapshot_writer
  FIXTURES_REQUIRED snapshot_fixture
  LABELS unit
  TIMEOUT 60)

# The same read-back checks, and the snapshot queue's, at 2 and 4 ranks (rank 1 holds no
# particle).
gpudem_add_test_on_ranks(test_snapshot_writer RANKS 2 4
  FILTER "SnapshotWriterTest.*:SnapshotQueueTest.*")
