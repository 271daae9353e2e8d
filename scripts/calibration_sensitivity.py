"""The sensitivity of a calibration's targets at its best evaluation (scripts/calibrate.py
--sensitivity): each target's slope along each parameter from a Gaussian process through the
stored evaluations, and whether the optimum is unique or a ridge."""
import numpy as np

import calibration_optimizers as optimizers

FLAT_RISE = 1.0   # a direction is flat when half the range along it raises the objective less
SLOPE_STEP = 0.05  # half the unit-cube span of the difference quotient of a fitted slope


def axis_ends(at, step=SLOPE_STEP):
    """The points at ± step along each unit axis from `at`, clipped to [0, 1]: rows 2i, 2i + 1."""
    ends = np.repeat(np.atleast_2d(at), 2 * len(at), axis=0)
    for i, x in enumerate(at):
        ends[2 * i, i], ends[2 * i + 1, i] = min(1.0, x + step), max(0.0, x - step)
    return ends


def fitted_slopes(points, values, at, seed, noise_floor=0.0):
    """The slope along each unit axis at `at` of a Gaussian process fitted to `values` at the
    points (its noise fitted too, at least noise_floor), as the difference quotient of the
    posterior mean over axis_ends, with the posterior standard deviation of that quotient; and
    the fitted noise's standard deviation."""
    gp = optimizers.GaussianProcess(points, values).fit(np.random.default_rng(seed), restarts=5,
                                                        noise_floor=noise_floor)
    ends = axis_ends(at)
    mean, covariance = gp.predict(ends)[0], gp.covariance(ends)
    width = ends[0::2].diagonal() - ends[1::2].diagonal()
    hi, lo = np.arange(0, len(ends), 2), np.arange(1, len(ends), 2)
    slope = (mean[hi] - mean[lo]) / width * gp.scale
    variance = (covariance[hi, hi] + covariance[lo, lo] - 2 * covariance[hi, lo]) / width ** 2
    return slope, np.sqrt(np.maximum(variance, 0.0)) * gp.scale, gp.noise_sd()


def sensitivity(spec, records, seed=1, run_sd=None):
    """Each target's slope along each parameter at the best evaluation, from a Gaussian process
    fitted to every evaluation that ran through (fitted_slopes; its noise at least
    run_sd[quantity], the spread of the target between runs that differ only in chance), per
    unit of the parameter and across its range; the objective's Gauss–Newton Hessian in unit
    coordinates, 2 Σ_t g_t g_tᵀ / σ_t² (exact at an optimum that meets the targets), its
    eigenvalues and the flat directions, along which half the range raises the objective by
    less than FLAT_RISE."""
    d = len(spec.parameters)
    if len(records) < 2 * d + 2:
        raise ValueError(f"--sensitivity: a Gaussian process in {d} parameters needs at "
                         f"least {2 * d + 2} evaluations that ran through; there are "
                         f"{len(records)}")
    best = min(records, key=lambda r: r["objective"])
    points, at = np.array([r["point"] for r in records]), np.array(best["point"], dtype=float)
    per_unit = [1 / p.span() / (best["parameters"][p.name] if p.log else 1.0)
                for p in spec.parameters]
    targets, hessian = {}, np.zeros((d, d))
    for t in spec.targets:
        slope, sd, noise = fitted_slopes(points, [r["targets"][t.quantity] for r in records],
                                         at, seed, (run_sd or {}).get(t.quantity, 0.0))
        hessian += 2 * np.outer(slope, slope) / t.sigma ** 2
        targets[t.quantity] = {"noise_sd": noise, "slopes": {
            p.name: {"per_range": float(g), "per_range_sd": float(s),
                     "per_unit": float(g * u), "per_unit_sd": float(s * u)}
            for p, g, s, u in zip(spec.parameters, slope, sd, per_unit)}}
    eigenvalues, vectors = np.linalg.eigh(hessian)
    directions = [{"eigenvalue": float(v), "direction": dict(zip(
        (p.name for p in spec.parameters), map(float, vectors[:, k])))}
        for k, v in enumerate(eigenvalues)]
    flat = [x for x in directions if 0.5 * x["eigenvalue"] * 0.5 ** 2 < FLAT_RISE]
    return {"best": best, "evaluations": len(records), "targets": targets,
            "hessian_eigenvalues": [float(v) for v in eigenvalues], "flat_directions": flat,
            "fixed_directions": [x for x in directions if x not in flat],
            "optimum": "ridge" if flat else "unique"}


def print_sensitivity(spec, result, units):
    """The result of sensitivity() as text; units: the unit of each quantity."""
    print(f"sensitivity at evaluation {result['best']['evaluation']} (objective "
          f"{result['best']['objective']:.4g}), a Gaussian process through the "
          f"{result['evaluations']} evaluations that ran through:")
    for t in spec.targets:
        unit_name = units[t.quantity]
        fit = result["targets"][t.quantity]
        print(f"  {t.quantity}: the runs scatter by {fit['noise_sd']:.4g} {unit_name} (sd) "
              "about the fit")
        for p in spec.parameters:
            s = fit["slopes"][p.name]
            print(f"  d {t.quantity} / d {p.name}: {s['per_unit']:.4g} ± {s['per_unit_sd']:.2g} "
                  f"{unit_name} per unit at {result['best']['parameters'][p.name]:.4g} "
                  f"({s['per_range']:.4g} ± {s['per_range_sd']:.2g} {unit_name} across the "
                  f"range{', log scale' if p.log else ''})")
    values = ", ".join(f"{v:.4g}" for v in result["hessian_eigenvalues"])
    print(f"  objective Hessian eigenvalues (unit coordinates): {values}")
    for fixed in result["fixed_directions"]:
        print(f"  the targets fix the combination (eigenvalue {fixed['eigenvalue']:.4g}): "
              f"{direction_text(fixed)}")
    if result["optimum"] == "unique":
        print("  the optimum is unique: every direction raises the objective by more than "
              f"{FLAT_RISE:g} within half its range")
        return
    print(f"  the optimum is a ridge: {len(result['flat_directions'])} direction(s) along "
          f"which half the range raises the objective by less than {FLAT_RISE:g}:")
    for flat in result["flat_directions"]:
        print(f"    eigenvalue {flat['eigenvalue']:.4g}: {direction_text(flat)}")


def direction_text(eigen):
    """An eigenvector of sensitivity()'s Hessian as "name ±c, ..."."""
    return ", ".join(f"{n} {c:+.3f}" for n, c in eigen["direction"].items())
