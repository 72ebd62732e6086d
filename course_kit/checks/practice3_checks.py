"""The checks of Practices 3 and 4: your Gaussian process (3.1), the workbench's BMC
estimate (3.2), your Bayesian Monte Carlo integrator (3.3) and its decorrelation (3.3.2),
classic Monte Carlo with importance sampling (4.1) and BMC with importance sampling (4.2),
run with your own code and judged against practice3_scenes.py.

`python -m pytest` runs them from the folder of AppRenderer.py (tests/test_practice3.py and
tests/test_practice4.py hold one test per check). practice3_render.py runs your code and
keeps what it makes as data; this module judges it:

- exact, to rounding, where the answer is a function of the inputs: Q^-1 on given
  positions, the BMC sum on given weights and colours, the workbench's estimate, and every
  integrator in the white furnace (the GPs handed to your integrators are the kit's, with
  known weights, so that their pixels are known exactly; cosine sampling makes classic
  Monte Carlo exact there);
- a workbench written as the course's script (no compute_estimate_bmc or
  practice4_methods to call) is read, not run: it passes when its code makes the course's
  calls of the step's estimate (a GP of the right p given positions and values,
  compute_integral_BMC; CosinePDF for MC IS), and the check's note says so;
- compute_z: equal, to rounding, to the course's estimate on the directions that
  sample_set_hemisphere draws after random.seed (the handout's set-up); a z computed
  otherwise must lie within the tolerance of monte_carlo_check.py around the exact z for
  50,000 samples (Bernstein's inequality: every term k p / (1 / (2 pi)) lies within
  [0, 2 pi 2^(2s-1)/s]), which a correct estimate exceeds with a chance of at most one in a
  million for the whole check;
- 3.3.2, from the rays your integrator casts at the floor's hits (all of the same normal):
  every GP of a pool of POOL is used (a correct integrator leaves one out with a chance of
  at most POOL (1 - 1/POOL)^M, M the floor's pixels: below 1e-15), and the sample sets of
  two hits are the same for fewer than half of the pairs that used the same GP (a correct
  integrator repeats a set only by drawing the same angle to the last bit, a chance below
  M^2 2^-53 < 1e-11 for any pair).
A failing check says what differs and, when it recognises it, the likely mistake.
"""
import math
from pathlib import Path

import numpy as np

import monte_carlo_check
import practice1_checks
import practice2_checks
import practice3_render as render
import practice3_scenes as scenes

PROJECT = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
OUT = PROJECT / "out" / "checks"
EXACT_RELATIVE = 1e-9
INVERSE_RELATIVE = 1e-7  # of Q^-1's largest entry: an inverse loses digits to Q's condition
NAMED_WITHIN = 0.05  # a ratio within this fraction of a mistake's ratio names the mistake
REPEATED_PAIRS = 0.5  # the fraction of same-GP hit pairs with one sample set that fails

TITLES = {
    "inv_q": "compute_inv_Q on given positions",
    "z": "compute_z for p = 1 and p = cos",
    "bmc_sum": "compute_integral_BMC on given weights and values",
    "workbench": "the workbench's compute_estimate_bmc with a GP of known weights",
    "bmc_furnace": "BayesianMonteCarloIntegrator in a white furnace",
    "bmc_box": "BayesianMonteCarloIntegrator inside a box of emitting walls",
    "bmc_pool": "BayesianMonteCarloIntegrator with a pool of GPs above a floor",
    "cmcis_furnace": "classic Monte Carlo with cosine sampling in a white furnace",
    "bmcis_furnace": "BMCISIntegrator in a white furnace",
    "workbench_mc_is": "the workbench's MC IS method (practice4_methods)",
    "workbench_bmc_is": "the workbench's BMC IS method (practice4_methods)",
}
STEPS = {"3.1": ("inv_q", "z", "bmc_sum"), "3.2": ("workbench",),
         "3.3": ("bmc_furnace", "bmc_box"), "3.3.2": ("bmc_pool",),
         "4.1": ("workbench_mc_is", "cmcis_furnace"),
         "4.2": ("workbench_bmc_is", "bmcis_furnace")}
STEP_OF = {name: step for step, names in STEPS.items() for name in names}
# A course-style workbench (a script, no function to call) is judged on its calls
SCRIPT_NOTE = ("your AppWorkbench.py is a script with no {function}: nothing of it can be "
               "called on given inputs, so it is judged on the course's calls its code "
               "makes ({calls}); {rest}; the plot it draws is for your teaching assistant "
               "to read")
Check = practice1_checks.Check
close = practice2_checks.close


def new_check(name):
    return Check(name, STEP_OF[name], TITLES[name])


def run_check(name, out=OUT, draw=scenes.PUBLISHED):
    """The Check called `name`, run on the student's modules with draw (the published one
    by default); its PNGs go into out/<name>/."""
    import random
    random.seed(draw.seed)
    rendered = render.collect(name, draw, Path(out) / name)
    return judge_rendered(rendered, draw, Path(out) / name)


def judge_rendered(rendered, draw, folder):
    """The Check of what the student's code made for one check (a Rendered), judged
    against draw; PNGs written into folder."""
    check = new_check(rendered.name)
    if rendered.error is not None:
        check.error = rendered.error["traceback"]
        return check.fail(_error_reason(rendered))
    if rendered.first_color is not None:
        return check.fail(f"your code returned {rendered.first_color}"
                          + (" (a stub's pass returns None)"
                             if rendered.first_color == "None" else "")
                          + ", where " + ("an RGBColor is" if "furnace" in rendered.name
                                          or rendered.name in ("bmc_sum", "bmc_pool")
                                          else "numbers are") + " needed")
    return JUDGES[rendered.name](check, rendered, draw, folder)


def _error_reason(rendered):
    error = rendered.error
    if rendered.name == "inv_q" and "Singular matrix" in error.get("text", ""):
        return ("np.linalg.inv refused Q as singular: Q is still all zeros (the handout's "
                "stub); fill Q[i, j] = cov_func.eval(pos_i, pos_j) and add noise^2 on the "
                "diagonal")
    return practice1_checks.error_reason(error)


def _named(got, candidates, relative=1e-6):
    """The first mistake of candidates, {mistake: values}, that got equals, or None."""
    for mistake, values in candidates.items():
        if np.all(close(got, values, relative, 1e-12)):
            return mistake
    return None


# ------------------------------------------------------------------------------------------
# Assignment 3.1
# ------------------------------------------------------------------------------------------
def _judge_inv_q(check, rendered, draw, folder):
    got = rendered.arrays["inv_q"]
    k = scenes.kernel_matrix(draw.positions)
    identity = np.identity(len(k))
    expected = np.linalg.inv(k + draw.noise ** 2 * identity)
    scale = float(np.max(np.abs(expected)))
    if np.all(np.abs(got - expected) <= INVERSE_RELATIVE * scale):
        return check.succeed()
    mistake = _named(got, {
        "Q holds the noise alone: the loop Q[i, j] = cov_func.eval(pos_i, pos_j) is still "
        "the handout's stub": np.linalg.inv(draw.noise ** 2 * identity),
        "Q has no noise on its diagonal: Q[i, i] = k(omega_i, omega_i) + noise^2":
            np.linalg.inv(k),
        "the diagonal gets the noise, where noise^2 is asked":
            np.linalg.inv(k + draw.noise * identity),
        "Q itself is returned, not its inverse": k + draw.noise ** 2 * identity,
        "the noise is the default 0.01, not the GP's own noise":
            np.linalg.inv(k + scenes.GP_NOISE ** 2 * identity),
    }, 1e-5)
    details = (f"  noise {draw.noise}, positions {draw.positions}\n  yours:\n"
               f"{np.array2string(got, precision=6)}\n  expected:\n"
               f"{np.array2string(expected, precision=6)}")
    return check.fail(mistake or "Q^-1 differs from the inverse of K + noise^2 I", details)


def _judge_z(check, rendered, draw, folder):
    notes, reasons, lines = [], [], []
    for key, p_exponent, offset in (("z_one", 0, 0), ("z_cos", 1, 1)):
        got = rendered.arrays[key]
        label = "p = 1" if p_exponent == 0 else "p = cos"
        seeded = scenes.course_z(draw.seed + offset, draw.positions, p_exponent)
        if np.all(close(got, seeded)):
            continue
        exact = scenes.exact_z(draw.positions, p_exponent)
        share = monte_carlo_check.FALSE_FAILURE / (2 * len(exact))
        tolerance = np.array([monte_carlo_check.bernstein_tolerance(
            [mu], scenes.z_term_bound(), scenes.COURSE_NS_Z, share)
            for mu in exact])
        lines.append(f"  {label}: yours {np.round(got, 6)}, exact {np.round(exact, 6)} "
                     f"+- {np.round(tolerance, 4)}, the course's seeded estimate "
                     f"{np.round(seeded, 6)}")
        if np.all(np.isfinite(got)) and np.all(np.abs(got - exact) <= tolerance):
            notes.append(f"{label}: not the seeded course estimate, but within chance of "
                         "the exact z")
            continue
        reasons.append(f"{label}: " + _z_mistake(got, exact, draw, p_exponent))
    if not reasons:
        return check.succeed("; ".join(notes))
    return check.fail("; ".join(reasons), "\n".join(lines))


def _z_mistake(got, exact, draw, p_exponent):
    if np.all(got == 0):
        return "z is all zeros: compute_z is still the handout's stub"
    density = 1 / (2 * math.pi)
    ratio = float(np.mean(got / exact))
    known = {density: "z does not divide by the density 1 / (2 pi) of the uniform "
                      "directions",
             density ** 2: "z multiplies by the density 1 / (2 pi) instead of dividing",
             scenes.COURSE_NS_Z: "z is the sum of the terms, not divided by their number"}
    if p_exponent == 1:
        without_p = scenes.exact_z(draw.positions, 0)
        if np.allclose(got, without_p, rtol=0.02):
            return ("z leaves out p: z_i is the integral of k(omega_i, omega) p(omega); "
                    "multiply each term by p_func.eval(omega) (or by p_func when it is a "
                    "number)")
    for value, mistake in known.items():
        if abs(ratio - value) <= NAMED_WITHIN * value:
            return f"{mistake} (z is {ratio:.3g} times the exact z)"
    return (f"z is {ratio:.4g} times the exact z on average, beyond what chance allows a "
            "50,000-sample estimate (one in a million): is each term k p divided by the "
            "density of the directions it is drawn from (1 / (2 pi), uniform)?")


def _judge_sum(check, rendered, draw, folder):
    got = rendered.arrays["sums"]
    expected = np.array([scenes.bmc_sum(case) for case in draw.sums])
    if np.all(close(got, expected)):
        return check.succeed()
    mistake = _named(got, {
        "the integral is BLACK: compute_integral_BMC is still the handout's stub":
            np.zeros_like(expected),
        "the values are averaged, not weighted: sum over i of w_i Y_i is asked":
            np.array([np.mean(case.values, axis=0) for case in draw.sums]),
        "the values are summed without their weights w_i":
            np.array([np.sum(case.values, axis=0) for case in draw.sums]),
        "the weighted sum is divided by the number of samples: BMC's weights already "
        "hold it": np.array([scenes.bmc_sum(case) / len(case.weights)
                              for case in draw.sums]),
    })
    details = "\n".join(f"  case {k + 1} ({len(case.weights)} samples): yours "
                        f"{np.round(one, 6)}, expected {np.round(right, 6)}"
                        for k, (case, one, right) in enumerate(zip(draw.sums, got,
                                                                     expected)))
    return check.fail(mistake or "the integral differs from sum over i of w_i Y_i", details)


# ------------------------------------------------------------------------------------------
# Assignment 3.2
# ------------------------------------------------------------------------------------------
def _script_calls(rendered, names):
    """The calls of SCRIPT_CALLS of names that the workbench's code never makes."""
    flags = dict(zip(render.SCRIPT_CALLS, rendered.arrays["script"]))
    return [name for name in names if not flags[name]]


def _judge_script(check, rendered, function, calls, rest):
    """A course-style workbench's check: passed when its code makes every call of calls."""
    missing = _script_calls(rendered, calls)
    if missing:
        return check.fail(f"your AppWorkbench.py defines no {function} and its code never "
                          f"calls {', '.join(missing)}: " + rest)
    return check.succeed(SCRIPT_NOTE.format(function=function, calls=", ".join(calls),
                                            rest=rest))


def _is_script(rendered):
    return not rendered.arrays["script"][-1]


def _judge_workbench(check, rendered, draw, folder):
    if _is_script(rendered):
        return _judge_script(
            check, rendered, "compute_estimate_bmc(gp, sample_pos_, sample_values_)",
            ("GP with p = 1", "add_sample_pos", "add_sample_val", "compute_integral_BMC"),
            "BMC's estimate is a GP given the samples' positions and values, then "
            "compute_integral_BMC, whose arithmetic Assignment 3.1 judges")
    got = rendered.arrays["estimates"]
    expected = np.array([scenes.cos_sum(gp) for gp in draw.pool])
    if np.all(close(got, expected)):
        return check.succeed()
    shown = ", ".join(f"yours {a:.6g}, expected {b:.6g}" for a, b in zip(got, expected))
    mistake = _named(got, {"compute_estimate_bmc returns 0: the handout's stub":
                           np.zeros_like(expected)})
    return check.fail(mistake or "the estimate is not sum over i of w_i Y_i of the GP given "
                      "its positions, then its values (the red channel)", "  " + shown)


# ------------------------------------------------------------------------------------------
# The integrators
# ------------------------------------------------------------------------------------------
def _furnace_check(check, rendered, draw, folder, factor, mistakes, on_average=None):
    """The furnace's image against c rho factor on the sphere and c on the sky, exactly;
    mistakes: {mistake: the factor it gives, exactly}; on_average: {mistake: the factor
    it gives on average (within a tenth)}, for estimates that are random."""
    image = rendered.arrays["image"]
    expected = scenes.furnace_expected(draw, factor)
    wrong = expected.exact[..., None] & ~close(image, expected.value,
                                               practice2_checks.MAP_RELATIVE,
                                               practice2_checks.MAP_ABSOLUTE)
    pixels = wrong.any(axis=2)
    check.images = practice1_checks.write_pngs(folder, image, expected.value, pixels)
    if not pixels.any():
        return check.succeed()
    sphere = scenes.furnace_sphere(draw)
    sphere_wrong = pixels & sphere
    y, x = (int(v) for v in np.argwhere(pixels)[0])
    where = (f"{int(pixels.sum())} pixels differ (the first at x = {x}, y = {y}: yours "
             f"{_rgb(image[y, x])}, expected {_rgb(expected.value[y, x])})")
    if not sphere_wrong.any():
        return check.fail("a camera ray that hits nothing sees the environment map "
                          "(scene.env_map.getValue(ray.d)): " + where)
    base = np.asarray(draw.furnace.albedo) * draw.furnace.sky
    ratio = image[sphere] / base
    for mistake, value in mistakes.items():
        if np.allclose(ratio, value, rtol=1e-4, atol=1e-12):
            return check.fail(f"{mistake}: {where}")
    mean = float(np.mean(ratio)) / factor if factor else float("nan")
    seen = f"the sphere's pixels are {mean:.4g} times the expected light on average"
    for mistake, value in (on_average or {}).items():
        if abs(mean - value) <= 0.1 * value:
            return check.fail(f"{mistake} ({seen}): {where}")
    return check.fail(f"{seen}: {where}")


def _rgb(pixel):
    """A pixel's channels as a text of plain numbers."""
    return "(" + ", ".join(f"{float(v):.6g}" for v in pixel) + ")"


def _judge_bmc_furnace(check, rendered, draw, folder):
    gp = draw.pool[0]
    y = np.asarray(gp.positions)[:, 1]
    w = np.asarray(gp.weights)
    return _furnace_check(check, rendered, draw, folder, scenes.cos_sum(gp) / math.pi, {
        "the cosine is counted twice: the Lambertian's get_value already holds it, the "
        "values are L_i times the BRDF's value": float(w @ y ** 2) / math.pi,
        "the values leave out the BRDF: Y_j is L_i times BRDF.get_value(...)":
            float(np.sum(w)) / np.asarray(draw.furnace.albedo),
        "the values are L_i kd, without the cosine: with p = 1 the GP models the whole "
        "integrand, L_i times the BRDF's value (kd cos)": float(np.sum(w)) / math.pi,
        "the integral is BLACK: compute_color returns the handout's stub": 0.0})


def _judge_bmc_box(check, rendered, draw, folder):
    image = rendered.arrays["image"]
    expected = scenes.box_expected(draw, scenes.cos_sum(draw.pool[0]) / math.pi)
    wrong = (expected.exact[..., None] & ~close(image, expected.value, EXACT_RELATIVE * 1e3,
                                                1e-12)).any(axis=2)
    check.images = practice1_checks.write_pngs(folder, image, expected.value, wrong)
    if not wrong.any():
        return check.succeed()
    sphere = scenes.furnace_sphere(draw)
    y, x = (int(v) for v in np.argwhere(wrong)[0])
    where = (f"{int(wrong.sum())} pixels differ (the first at x = {x}, y = {y}: yours "
             f"{_rgb(image[y, x])}, expected {_rgb(expected.value[y, x])})")
    if (wrong & sphere).any() and np.allclose(image[sphere], 0.0):
        return check.fail("no light from the walls: the emission of the object a sample "
                          "ray hits is its L_i (scene.object_list[hit.primitive_index]"
                          ".emission): " + where)
    walls = expected.exact & ~sphere
    if (wrong & walls).any() and np.allclose(image[walls], scenes.box_emission(draw)):
        return check.fail("the emission of the object a camera ray hits is added: the "
                          "course's algorithm adds only what the sample rays gather: " + where)
    return check.fail(where)


def _judge_bmcis_furnace(check, rendered, draw, folder):
    gp = draw.pool_is[0]
    y = np.asarray(gp.positions)[:, 1]
    w = np.asarray(gp.weights)
    return _furnace_check(check, rendered, draw, folder, float(np.sum(w)) / math.pi, {
        "the values keep the cosine: with p = cos in z the GP models L_i kd alone, not the "
        "BRDF's value (kd cos)": float(w @ y) / math.pi,
        "the cosine is counted twice": float(w @ y ** 2) / math.pi,
        "no light: the stub's BLACK": 0.0})


def _judge_cmcis_furnace(check, rendered, draw, folder):
    return _furnace_check(check, rendered, draw, folder, 1.0, {
        "no light: the stub's BLACK": 0.0}, on_average={
        "the cosine is counted twice: the Lambertian's get_value already holds it": 2 / 3,
        "the estimate does not divide by the density p = cos / pi": 2 / (3 * math.pi),
        "the directions are not drawn from the cosine (CosinePDF(1)): with cosine "
        "sampling every term is L kd pi, exact in a white furnace": 1.0})


def _judge_pool(check, rendered, draw, folder):
    floor = scenes.floor_pixels(draw)
    chosen = rendered.arrays["chosen"][floor].astype(int)
    sets = rendered.arrays["directions"][floor]
    count = int(floor.sum())
    if np.any(chosen < 0):
        return check.fail("compute_integral_BMC of no GP of the pool was called at "
                          f"{int(np.sum(chosen < 0))} of the floor's {count} hits")
    unused = sorted(set(range(scenes.POOL)) - set(chosen.tolist()))
    if unused:
        return check.fail(f"GPs {unused} of a pool of {scenes.POOL} were never used in "
                          f"{count} hits: choose a GP of the pool (myGP, a list) at random "
                          "at each hit")
    pairs = repeated = 0
    keys = [tuple(sorted(map(tuple, np.round(one, 12)))) for one in sets]
    for index in range(scenes.POOL):
        mine = [key for key, gp in zip(keys, chosen) if gp == index]
        counts = {}
        for key in mine:
            counts[key] = counts.get(key, 0) + 1
        pairs += len(mine) * (len(mine) - 1) // 2
        repeated += sum(c * (c - 1) // 2 for c in counts.values())
    if pairs and repeated / pairs >= REPEATED_PAIRS:
        return check.fail(f"the same sample set is cast at every hit of a GP ({repeated} of "
                          f"{pairs} pairs of hits with the same GP): turn the set about y "
                          "(rotate_around_y) by a random angle at each hit, before it is "
                          "centred around the normal")
    return check.succeed()


def _judge_workbench_method(check, rendered, draw, folder):
    label = render.WORKBENCH_CHECKS[rendered.name]
    if _is_script(rendered):
        if label == "MC IS":
            return _judge_script(check, rendered, "practice4_methods()",
                                 ("CosinePDF", "compute_estimate_cmc"),
                                 "MC IS is the classic estimate of samples drawn from "
                                 "CosinePDF(1)")
        return _judge_script(check, rendered, "practice4_methods()",
                             ("GP with p = CosineLobe", "add_sample_pos",
                              "compute_integral_BMC"),
                             "BMC IS is a GP whose p is CosineLobe(1), which goes into z")
    y = np.asarray(draw.pool[0].positions)[:, 1]
    pdf, p, f = (rendered.arrays[key] for key in ("pdf", "p", "f"))
    if np.all(np.isnan(pdf)):
        return check.fail(f"practice4_methods() has no method labelled {label!r} (the "
                          "handout's stub adds none)")
    if not np.all(close(pdf, y / math.pi)):
        return check.fail(f"{label} does not sample from the cosine, CosinePDF(1) "
                          "(density cos / pi)")
    if label == "MC IS":
        return check.succeed()
    if not np.all(close(p, y)):
        return check.fail("BMC IS's p is not the cosine (p_func = CosineLobe(1), which "
                          "goes into z)")
    if np.all(close(f, y ** 4)):
        return check.fail("BMC IS's values keep the cosine: with p = cos the GP models "
                          "f = cos^3 alone")
    if not np.all(close(f, y ** 3)):
        return check.fail("BMC IS's values are not f = cos^3")
    return check.succeed()


JUDGES = {"inv_q": _judge_inv_q, "z": _judge_z, "bmc_sum": _judge_sum,
          "workbench": _judge_workbench, "bmc_furnace": _judge_bmc_furnace,
          "bmc_box": _judge_bmc_box,
          "bmc_pool": _judge_pool, "cmcis_furnace": _judge_cmcis_furnace,
          "bmcis_furnace": _judge_bmcis_furnace,
          "workbench_mc_is": _judge_workbench_method,
          "workbench_bmc_is": _judge_workbench_method}
