"""The checks of GaussianProcess.py's input: each bad argument is refused with a message that
says what to pass instead, before it can turn into a NaN or a bare numpy error."""
import math

import numpy as np

from PyRT_Common import Function, PDF, RGBColor, is_number

# A sample position is a unit direction when its length is within this of 1 (the course's
# directions, built from sines and square roots, are within a few units of 1e-16), and on
# the hemisphere around +y when its y is at least -UNIT_TOLERANCE.
UNIT_TOLERANCE = 1e-9


def check_positive_number(where: str, name: str, value, above: float = 0.0):
    """Refuses a value that is not a finite number larger than `above`."""
    if not is_number(value):
        raise TypeError(f"{where}: {name} must be a number, got {value!r}")
    if not (math.isfinite(value) and value > above):
        raise ValueError(f"{where}: {name} must be a finite number larger than {above:g}, "
                         f"got {value!r}")


def check_noise(where: str, noise):
    """Refuses a noise that is not a finite number of 0 or more."""
    if not is_number(noise):
        raise TypeError(f"{where}: noise_ must be a number (the standard deviation of the "
                        f"observations' noise, 0.01 by default), got {noise!r}")
    if not (math.isfinite(noise) and noise >= 0):
        raise ValueError(f"{where}: noise_ must be a finite number of 0 or more, got "
                         f"{noise!r}")


Z_ESTIMATES = ("exact", "course")


def check_z_estimate(z_estimate):
    """Refuses a z_estimate other than "exact" (quadrature) and "course" (the course's
    50,000-sample Monte Carlo)."""
    if z_estimate not in Z_ESTIMATES:
        raise ValueError(f"GP: z_estimate must be 'exact' (quadrature) or 'course' (the "
                         f"course's 50,000-sample Monte Carlo), got {z_estimate!r}")


def check_p_func(p_func):
    """Refuses a p_func that is neither a Function (Constant(1), CosineLobe(1), one of your
    own) nor a finite number."""
    if isinstance(p_func, Function):
        return
    if isinstance(p_func, PDF):
        raise TypeError(f"GP: p_func must be a Function, not the pdf {type(p_func).__name__}; "
                        "for the cosine pass CosineLobe(1), for no known part Constant(1)")
    if not is_number(p_func):
        raise TypeError(f"GP: p_func must be a Function (Constant(1), CosineLobe(1), one of "
                        f"your own) or a number, got {p_func!r}")
    if not math.isfinite(p_func):
        raise ValueError(f"GP: p_func must be a finite number, got {p_func!r}")


def check_cov_func(cov_func):
    """Refuses a cov_func without an eval(omega_i, omega_j) method."""
    if not callable(getattr(cov_func, "eval", None)):
        raise TypeError(f"GP: cov_func must be a CovarianceFunction (SobolevCov(), "
                        f"SECov(l, noise) or one of your own with eval(omega_i, omega_j)), "
                        f"got {cov_func!r}")


def positions_array(samples_pos) -> np.ndarray:
    """The sample positions as an (n, 3) array, refusing an empty set, anything but a list
    of vectors, and a position that is not a unit direction of the hemisphere around +y."""
    try:
        positions = list(samples_pos)
    except TypeError:
        raise TypeError(f"GP.add_sample_pos: samples_pos_ must be a list of Vector3D "
                        f"directions, got {samples_pos!r}") from None
    if not positions:
        raise ValueError("GP.add_sample_pos: the sample set is empty; pass at least one "
                         "direction (e.g. sample_set_hemisphere(40, UniformPDF())[0])")
    try:
        array = np.array([(p.x, p.y, p.z) for p in positions], dtype=float)
    except (AttributeError, TypeError, ValueError):
        raise TypeError("GP.add_sample_pos: samples_pos_ must be a list of Vector3D "
                        "directions (the first list that sample_set_hemisphere returns, "
                        "not the pair)") from None
    with np.errstate(invalid="ignore", over="ignore"):
        lengths = np.sqrt(np.einsum("ij,ij->i", array, array))
    bad = ~(np.abs(lengths - 1.0) <= UNIT_TOLERANCE) | (array[:, 1] < -UNIT_TOLERANCE)
    if bad.any():
        index = int(np.argmax(bad))
        position, length, y = positions[index], lengths[index], array[index, 1]
        if not math.isfinite(length):
            raise ValueError(f"GP.add_sample_pos: position {index} is not finite: "
                             f"{position!r}")
        if abs(length - 1.0) > UNIT_TOLERANCE:
            raise ValueError(f"GP.add_sample_pos: position {index} is not a unit direction "
                             f"(length {length:.6g}): {position!r}; Normalize it")
        raise ValueError(f"GP.add_sample_pos: position {index} lies below the hemisphere "
                         f"around +y (y = {y:.6g}): {position!r}; the GP's samples are "
                         "directions around +y, as sample_set_hemisphere draws them "
                         "(centre them around a normal afterwards)")
    return array


def check_values(samples_val, n_positions):
    """Refuses observations given before the positions, of another length than the
    positions, or not finite numbers or RGBColors."""
    if n_positions is None:
        raise ValueError("GP.add_sample_val: no sample positions yet; call "
                         "add_sample_pos(positions) first, then add_sample_val(values)")
    try:
        values = list(samples_val)
    except TypeError:
        raise TypeError(f"GP.add_sample_val: samples_val_ must be a list of RGBColor or "
                        f"numbers, got {samples_val!r}") from None
    if len(values) != n_positions:
        raise ValueError(f"GP.add_sample_val: {len(values)} values for {n_positions} sample "
                         "positions; pass one value per position, in the same order")
    colours = [isinstance(v, RGBColor) for v in values]
    for index, value in enumerate(values):
        parts = (value.r, value.g, value.b) if colours[index] else (value,)
        if not all(is_number(part) for part in parts):
            raise TypeError(f"GP.add_sample_val: value {index} must be an RGBColor of "
                            f"numbers or a number, got {value!r}")
    if any(colours) and not all(colours):
        raise TypeError(f"GP.add_sample_val: value {colours.index(not colours[0])} is "
                        f"{'a number' if colours[0] else 'an RGBColor'} where value 0 is "
                        f"{'an RGBColor' if colours[0] else 'a number'}; pass RGBColors "
                        "only or numbers only")
    channels = np.array([(v.r, v.g, v.b) for v in values] if colours[0] else values,
                        dtype=float)
    finite = np.isfinite(channels).reshape(len(values), -1).all(axis=1)
    if not finite.all():
        index = int(np.argmin(finite))
        raise ValueError(f"GP.add_sample_val: value {index} is not finite: "
                         f"{values[index]!r}; every observation must be a finite number")
    return values
