"""ESyS-Particle side of scripts/peers/compare.sh: the bed of inputs/bench/peers_bed.toml from
the same particles (the CSV written from gpudem-mpi's insertion), settled for SETTLE steps and
run SETTLED steps more. Pairs: ESyS-Particle's HertzMindlinVisco (Hertz normal spring from E
and nu, its viscous damping for restitution e, Mindlin tangential spring with Coulomb
friction). Walls: ESyS-Particle's plane walls are undamped, frictionless linear springs (the
only wall law it has for spheres) of stiffness 5,000 N/m: a sphere of R = 8.5 mm falling 0.3 m
onto it (2.4 m/s) overlaps it by 2.3 mm at most, as it overlaps a Hertz wall of the soil's own
E* = E / (2 (1 - nu^2)) by 2.2 mm (in the settled bed, under about 0.4 N, it sinks 0.09 mm
into the spring against 0.21 mm into the Hertz wall). ESyS-Particle multiplies a wall's
normalK by pi R in 3D (measured: a sphere resting on the floor sinks m g / (pi R normalK)), so
normalK is that stiffness over pi R. Same time step, skin, gravity and bin. Runs on WORKERS
worker ranks (slabs along x) under one master rank (mpirun -np WORKERS+1 esysparticle). Each
phase prints "Loop time of SECONDS on" and ends with a text dump (id x y z radius vx vy vz
omegax omegay omegaz), as the LAMMPS-family peers do.

Usage: mpirun -np WORKERS+1 esysparticle esys_peers.py CSV SETTLE SETTLED WORKERS
"""
import math
import sys
import time

from esys.lsm import (GravityPrms, HertzMindlinViscoPrms, LsmMpi, NRotElasticWallPrms,
                      RotSphere)
from esys.lsm.util import BoundingBox, Vec3

DENSITY = 1850.0
YOUNG, POISSON, FRICTION, RESTITUTION = 2.0e6, 0.38, 0.6, 0.5
WALL_STIFFNESS = 5.0e3  # N/m, the wall spring's stiffness (see above)
BIN = (1.0, 0.7)
WALLS = (("floor", (0, 0, 0), (0, 0, 1)), ("left", (0, 0, 0), (1, 0, 0)),
         ("right", (BIN[0], 0, 0), (-1, 0, 0)), ("front", (0, 0, 0), (0, 1, 0)),
         ("back", (0, BIN[1], 0), (0, -1, 0)))


def read_csv(path):
    with open(path) as f:
        names = f.readline().strip().split(",")
        rows = [dict(zip(names, map(float, line.split(",")))) for line in f if line.strip()]
    return rows


def build(rows, workers):
    sim = LsmMpi(numWorkerProcesses=workers, mpiDimList=[workers, 1, 1])
    r_max = max(row["r"] for row in rows)
    sim.initNeighbourSearch(particleType="RotSphere", gridSpacing=2 * r_max + 0.006,
                            verletDist=0.004)
    sim.setSpatialDomain(BoundingBox(Vec3(-0.05, -0.05, -0.05), Vec3(BIN[0] + 0.05,
                                                                   BIN[1] + 0.05, 0.5)))
    sim.setTimeStepSize(1.0e-4)
    for i, row in enumerate(rows):
        mass = DENSITY * 4.0 / 3.0 * math.pi * row["r"] ** 3
        sim.createParticle(RotSphere(id=i, posn=Vec3(row["x"], row["y"], row["z"]),
                                     radius=row["r"], mass=mass))
    for i, row in enumerate(rows):
        velocity = (row.get("vx", 0.0), row.get("vy", 0.0), row.get("vz", 0.0))
        if any(velocity):
            sim.setParticleVelocity(i, Vec3(*velocity))
    sim.createInteractionGroup(HertzMindlinViscoPrms(
        name="pairs", youngsModulus=YOUNG, poissonsRatio=POISSON, dynamicMu=FRICTION,
        restitution=RESTITUTION))
    sim.createGravity(GravityPrms(name="gravity", acceleration=Vec3(0.0, 0.0, -9.81)))
    r_mean = sum(row["r"] for row in rows) / len(rows)
    for name, point, normal in WALLS:
        sim.createWall(name=name, posn=Vec3(*point), normal=Vec3(*normal))
        sim.createInteractionGroup(NRotElasticWallPrms(
            name=name + "_contact", wallName=name, normalK=WALL_STIFFNESS / (math.pi * r_mean)))
    return sim


def dump(sim, path, step):
    particles = sorted(sim.getParticleList(), key=lambda p: p.getId())
    with open(path, "w") as f:
        f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(particles)}\n"
                "ITEM: ATOMS id x y z radius vx vy vz omegax omegay omegaz\n")
        for p in particles:
            values = [*p.getPosn().toList(), p.getRadius(), *p.getVelocity().toList(),
                      *p.getAngularVelocity().toList()]
            f.write(f"{p.getId() + 1} " + " ".join(f"{v:.10g}" for v in values) + "\n")


def main():
    path, settle, settled, workers = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), \
        int(sys.argv[4])
    sim = build(read_csv(path), workers)
    sim.setNumTimeSteps(settle + settled)
    for phase, steps in (("settle", settle), ("settled", settled)):
        start = time.perf_counter()
        for _ in range(steps):
            sim.runTimeStep()
        print(f"Loop time of {time.perf_counter() - start:.6g} on {workers} workers for "
              f"{steps} steps", flush=True)
        dump(sim, f"{phase}.dump", sim.getTimeStep())
    sim.exit()


main()
