#!/usr/bin/python3
"""The optimizers of scripts/calibrate.py (scripts/calibration_optimizers.py) on a synthetic
calibration, no solver run: three parameters u in [0, 1]^3 give three "targets"
t(u) = J (u − u*) + 0.5 Σ sin(3 u_i) with measurement noise of standard deviation 0.3 on each
(the same for the same point), and the objective is Σ (t(u) − t(u*))², whose noise-free
minimum 0 lies at u* = (0.3, 0.7, 0.55).
A run reaches the tolerance at the evaluation after which its best evaluated point (the least
objective so far) lies within 0.03 of u* in every coordinate and stays so. Wanted: differential
evolution with the thesis's settings (population 60, F = 0.8, CR = 0.5) reaches it within 3,000
evaluations, Bayesian optimization (batches of 4) within 100, and in at most a fifth of the
evaluations differential evolution needs; both give the same points again from the same seed
and other points from another seed. Prints the evaluations each needed.
usage: check_calibration_optimizers.py PROJECT_SOURCE_DIR"""
import hashlib
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(sys.argv[1]) / "scripts"))
import calibration_optimizers as optimizers  # noqa: E402

OPTIMUM = np.array([0.3, 0.7, 0.55])
JACOBIAN = np.array([[40.0, 10.0, 0.0], [0.0, 30.0, -15.0], [5.0, 0.0, 25.0]])
TOLERANCE = 0.03
failures = []


def targets(u):
    return JACOBIAN @ (u - OPTIMUM) + 0.5 * np.sin(3 * u).sum()


def measured(u):
    seed = int.from_bytes(hashlib.sha256(np.asarray(u, dtype=float).tobytes()).digest()[:8],
                          "little")
    return targets(u) + np.random.default_rng(seed).normal(0.0, 0.3, 3)


def objective(u):
    return float(((measured(u) - targets(OPTIMUM)) ** 2).sum())


def run(method, seed, **settings):
    """The points evaluated, in order, with their objectives."""
    history = []

    def evaluate(points):
        values = [objective(p) for p in points]
        history.extend(zip((tuple(p) for p in points), values))
        return values

    method(evaluate, 3, seed=seed, **settings)
    return history


def evaluations_to_tolerance(history):
    """The evaluation count after which the best point stays within TOLERANCE of the optimum;
    None when the last best is outside it."""
    best, reached = None, None
    for count, (point, value) in enumerate(history, 1):
        if best is None or value < best[1]:
            best = (np.array(point), value)
            inside = np.abs(best[0] - OPTIMUM).max() < TOLERANCE
            reached = (reached or count) if inside else None
    return reached


de = run(optimizers.differential_evolution, 1, budget=3000, population=60, mutation=0.8,
         crossover=0.5)
bo = run(optimizers.bayesian, 1, budget=100, batch=4)
de_count, bo_count = evaluations_to_tolerance(de), evaluations_to_tolerance(bo)
print(f"evaluations to within {TOLERANCE} of the optimum: differential evolution {de_count} "
      f"of {len(de)}, Bayesian optimization {bo_count} of {len(bo)}")
if len(de) != 3000 or len(bo) != 100:
    failures.append(f"budgets: {len(de)} and {len(bo)} evaluations, wanted 3000 and 100")
if de_count is None or bo_count is None:
    failures.append(f"not within {TOLERANCE}: differential evolution {de_count}, "
                    f"Bayesian optimization {bo_count}")
elif bo_count > de_count / 5:
    failures.append(f"Bayesian optimization needs {bo_count} evaluations, more than a fifth "
                    f"of differential evolution's {de_count}")
if any(np.any(np.array(p) < 0) or np.any(np.array(p) > 1) for p, _ in de + bo):
    failures.append("a point outside the unit cube")

again = run(optimizers.differential_evolution, 1, budget=600, population=60)
if again != de[:600]:
    failures.append("differential evolution from the same seed asked for other points")
if run(optimizers.differential_evolution, 2, budget=60, population=60) == de[:60]:
    failures.append("differential evolution from another seed asked for the same points")
if run(optimizers.bayesian, 1, budget=16, batch=4) != bo[:16]:
    failures.append("Bayesian optimization from the same seed asked for other points")
if run(optimizers.bayesian, 2, budget=8, batch=4) == bo[:8]:
    failures.append("Bayesian optimization from another seed asked for the same points")

# The Gaussian process itself: it interpolates noise-free data of a smooth function closely.
rng = np.random.default_rng(3)
points = rng.random((30, 2))
truth = np.sin(4 * points[:, 0]) + points[:, 1] ** 2
gp = optimizers.GaussianProcess(points, truth).fit(rng)
probe = rng.random((50, 2))
mean, sd = gp.predict(probe)
error = np.abs(mean * gp.scale + gp.offset - (np.sin(4 * probe[:, 0]) + probe[:, 1] ** 2)).max()
if error > 0.05 or not np.all(sd >= 0):
    failures.append(f"the Gaussian process misses a smooth function by {error:.3g} (> 0.05)")

for failure in failures:
    print(failure)
print(f"check_calibration_optimizers: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
