"""The checks of Practice 2: your classic Monte Carlo estimate (Assignment 2.1) and your
Monte Carlo integrator (Assignment 2.3), run with your own code and judged against closed
forms (practice2_scenes.py).

`python -m pytest` runs them from the folder of AppRenderer.py (tests/test_practice2.py
holds one test per check, named after its step). practice2_render.py runs your code and
keeps what it makes as data; this module judges it:

- the estimate: compute_estimate_cmc on given sample sets must give (1/N) sum f/p, to
  rounding (EXACT_RELATIVE);
- the workbench's curve: the average error of your estimates on the directions that
  sample_set_hemisphere draws after random.seed(seed) must be the closed form's, to
  rounding: the course fixes the order of the draws (u1 then u2 for each sample);
- the integrator, in a white furnace and under an emitting sphere: where the answer is
  exact (what a camera ray that misses sees, what the camera sees of the emitter itself)
  it must be exact; where it is random, the mean of your pixels must lie within the
  tolerance of monte_carlo_check.py around the closed form's mean, which a correct
  integrator exceeds with a chance of at most one in a million per check (Bernstein's
  inequality, every term of the estimate bounded), one sum per channel.
A failing check says what differs and, when it recognises it, the likely mistake, and
writes your image (or curve), the expected one and their difference into out/checks/.
"""
import math
import threading
from pathlib import Path

import numpy as np

import monte_carlo_check
import practice1_checks
import practice2_render as render
import practice2_scenes as scenes

PROJECT = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
OUT = PROJECT / "out" / "checks"
EXACT_RELATIVE = 1e-9  # an estimate computed in another order differs in its last digits
EXACT_ABSOLUTE = 1e-12
# A map's value comes through OpenCV's float32 grey reading of the .hdr file
MAP_RELATIVE = 1e-5
MAP_ABSOLUTE = 1e-9
NAMED_WITHIN = 0.1  # a ratio within this fraction of a mistake's ratio names the mistake
PLOTTING = threading.Lock()

TITLES = {
    "estimate": "compute_estimate_cmc on given sample sets",
    "curve": "the workbench's curve of the average error (seeded)",
    "furnace": "CMCIntegrator in a white furnace (an environment map of one value)",
    "emitter": "CMCIntegrator on a floor under an emitting sphere",
}
STEPS = {"2.1": ("estimate", "curve"), "2.3": ("furnace", "emitter")}
STEP_OF = {name: step for step, names in STEPS.items() for name in names}
Check = practice1_checks.Check


def new_check(name):
    return Check(name, STEP_OF[name], TITLES[name])


def run_check(name, out=OUT, draw=scenes.PUBLISHED):
    """The Check called `name`, run on the student's modules with draw (the published one
    by default, its draws seeded as it says); its PNGs go into out/<name>/."""
    rendered = render.collect(name, draw, Path(out) / name)
    return judge_rendered(rendered, draw, Path(out) / name)


def judge_rendered(rendered, draw, folder):
    """The Check of what the student's code made for one check (a Rendered), judged
    against the closed forms of draw; PNGs written into folder."""
    check = new_check(rendered.name)
    if rendered.error is not None:
        check.error = rendered.error["traceback"]
        return check.fail(practice1_checks.error_reason(rendered.error))
    if rendered.name == "estimate":
        return _judge_estimate(check, rendered, draw)
    if rendered.name == "curve":
        return _judge_curve(check, rendered, draw, folder)
    return _judge_image(check, rendered, draw, folder)


def close(values, expected, relative=EXACT_RELATIVE, absolute=EXACT_ABSOLUTE):
    with np.errstate(invalid="ignore"):
        return np.abs(values - expected) <= absolute + relative * np.abs(expected)


# ------------------------------------------------------------------------------------------
# Assignment 2.1
# ------------------------------------------------------------------------------------------
def estimate_mistakes(draw):
    """{the likely mistake: the estimates it gives for draw's sample sets}."""
    sets = [(np.array(s.probs), np.array(s.values)) for s in draw.sample_sets]
    return {
        "compute_estimate_cmc returns 0 for every sample set: the handout's stub":
            np.zeros(len(sets)),
        "the estimate does not divide by the density: (1/N) sum f, where (1/N) sum "
        "f/p is asked": np.array([np.mean(f) for p, f in sets]),
        "the estimate multiplies by the density instead of dividing by it":
            np.array([np.mean(f * p) for p, f in sets]),
        "the estimate does not divide by the number of samples N: sum f/p":
            np.array([np.sum(f / p) for p, f in sets]),
        "the estimate divides by N - 1, not by the number of samples N":
            np.array([np.sum(f / p) / (len(f) - 1) for p, f in sets]),
        "the estimate divides by N + 1, not by the number of samples N":
            np.array([np.sum(f / p) / (len(f) + 1) for p, f in sets]),
    }


def _judge_estimate(check, rendered, draw):
    if rendered.first_color is not None:
        return check.fail(f"compute_estimate_cmc returned {rendered.first_color}, where "
                          "the estimate is a number (the red channel's)")
    got = rendered.arrays["estimates"]
    expected = scenes.estimates(draw)
    wrong = ~close(got, expected)
    if not wrong.any():
        return check.succeed()
    for mistake, values in estimate_mistakes(draw).items():
        if np.all(close(got, values)):
            return check.fail(mistake, _estimate_details(got, expected, draw))
    return check.fail(f"wrong for {int(wrong.sum())} of {len(got)} sample sets",
                      _estimate_details(got, expected, draw))


def _estimate_details(got, expected, draw):
    lines = []
    for k, (value, right) in enumerate(zip(got, expected)):
        if not close(value, right):
            lines.append(f"  sample set {k + 1} ({len(draw.sample_sets[k].values)} "
                         f"samples): yours {float(value)!r}, expected {float(right)!r}")
    return "\n".join(lines[:practice1_checks.SHOWN_PIXELS])


def _judge_curve(check, rendered, draw, folder):
    if rendered.first_color is not None:
        return check.fail(f"compute_estimate_cmc returned {rendered.first_color}, where "
                          "the estimate is a number (the red channel's)")
    got = rendered.arrays["curve"]
    expected = scenes.curve(draw.seed)
    wrong = ~close(got, expected)
    check.images = write_curve_pngs(folder, got, expected)
    if not wrong.any():
        return check.succeed()
    shown = ", ".join(f"N = {ns}: yours {value:.6g}, expected {right:.6g}"
                      for ns, value, right, bad in zip(scenes.CURVE_NS, got, expected, wrong)
                      if bad)
    return check.fail(f"the average error differs at {int(wrong.sum())} of "
                      f"{len(got)} numbers of samples (the curve of the course's figure "
                      "comes from compute_estimate_cmc: its check says more)", "  " + shown)


def write_curve_pngs(folder, got, expected):
    """The student's curve and the expected one, on the same log-log axes, as PNGs."""
    with PLOTTING:  # pyplot's figures are not for two threads at once (the grader's)
        return _curve_pngs(folder, got, expected)


def _curve_pngs(folder, got, expected):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter, StrMethodFormatter
    folder.mkdir(parents=True, exist_ok=True)
    finite = [v for v in np.concatenate([got, expected]) if np.isfinite(v)]
    high = max(max(finite, default=1.0), 0.0) * 1.15 or 1.0
    paths = {}
    for kind, values in (("render", got), ("expected", expected)):
        figure, axes = plt.subplots(figsize=(3, 3), dpi=80)
        axes.plot(scenes.CURVE_NS, np.where(np.isfinite(values), values, np.nan),
                  marker="o")
        axes.set_xscale("log")
        axes.set_ylim(0.0, high)
        axes.xaxis.set_major_formatter(StrMethodFormatter("{x:g}"))  # plain numbers
        axes.xaxis.set_minor_formatter(NullFormatter())
        axes.set_xticks(scenes.CURVE_NS)
        axes.set_xlabel("N")
        axes.set_title("average absolute error", fontsize=9)
        figure.subplots_adjust(left=0.2, bottom=0.16)
        paths[kind] = folder / f"{kind}.png"
        figure.savefig(paths[kind])
        plt.close(figure)
    return paths


# ------------------------------------------------------------------------------------------
# Assignment 2.3
# ------------------------------------------------------------------------------------------
def sums_of(image, expected, n_samples):
    """The Sums of the estimated pixels of image, one per channel."""
    return [monte_carlo_check.Sum(f"channel {'rgb'[c]}", image[..., c][expected.estimated],
                                  expected.value[..., c][expected.estimated],
                                  expected.bound[c], n_samples) for c in range(3)]


def judge_image(name, image, draw, delta=monte_carlo_check.FALSE_FAILURE):
    """(the Expected of the image `name` at draw; where its exact pixels are wrong, per
    channel; its Sums judged at the chance delta of failing a correct integrator)."""
    expected = scenes.EXPECTED[name](draw)
    relative, absolute = ((MAP_RELATIVE, MAP_ABSOLUTE) if name == "furnace"
                          else (EXACT_RELATIVE, EXACT_ABSOLUTE))
    exact_wrong = expected.exact[..., None] & ~close(image, expected.value, relative,
                                                      absolute)
    return expected, exact_wrong, monte_carlo_check.judge_sums(
        sums_of(image, expected, draw.n_samples), delta)


def _judge_image(check, rendered, draw, folder):
    if rendered.first_color is not None:
        return check.fail(f"compute_color returned {rendered.first_color}"
                          + (" (the handout's pass returns None)"
                             if rendered.first_color == "None" else "")
                          + ", where an RGBColor is needed")
    image = rendered.arrays["image"]
    expected, exact_wrong, judged = judge_image(rendered.name, image, draw)
    failed_sums = [one for one in judged if not one.passed]
    wrong = exact_wrong.any(axis=2) | (expected.estimated & bool(failed_sums))
    check.images = practice1_checks.write_pngs(folder, image, expected.value, wrong)
    if not exact_wrong.any() and not failed_sums:
        return check.succeed()
    reasons = []
    if exact_wrong.any():
        reasons.append(_exact_reason(rendered.name, image, expected, exact_wrong, draw))
    if failed_sums:
        reasons.append(_estimate_reason(rendered.name, judged, draw))
    details = "\n".join(f"  {one.describe()}" for one in judged)
    return check.fail("; ".join(reasons), details)


def _exact_reason(name, image, expected, exact_wrong, draw):
    pixels = exact_wrong.any(axis=2)
    count = int(pixels.sum())
    y, x = (int(v) for v in np.argwhere(pixels)[0])
    where = (f"{count} pixels whose answer is exact differ (the first at x = {x}, "
             f"y = {y}: yours {_rgb(image[y, x])}, expected "
             f"{_rgb(expected.value[y, x])})")
    if name == "furnace" and np.allclose(image[pixels], 0.0):
        return ("a camera ray that hits nothing sees black, not the environment map "
                "(scene.env_map.getValue(ray.d)): " + where)
    if name == "emitter":
        emission = np.asarray(draw.emitter.emission)
        if np.all(close(image[pixels], emission, 1e-6)):
            return ("the light of the object a camera ray hits is added (its emission): "
                    "the course's algorithm adds only what the sample rays gather: " + where)
    return where


def _rgb(pixel):
    return tuple(round(float(value), 6) for value in pixel)


def _estimate_reason(name, judged, draw):
    ratio = float(np.mean([one.ratio for one in judged]))
    seen = f"the estimate is {ratio:.3g} times the expected light on average"
    known = {2 / 3: "the cosine is counted twice: the Lambertian's get_value already "
                    "holds it (kd * cos), do not multiply by Dot(n, wi) again",
             1 / (2 * math.pi): "the estimate does not divide by the density p "
                                "(1 / (2 pi) for uniform sampling)",
             float(draw.n_samples): "the sum of the samples is not divided by their "
                                    f"number N = {draw.n_samples}"}
    for value, mistake in known.items():
        if abs(ratio - value) <= NAMED_WITHIN * value:
            return f"{mistake} ({seen})"
    if ratio <= NAMED_WITHIN:
        if name == "emitter":
            return ("no light from the emitter: the emission of the object a sample ray "
                    f"hits is its L_i (scene.object_list[hit.primitive_index].emission) "
                    f"({seen})")
        return f"no light reaches the object ({seen})"
    if name == "emitter" and ratio > 2:
        return ("far too bright where only some sample rays find light: the sum is "
                "divided by the sample rays that found light, not by all N "
                f"({seen})")
    return (f"{seen}, beyond what chance allows a correct integrator (one in a million): "
            "see each channel below")
