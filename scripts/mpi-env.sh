# Sourced by the scripts: lets Open MPI's mpirun run as root (containers, CI) and start more
# ranks than cores.
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1

# share_cores NP: unless OMP_NUM_THREADS is set, gives each of NP ranks an equal share of the
# cores as OpenMP threads (at least one), so that ranks and threads do not oversubscribe them.
share_cores() {
  local share=$(( $(nproc) / $1 ))
  export OMP_NUM_THREADS=${OMP_NUM_THREADS:-$(( share > 1 ? share : 1 ))}
}
