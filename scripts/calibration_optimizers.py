"""The two optimizers of scripts/calibrate.py, on the unit cube [0, 1]^d: differential evolution
(rand/1/bin, the settings of the GPU DEM tillage thesis: a population of 60, mutation F = 0.8,
crossover CR = 0.5) and Gaussian-process Bayesian optimization (a Matérn 5/2 kernel with one
length scale per dimension, fitted with its signal and noise variances by the marginal
likelihood; expected improvement; batches by the kriging believer).

Both take evaluate(points) -> objective values, called with a whole batch (a generation of
differential evolution, a batch of proposals) so that the caller can run its points at once, and
both are deterministic given the seed and the values evaluate returns: run again on the same
values they ask for the same points, which is how a calibration resumes (scripts/calibrate.py
looks every point up among its stored evaluations first).
"""
import numpy as np
import scipy.optimize
import scipy.stats
from scipy.linalg import cho_factor, cho_solve, solve_triangular


def latin_hypercube(count, dimensions, rng):
    """`count` points of [0, 1]^d, one in each of `count` equal slices of every axis."""
    return scipy.stats.qmc.LatinHypercube(d=dimensions, seed=rng).random(count)


def differential_evolution(evaluate, dimensions, budget, seed, population=60, mutation=0.8,
                           crossover=0.5):
    """Differential evolution rand/1/bin (scipy's, one generation per evaluate call) from a
    Latin-hypercube population of `population` points, for budget // population generations
    (the first one the starting population)."""
    if budget < population:
        raise ValueError(f"a budget of {budget} evaluations does not cover one population "
                         f"of {population}")
    rng = np.random.default_rng(seed)
    start = latin_hypercube(population, dimensions, rng)

    def generation(_func, points):
        return evaluate([np.asarray(p, dtype=float) for p in points])

    scipy.optimize.differential_evolution(
        _never_called, [(0.0, 1.0)] * dimensions, strategy="rand1bin",
        maxiter=budget // population - 1, init=start, mutation=mutation,
        recombination=crossover, seed=rng, tol=0.0, atol=0.0, polish=False,
        updating="deferred", workers=generation)


def _never_called(_point):
    raise AssertionError("differential evolution evaluates through its workers map")


class GaussianProcess:
    """A zero-mean Gaussian process on standardised values with a Matérn 5/2 kernel
    s² (1 + √5 r + 5r²/3) exp(−√5 r), r² = Σ ((x_i − x'_i)/ℓ_i)², plus noise variance n² on
    the diagonal. fit() chooses log ℓ, log s² and log n² by the marginal likelihood."""

    def __init__(self, points, values):
        self.points = np.asarray(points, dtype=float)
        values = np.asarray(values, dtype=float)
        self.offset, self.scale = values.mean(), values.std() or 1.0
        self.values = (values - self.offset) / self.scale
        self.theta = None

    def kernel(self, a, b, theta):
        lengths, signal = np.exp(theta[:-2]), np.exp(theta[-2])
        r = np.sqrt(np.maximum(
            (((a[:, None, :] - b[None, :, :]) / lengths) ** 2).sum(axis=-1), 0.0))
        root5r = np.sqrt(5.0) * r
        return signal * (1.0 + root5r + root5r ** 2 / 3.0) * np.exp(-root5r)

    def _factor(self, theta):
        k = self.kernel(self.points, self.points, theta)
        k[np.diag_indices_from(k)] += np.exp(theta[-1]) + 1e-10
        return cho_factor(k, lower=True)

    def negative_log_likelihood(self, theta):
        try:
            factor = self._factor(theta)
        except np.linalg.LinAlgError:
            return 1e25
        alpha = cho_solve(factor, self.values)
        return 0.5 * self.values @ alpha + np.log(np.diag(factor[0])).sum()

    def fit(self, rng, restarts=3, noise_floor=0.0):
        """Maximum marginal likelihood over length scales 0.01–10, signal variance 0.05–20 and
        noise variance 1e-6–1 (on standardised values; at least noise_floor², noise_floor a
        standard deviation in the values' units), from the middle and `restarts` − 1 random
        starts."""
        d = self.points.shape[1]
        floor = np.log(max(1e-6, (noise_floor / self.scale) ** 2))
        bounds = [(np.log(0.01), np.log(10.0))] * d + [(np.log(0.05), np.log(20.0)),
                                                     (floor, max(0.0, floor))]
        starts = [np.array([np.log(0.3)] * d + [0.0, max(np.log(1e-3), floor)])]
        starts += [np.array([rng.uniform(lo, hi) for lo, hi in bounds])
                   for _ in range(restarts - 1)]
        fits = [scipy.optimize.minimize(self.negative_log_likelihood, s, method="L-BFGS-B",
                                        bounds=bounds) for s in starts]
        self.theta = min(fits, key=lambda fit: fit.fun).x
        self.condition()
        return self

    def condition(self):
        """Solves for the current data and hyperparameters (after fit() or added points)."""
        self.factor = self._factor(self.theta)
        self.alpha = cho_solve(self.factor, self.values)

    def add(self, point, standardised_value):
        """Adds a point (the kriging believer's fantasy) without refitting the hyperparameters."""
        self.points = np.vstack([self.points, point])
        self.values = np.append(self.values, standardised_value)
        self.condition()

    def covariance(self, x):
        """Posterior covariance, standardised, between the rows of x."""
        x = np.atleast_2d(x)
        v = solve_triangular(self.factor[0], self.kernel(x, self.points, self.theta).T, lower=True)
        return self.kernel(x, x, self.theta) - v.T @ v

    def noise_sd(self):
        """The fitted noise's standard deviation, in the values' units."""
        return float(np.sqrt(np.exp(self.theta[-1]))) * self.scale

    def predict(self, x):
        """Mean and standard deviation, standardised, at the rows of x."""
        k = self.kernel(np.atleast_2d(x), self.points, self.theta)
        mean = k @ self.alpha
        v = solve_triangular(self.factor[0], k.T, lower=True)
        variance = np.exp(self.theta[-2]) - (v * v).sum(axis=0)
        return mean, np.sqrt(np.maximum(variance, 1e-18))


def expected_improvement(gp, x, best):
    """E[max(best − Y(x), 0)] for minimisation, on the standardised scale."""
    mean, sd = gp.predict(x)
    z = (best - mean) / sd
    return (best - mean) * scipy.stats.norm.cdf(z) + sd * scipy.stats.norm.pdf(z)


def propose(gp, rng, best):
    """The point of [0, 1]^d with the largest expected improvement: the best of random and
    local candidates, refined by L-BFGS-B from the five best."""
    d = gp.points.shape[1]
    incumbents = gp.points[np.argsort(gp.predict(gp.points)[0])[:5]]
    local = np.clip(np.repeat(incumbents, 100, axis=0) +
                    rng.normal(0.0, 0.05, (100 * len(incumbents), d)), 0.0, 1.0)
    candidates = np.vstack([rng.random((1000 * d, d)), local])
    scores = expected_improvement(gp, candidates, best)
    refined = [scipy.optimize.minimize(lambda x: -expected_improvement(gp, x, best)[0], start,
                                       method="L-BFGS-B", bounds=[(0.0, 1.0)] * d)
               for start in candidates[np.argsort(-scores)[:5]]]
    point = min(refined, key=lambda fit: fit.fun).x
    if np.min(np.abs(gp.points - point).max(axis=1)) < 1e-9:  # a repeat: explore instead
        point = candidates[np.argmax(gp.predict(candidates)[1])]
    return point


def bayesian(evaluate, dimensions, budget, seed, batch=4, initial=None):
    """Gaussian-process Bayesian optimization of an objective >= 0 (modelled as log(1 + f)):
    a Latin-hypercube start of `initial` points (default 2d + 2), then batches of `batch`
    proposals by expected improvement, the kriging believer adding each proposal's predicted
    mean before the next, until `budget` evaluations."""
    rng = np.random.default_rng(seed)
    initial = min(budget, initial or 2 * dimensions + 2)
    points = list(latin_hypercube(initial, dimensions, rng))
    values = list(evaluate(points))
    while len(points) < budget:
        gp = GaussianProcess(points, np.log1p(np.maximum(values, 0.0))).fit(rng)
        best = gp.predict(gp.points)[0].min()
        proposals = []
        for _ in range(min(batch, budget - len(points))):
            point = propose(gp, rng, best)
            proposals.append(point)
            gp.add(point, gp.predict(point)[0][0])
        points += proposals
        values += list(evaluate(proposals))
