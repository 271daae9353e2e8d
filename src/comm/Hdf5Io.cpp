#include "comm/Hdf5Io.hpp"

#include <algorithm>
#include <stdexcept>

namespace gpudem {
namespace {

H5Handle file_access(const H5Calls& h5, MPI_Comm comm) {
  H5Handle access = h5.handle(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(access)");
  h5.check(H5Pset_fapl_mpio(access.id(), comm, MPI_INFO_NULL), "H5Pset_fapl_mpio");
  h5.check(H5Pset_all_coll_metadata_ops(access.id(), true), "H5Pset_all_coll_metadata_ops");
  h5.check(H5Pset_coll_metadata_write(access.id(), true), "H5Pset_coll_metadata_write");
  return access;
}

/// Link creation that makes the missing groups of a path, so "mesh/tool/force" can be created
/// in a file without group "mesh".
H5Handle link_creation(const H5Calls& h5) {
  H5Handle links = h5.handle(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "H5Pcreate(links)");
  h5.check(H5Pset_create_intermediate_group(links.id(), 1), "H5Pset_create_intermediate_group");
  return links;
}

H5Handle dataset_creation(const H5Calls& h5) {
  H5Handle creation = h5.handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(create)");
  h5.check(H5Pset_fill_time(creation.id(), H5D_FILL_TIME_NEVER), "H5Pset_fill_time");
  return creation;
}

H5Handle collective_transfer(const H5Calls& h5) {
  H5Handle transfer = h5.handle(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate(transfer)");
  h5.check(H5Pset_dxpl_mpio(transfer.id(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
  return transfer;
}

/// Selects this rank's rows in the file and the matching values in memory; nothing at all on
/// a rank without rows, which still takes part in the collective write.
void select_slice(const H5Calls& h5, hid_t file_space, hid_t memory_space, const FieldSource& field,
                  const Slice& slice, const std::string& what) {
  if (slice.count == 0) {
    h5.check(H5Sselect_none(file_space), "H5Sselect_none" + what);
    h5.check(H5Sselect_none(memory_space), "H5Sselect_none" + what);
    return;
  }
  const hsize_t count[2] = {slice.count, field.components};
  const hsize_t file_start[2] = {slice.offset, 0};
  const hsize_t memory_start[2] = {0, field.first};
  h5.check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, file_start, nullptr, count, nullptr),
           "H5Sselect_hyperslab" + what);
  h5.check(H5Sselect_hyperslab(memory_space, H5S_SELECT_SET, memory_start, nullptr, count, nullptr),
           "H5Sselect_hyperslab" + what);
}

}  // namespace

void H5Calls::fail(const std::string& call) const {
  throw std::runtime_error(kind_ + " '" + file_ + "': HDF5 call " + call + " failed");
}

Slice global_slice(MPI_Comm comm, std::uint64_t count) {
  std::uint64_t offset = 0, total = 0;
  MPI_Exscan(&count, &offset, 1, MPI_UINT64_T, MPI_SUM, comm);
  MPI_Allreduce(&count, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) offset = 0;  // MPI_Exscan leaves rank 0's result undefined
  return {offset, count, total};
}

ParallelFile::ParallelFile(MPI_Comm comm, const H5Calls& h5, const std::string& path)
    : h5_(h5),
      access_(file_access(h5, comm)),
      links_(link_creation(h5)),
      creation_(dataset_creation(h5)),
      transfer_(collective_transfer(h5)),
      file_(h5.handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access_.id()), H5Fclose,
                      "H5Fcreate")) {}

void ParallelFile::write_dataset(const FieldSource& field, const Slice& slice) const {
  const std::string what = std::string("(") + field.name + ")";
  const hsize_t file_dims[2] = {slice.total, field.components};
  H5Handle file_space =
      h5_.handle(H5Screate_simple(field.components > 1 ? 2 : 1, file_dims, nullptr), H5Sclose,
                 "H5Screate_simple" + what);
  H5Handle dataset = h5_.handle(H5Dcreate2(file_.id(), field.name, field.file_type, file_space.id(),
                                           links_.id(), creation_.id(), H5P_DEFAULT),
                                H5Dclose, "H5Dcreate2" + what);
  // An empty dataset has no storage address, and HDF5 1.10 fails a collective write to it
  // even with nothing selected; every rank knows the total, so all skip together.
  if (slice.total == 0) return;
  const hsize_t memory_dims[2] = {std::max<hsize_t>(slice.count, 1), field.stride};
  H5Handle memory_space =
      h5_.handle(H5Screate_simple(2, memory_dims, nullptr), H5Sclose, "H5Screate_simple" + what);
  select_slice(h5_, file_space.id(), memory_space.id(), field, slice, what);
  static const std::uint64_t no_values = 0;
  const void* data = slice.count > 0 ? field.data : &no_values;
  h5_.check(H5Dwrite(dataset.id(), field.memory_type, memory_space.id(), file_space.id(),
                     transfer_.id(), data),
            "H5Dwrite" + what);
}

void ParallelFile::close() { h5_.check(file_.close(), "H5Fclose"); }

}  // namespace gpudem
