#!/usr/bin/env bash
# Sourced by the benchmark scripts: write_bench_scene BUILD WORK EXPONENT writes WORK/bed.csv,
# the benchmarks' settled periodic bed of 10^EXPONENT spheres (bench/SettledBed.hpp), and
# WORK/scene.toml, the scene that runs it (Hooke, linear history, one floor, periodic in x and
# y; time-series rows first and last only), with BUILD's binaries; sets lx and ly, the box [m].
# EXPONENT may also be "TX TY": the 10^4 seed bed tiled TX x TY times.
write_bench_scene() {
  local build=$1 work=$2 exponent=$3
  # shellcheck disable=SC2086  # "TX TY" is two arguments
  read -r lx ly < <("$build"/bench/gpudem-bench-write-bed $exponent "$work/bed.csv" | tail -1)
cat > "$work/scene.toml" <<TOML
[simulation]
end_time = 1.0
seed = 1

[domain]
min = [0.0, 0.0, 0.0]
max = [$lx, $ly, 0.3]
periodic = [true, true, false]

[[material]]
name = "grain"
density = 1850.0
young = 1.0e6
poisson = 0.3
restitution = 0.2
friction = 0.5

[contact]
stiffness = 2000.0

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "grain"

[[insert]]
csv = "bed.csv"

[output]
timeseries_every = 1.0  # first and last rows only: the loop times the steps, not diagnostics
TOML
}
