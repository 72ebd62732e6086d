"""How a check judges a Monte Carlo estimate, whose answer is random, without ever failing
a correct estimator but by a chance it states: at most FALSE_FAILURE (one in a million)
per check.

A correct estimator's pixel j is the mean of n independent terms, each within [0, b] (the
integrand and the density bounded, so f/p is) and of mean mu_j, the closed form of the
pixel. A check adds up the terms of many pixels, S = n * (the sum of their values), whose
expectation is n * (the sum of their mu_j). Bernstein's inequality bounds how far S
strays: for independent terms X_i within [0, b],

    P(|S - E S| >= s) <= 2 exp(-s^2 / (2 (V + b s / 3))),   V = sum of Var X_i,

and a term within [0, b] of mean mu has a variance of at most mu (b - mu) (the
Bhatia-Davis inequality), whatever the estimator's style (uniform or cosine sampling, any
order of draws): V <= n * sum of mu_j (b - mu_j). Setting the right side to delta and
solving for s gives the tolerance

    s = b L / 3 + sqrt((b L / 3)^2 + 2 V L),   L = ln(2 / delta).

A check of k such sums (a channel each, or a part of an image each) gives each delta / k,
so that by the union bound it fails a correct estimator with a chance of at most delta.
A mistake that moves the sum's expectation by more than twice its tolerance fails it
almost surely; benchmarks/monte_carlo_checks.py measures both rates.

Where the course fixes the order of the draws (sample_set_hemisphere draws u1 then u2 for
each sample), a check seeds Python's generator instead and compares exactly.
"""
import math
from dataclasses import dataclass
from typing import List

import numpy as np

FALSE_FAILURE = 1e-6  # the largest chance that a check fails a correct estimator


@dataclass(frozen=True)
class Sum:
    """One sum of a check: what it covers, the values of its pixels (one channel), their
    closed-form means, the bound b of a term, and the number n of terms per pixel."""

    label: str
    values: np.ndarray
    means: np.ndarray
    bound: float
    terms_per_value: int


@dataclass(frozen=True)
class Judged:
    """A Sum judged: the mean of its pixels against their expected mean, with the
    tolerance that a correct estimator exceeds with a chance of at most its share of the
    check's FALSE_FAILURE."""

    label: str
    observed: float
    expected: float
    tolerance: float

    @property
    def passed(self):
        return math.isfinite(self.observed) and abs(self.observed - self.expected) <= \
            self.tolerance

    @property
    def ratio(self):
        """observed / expected (nan when nothing is expected)."""
        return self.observed / self.expected if self.expected else math.nan

    def describe(self):
        return (f"{self.label}: mean {self.observed:.6g}, expected {self.expected:.6g} "
                f"+- {self.tolerance:.3g}")


def bernstein_tolerance(means, bound, terms_per_value, delta):
    """The tolerance s / (n m) on the mean of m pixel values, each the mean of n terms
    within [0, bound] whose means are `means`, that a correct estimator exceeds with a
    chance of at most delta (see the module's docstring)."""
    means = np.asarray(means, dtype=float)
    count = terms_per_value * means.size
    variance = terms_per_value * float(np.sum(means * (bound - means)))
    log_term = math.log(2.0 / delta)
    linear = bound * log_term / 3.0
    return (linear + math.sqrt(linear * linear + 2.0 * variance * log_term)) / count


def judge_sums(sums: List[Sum], delta=FALSE_FAILURE) -> List[Judged]:
    """Each Sum judged at its share delta / len(sums) of the check's chance of failing a
    correct estimator."""
    share = delta / len(sums)
    judged = []
    for one in sums:
        values = np.asarray(one.values, dtype=float)
        judged.append(Judged(one.label, float(np.mean(values)) if values.size else 0.0,
                             float(np.mean(one.means)) if values.size else 0.0,
                             bernstein_tolerance(one.means, one.bound,
                                                 one.terms_per_value, share)
                             if values.size else 0.0))
    return judged
