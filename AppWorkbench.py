"""The Monte Carlo workbench of Practices 2, 3 and 4: estimates an integral over the
hemisphere many times for each number of samples N, and plots the average absolute error
against N, beside the error that theory predicts (classic Monte Carlo) or that the Gaussian
process believes (Bayesian Monte Carlo).

Run it with no arguments (the play button of VSCode) for Assignment 2.1, the integral of
cos over the hemisphere (pi), with uniform sampling (MC) and cosine sampling (MC IS);
`--practice 3` for Assignment 3.2 (MC against BMC on the same integral), `--practice 4`
for Practice 4 (MC, MC IS, BMC and BMC IS on the integral of cos^3 times cos, 2 pi/5).
`python AppWorkbench.py --help` lists the options. The plot is saved as
out/workbench_error.png (out/workbench_error_practice3.png, ...) next to this script and
shown in a window when there is a screen.
"""
import argparse
import math
import os
import sys
import time
from pathlib import Path
from typing import NamedTuple, Optional

# FRAMEWORK ONLY BEGIN
# The GPs' matrices are small (N up to a few hundred): the linear algebra inverts them
# fastest on one thread, where threads that wait for a busy core make each inverse several
# times slower. Set before numpy is imported, unless the environment says otherwise.
for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_threads, "1")
# FRAMEWORK ONLY END
import matplotlib
from matplotlib.ticker import LogLocator, NullFormatter, NullLocator, StrMethodFormatter
from tqdm import tqdm

from PyRT_Common import *
from GaussianProcess import *
# The module random, for random.seed. It comes after the star import, which brings the
# function random() under the same name.
import random

# out/ next to this script, wherever it is run from
DIRECTORY = Path(__file__).resolve().parent / "out"
# The plots: Practice 2's workbench_error.png, Practice 3's workbench_error_practice3.png
# and workbench_weights_practice3.png, and so on
FILENAME = "workbench_error.png"
WEIGHTS_STEM = "workbench_weights"
# --weights shows a GP of the number of samples closest to this (Practice 3's renders' 40)
WEIGHTS_SAMPLES = 40


class Integrand(NamedTuple):
    """An integrand: Functions multiplied together, the value of their integral over the
    hemisphere, and how the plot writes that integral."""
    functions: list
    ground_truth: float
    title: str


class Method(NamedTuple):
    """A Monte Carlo method of the plot: the course's label and marker, and the pdf it
    samples directions from (with its name on the command line). A Bayesian Monte Carlo
    method also has p_func, the known part p of the integrand f p that goes into the GP's
    z, and the Functions whose product is f, the GP's observations (None: the whole
    integrand)."""
    label: str
    marker: str
    pdf: PDF
    pdf_name: str
    p_func: Optional[object] = None
    value_functions: Optional[list] = None

    @property
    def is_bmc(self) -> bool:
        return self.p_func is not None


# The integrands are of the form L_i * BRDF * cos; their constants are 1, so each integral is
# the get_integral() of the one Function that is not constant.
INTEGRANDS = {
    # Assignment 2.1: L_i = 1, a BRDF of kd = 1 and the cosine
    "cos": Integrand([Constant(1), Constant(1), CosineLobe(1)], CosineLobe(1).get_integral(),
                     r"$\int_{H^2} \, \cos\theta \, d\omega = \pi$"),
    # The course's figure: L_i = 1 and a lobe cos^4
    "cos4": Integrand([Constant(1), CosineLobe(4)], CosineLobe(4).get_integral(),
                      r"$\int_{H^2} \, \cos^4\theta \, d\omega = 2\pi/5$"),
    # The solid angle of the hemisphere
    "constant": Integrand([Constant(1)], Constant(1).get_integral(),
                          r"$\int_{H^2} \, 1 \, d\omega = 2\pi$"),
}
# Practice 4: f p with f = cos^3 and the cosine p known, the integral of cos^4
PRACTICE4_INTEGRAND = Integrand([CosineLobe(3), CosineLobe(1)], CosineLobe(4).get_integral(),
                                r"$\int_{H^2} \, \cos^3\theta \, \cos\theta \, d\omega "
                                r"= 2\pi/5$")
PDFS = {"uniform": UniformPDF(), "cos": CosinePDF(1), "cos4": CosinePDF(4)}
# MC IS always samples the cosine: for the integrand cos it has zero variance
IMPORTANCE_PDF = "cos"

# The theory's sigma comes from the midpoint rule on a grid of QUADRATURE_GRID x
# QUADRATURE_GRID points (u1, u2) of the unit square, and is checked against the grid of half
# as many points a side: a sigma that moves by more than the fraction SETTLED between the two
# does not settle, the variance of f/p is infinite (or too large to trust a line drawn from it).
QUADRATURE_GRID = 128
SETTLED = 0.01
# f/p is constant, and every estimate exact, when its values differ by less than this
# fraction of their mean: the rounding of f / p.
CONSTANT = 1e-12


# ------------------------------------------------------------------------------------------
# The course's functions
# ------------------------------------------------------------------------------------------
def collect_samples(function_list, sample_pos_):
    """The integrand at each direction of sample_pos_: the product of the eval of every
    function of function_list, as RGBColor(value, 0, 0) (only the red channel is used)."""
    sample_values = []
    for omega in sample_pos_:
        value = 1
        for function in function_list:
            value *= function.eval(omega)
        sample_values.append(RGBColor(value, 0, 0))
    return sample_values


def compute_estimate_cmc(sample_prob_, sample_values_):
    """The classic Monte Carlo estimate (1/N) sum f(omega_j) / p(omega_j) of the red
    channel, from the densities p and the values f of N samples."""
    total = 0.0
    for prob, value in zip(sample_prob_, sample_values_):
        total += value.r / prob
    return total / len(sample_values_)


def compute_estimate_bmc(gp, sample_pos_, sample_values_):
    """The Bayesian Monte Carlo estimate sum over i of w_i Y_i of the red channel, from a
    fresh GP, the sample directions and the values Y of f there."""
    # ASSIGNMENT 3.2 BEGIN
    gp.add_sample_pos(sample_pos_)
    gp.add_sample_val(sample_values_)
    return gp.compute_integral_BMC().r
    # ASSIGNMENT 3.2 END


def practice3_methods(mc_pdf_name: str):
    """Assignment 3.2's methods: classic Monte Carlo (samples from the pdf named
    mc_pdf_name) against Bayesian Monte Carlo with uniform samples and p = 1, the GP
    modelling the whole integrand."""
    methods = [Method("MC", "o", PDFS[mc_pdf_name], mc_pdf_name)]
    # ASSIGNMENT 3.2 BEGIN
    methods.append(Method("BMC", "x", UniformPDF(), "uniform", p_func=Constant(1)))
    # ASSIGNMENT 3.2 END
    return methods


def practice4_methods():
    """Practice 4's methods on the integral of f p, f = cos^3 and p = cos: MC (uniform),
    MC IS (samples from the cosine), BMC (uniform, p = 1, the GP modelling cos^4) and
    BMC IS (samples from the cosine, p = cos in z, the GP modelling f = cos^3 alone)."""
    methods = [Method("MC", "o", UniformPDF(), "uniform")]
    # ASSIGNMENT 4.1 BEGIN
    methods.append(Method("MC IS", "v", CosinePDF(1), "cos"))
    # ASSIGNMENT 4.1 END
    methods.append(Method("BMC", "x", UniformPDF(), "uniform", p_func=Constant(1)))
    # ASSIGNMENT 4.2 BEGIN
    methods.append(Method("BMC IS", "1", CosinePDF(1), "cos", p_func=CosineLobe(1),
                          value_functions=[CosineLobe(3)]))
    # ASSIGNMENT 4.2 END
    return methods


# ------------------------------------------------------------------------------------------
# The experiment
# ------------------------------------------------------------------------------------------
def absolute_errors(integrand: Integrand, pdf: PDF, ns: int, n_estimates: int) -> np.ndarray:
    """The absolute errors |estimate - ground truth| of n_estimates classic Monte Carlo
    estimates of ns samples drawn from pdf each."""
    errors = np.zeros(n_estimates)
    for i in range(n_estimates):
        sample_set, sample_prob = sample_set_hemisphere(ns, pdf)
        sample_values = collect_samples(integrand.functions, sample_set)
        estimate = compute_estimate_cmc(sample_prob, sample_values)
        errors[i] = abs(estimate - integrand.ground_truth)
    return errors


class BMCErrors(NamedTuple):
    """The absolute errors of Bayesian Monte Carlo estimates, and for each the error its GP
    believes in, sqrt(2/pi) sqrt(compute_variance_BMC()) (the average distance of a normal
    variable from its mean)."""
    errors: np.ndarray
    believed: np.ndarray


def bmc_absolute_errors(integrand: Integrand, method: Method, ns: int,
                        n_estimates: int) -> BMCErrors:
    """The absolute errors |estimate - ground truth| of n_estimates Bayesian Monte Carlo
    estimates of ns samples drawn from method.pdf each, every one with a fresh sample set
    and a fresh GP (the Sobolev kernel, p = method.p_func), and the errors the GPs
    believe in."""
    functions = method.value_functions or integrand.functions
    errors, believed = np.zeros(n_estimates), np.zeros(n_estimates)
    for i in range(n_estimates):
        sample_set, _ = sample_set_hemisphere(ns, method.pdf)
        gp = GP(SobolevCov(), method.p_func)
        estimate = compute_estimate_bmc(gp, sample_set, collect_samples(functions, sample_set))
        errors[i] = abs(estimate - integrand.ground_truth)
        believed[i] = math.sqrt(2 / pi) * math.sqrt(gp.compute_variance_BMC())
    return BMCErrors(errors, believed)


class Measured(NamedTuple):
    """The matrices (sample counts x methods) of the average absolute error of each method
    and of the average error its GPs believe in (0 for classic Monte Carlo)."""
    results: np.ndarray
    believed: np.ndarray


def measure(integrand: Integrand, methods: list, ns_vector, n_estimates: int,
            bmc_estimates: int, progress: bool = True) -> Measured:
    """The average absolute errors of n_estimates estimates of each classic method, and of
    bmc_estimates of each Bayesian one, with each number of samples of ns_vector."""
    shape = (len(ns_vector), len(methods))
    results, believed = np.zeros(shape), np.zeros(shape)
    for k, ns in enumerate(tqdm(ns_vector, desc="Sample counts", disable=not progress)):
        for m, method in enumerate(methods):
            if method.is_bmc:
                bmc = bmc_absolute_errors(integrand, method, ns, bmc_estimates)
                results[k, m], believed[k, m] = np.mean(bmc.errors), np.mean(bmc.believed)
            else:
                results[k, m] = np.mean(absolute_errors(integrand, method.pdf, ns,
                                                        n_estimates))
    return Measured(results, believed)


def average_errors(integrand: Integrand, methods: list, ns_vector, n_estimates: int,
                   progress: bool = True) -> np.ndarray:
    """The matrix results (sample counts x methods): the average absolute error of
    n_estimates estimates of each method with each number of samples of ns_vector."""
    return measure(integrand, methods, ns_vector, n_estimates, n_estimates,
                   progress).results


# ------------------------------------------------------------------------------------------
# The theory
# ------------------------------------------------------------------------------------------
def f_over_p_grid(function_list, pdf: PDF, n: int) -> np.ndarray:
    """f/p at the directions pdf.generate_dir(u1, u2) of the n x n midpoints (u1, u2) of the
    unit square. Directions made from uniform u1, u2 have density p, so the mean of any
    g(omega) over these points is the midpoint rule for the mean of g under p."""
    values = []
    for i in range(n):
        for j in range(n):
            omega = pdf.generate_dir((i + 0.5) / n, (j + 0.5) / n)
            f = math.prod(function.eval(omega) for function in function_list)
            values.append(f / pdf.get_val(omega))
    return np.array(values)


def standard_deviation(function_list, pdf: PDF) -> float:
    """The standard deviation sigma of f/p under p, by quadrature (f_over_p_grid): 0.0 where
    f/p is constant, inf where the variance does not settle as the grid is refined."""
    fine = f_over_p_grid(function_list, pdf, QUADRATURE_GRID)
    if np.ptp(fine) <= CONSTANT * abs(np.mean(fine)):
        return 0.0
    sigma = float(np.std(fine))
    coarse_sigma = float(np.std(f_over_p_grid(function_list, pdf, QUADRATURE_GRID // 2)))
    if abs(sigma - coarse_sigma) > SETTLED * sigma:
        return math.inf
    return sigma


def expected_error(sigma: float, ns):
    """The average absolute error that theory predicts for N = ns samples,
    sqrt(2/pi) sigma / sqrt(N): the mean of N draws of f/p is close to normal with standard
    deviation sigma / sqrt(N) (central limit theorem), and a normal variable of standard
    deviation s lies on average sqrt(2/pi) s from its mean."""
    return math.sqrt(2 / pi) * sigma / np.sqrt(ns)


def describe(method: Method, sigma: Optional[float], errors: np.ndarray) -> str:
    """One line on what theory says of a method's error, from the sigma of its f/p and its
    measured average errors (sigma None: a Bayesian method, which theory does not bound)."""
    if method.is_bmc:
        return (f"{method.label}: {method.pdf_name} samples, a GP of SobolevCov() with p = "
                f"{p_name(method.p_func)}; its belief sqrt(2/pi) sqrt(compute_variance_BMC()) "
                f"is the error the GP expects if f were drawn from its prior: a belief, "
                f"not a bound")
    if sigma == 0.0:
        return (f"{method.label}: zero variance, every estimate is exact (error 0 at every N; "
                f"the largest measured is {errors.max():.1e}, rounding)")
    if math.isinf(sigma):
        return (f"{method.label}: f/p has no finite variance under the {method.pdf_name} pdf "
                f"(its quadrature does not settle), so theory draws no line "
                f"sqrt(2/pi) sigma / sqrt(N)")
    return (f"{method.label}: {method.pdf_name} pdf, sigma of f/p = {sigma:.4f} (quadrature), "
            f"average error in theory sqrt(2/pi) sigma / sqrt(N)")


def p_name(p_func) -> str:
    """How the workbench writes a GP's p: 1, cos, cos^e, or the Function's class."""
    if isinstance(p_func, CosineLobe):
        return "cos" if p_func.exp == 1 else f"cos^{p_func.exp:g}"
    if isinstance(p_func, Constant):
        return f"{p_func.const_value:g}"
    return type(p_func).__name__


def error_table(ns_vector, results: np.ndarray, methods: list, sigmas: list,
                believed: Optional[np.ndarray] = None) -> str:
    """The measured average errors and the theory's (classic Monte Carlo) or the GPs'
    belief (Bayesian Monte Carlo), one row per number of samples."""
    header = f"{'N':>5}" + "".join(
        f"{method.label:>10}{'belief' if method.is_bmc else 'theory':>10}"
        for method in methods)
    rows = [header]
    for k, ns in enumerate(ns_vector):
        row = f"{ns:>5}"
        for m, (method, sigma) in enumerate(zip(methods, sigmas)):
            if method.is_bmc:
                theory = f"{believed[k, m]:.4f}"
            else:
                theory = "-" if math.isinf(sigma) else f"{expected_error(sigma, ns):.4f}"
            row += f"{results[k, m]:>10.4f}{theory:>10}"
        rows.append(row)
    return "\n".join(rows)


# ------------------------------------------------------------------------------------------
# The plot
# ------------------------------------------------------------------------------------------
def plot_errors(ns_vector, results: np.ndarray, methods: list, sigmas: list,
                integrand: Integrand, n_estimates: int, believed: Optional[np.ndarray] = None,
                bmc_estimates: Optional[int] = None):
    """The figure of the average absolute error against N on log-log axes: for each method
    its measured error (solid, with the course's marker) and the theory's or, for a
    Bayesian method, its GPs' belief (dashed). A log scale has no 0, so a method of zero
    variance is named in the legend and not drawn; when every method has zero variance the
    y axis is linear and shows their errors at 0."""
    bayesian = any(method.is_bmc for method in methods)
    # Bayesian methods add beliefs to the legend, which then stands beside the axes
    figure, axes = plt.subplots(figsize=(11.0, 5.5) if bayesian else (7.5, 5.5))
    log_scale = any(method.is_bmc or sigma != 0.0 for method, sigma in zip(methods, sigmas))
    for m, (method, sigma) in enumerate(zip(methods, sigmas)):
        colour = f"C{m}"
        if method.is_bmc:
            axes.plot(ns_vector, results[:, m], color=colour, marker=method.marker,
                      label=method.label)
            axes.plot(ns_vector, believed[:, m], color=colour, linestyle="--",
                      label=rf"{method.label} belief: $\sqrt{{2/\pi}}\,\sqrt{{Var}}$ "
                            "(not a bound)")
            continue
        if sigma == 0.0:
            label = f"{method.label}: zero variance, error 0 at every N"
            if log_scale:
                axes.plot([], [], color=colour, marker=method.marker, linestyle="none",
                          label=label + " (not drawn)")
                continue
        elif math.isinf(sigma):
            label = f"{method.label} (infinite variance: no theory line)"
        else:
            label = method.label
        axes.plot(ns_vector, results[:, m], color=colour, marker=method.marker, label=label)
        if 0.0 < sigma < math.inf:
            axes.plot(ns_vector, expected_error(sigma, ns_vector), color=colour,
                      linestyle="--", label=rf"{method.label} theory: $\sqrt{{2/\pi}}\,"
                                            rf"\sigma/\sqrt{{N}}$, $\sigma$ = {sigma:.3f}")
    axes.set_xscale("log")
    if len(ns_vector) <= 8:  # few enough to label each number of samples
        axes.set_xticks(ns_vector, labels=[str(ns) for ns in ns_vector])
        axes.xaxis.set_minor_locator(NullLocator())
    else:
        label_log_axis(axes.xaxis, ns_vector[0], ns_vector[-1])
    if log_scale:
        axes.set_yscale("log")
        label_log_axis(axes.yaxis, *axes.get_ylim())
    else:  # wide enough that errors of rounding, 1e-15, lie on the line 0
        axes.set_ylim(-1.0, 1.0)
    axes.set_xlabel("number of samples N")
    axes.set_ylabel("average absolute error")
    axes.grid(True, which="both", alpha=0.3)
    if bayesian:
        axes.set_title(f"Average absolute error of {n_estimates} MC and {bmc_estimates} "
                       f"BMC estimates of\n{integrand.title}")
        axes.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")
    else:
        axes.set_title(f"Average absolute error of {n_estimates} estimates of "
                       f"{integrand.title}")
        axes.legend()
    figure.tight_layout()
    return figure


def plot_weights(method: Method, ns: int):
    """The figure of visualize_sample_set for one GP of a Bayesian method: ns directions
    drawn from its pdf, coloured by their weights w_i divided by the weights' sum (the
    colours run from 0.7/n to 1.3/n, around the 1/n of equal weights)."""
    sample_set, _ = sample_set_hemisphere(ns, method.pdf)
    gp = GP(SobolevCov(), method.p_func)
    gp.add_sample_pos(sample_set)
    figure = visualize_sample_set(sample_set, gp.weights / np.sum(gp.weights), show=False)
    figure.axes[0].set_title(f"{method.label}: the weights of a GP of {ns} samples "
                             f"({method.pdf_name}), over their sum", pad=28)
    figure.tight_layout()
    return figure


def label_log_axis(axis, low: float, high: float):
    """Labels a log axis from low to high with plain numbers (0.2, not 2 x 10^-1), every
    0.5 from 1 to 9.5 times each power of ten when it spans less than a factor 3, every 1
    within a decade, and 1, 2 and 5 times each power of ten across more."""
    if high / low < 3:
        subs = np.arange(1.0, 10.0, 0.5)
    elif high / low < 10:
        subs = range(1, 10)
    else:
        subs = (1, 2, 5)
    axis.set_major_locator(LogLocator(subs=subs))
    axis.set_major_formatter(StrMethodFormatter("{x:g}"))
    axis.set_minor_formatter(NullFormatter())


def has_screen() -> bool:
    """Whether plt.show() can open a window: matplotlib's backend is interactive and, on
    Linux, there is a display to show it on."""
    backend = matplotlib.get_backend().lower()
    if backend in ("agg", "pdf", "ps", "svg", "pgf", "cairo", "template"):
        return False
    if sys.platform.startswith("linux"):
        return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return True


# ------------------------------------------------------------------------------------------
# The command line
# ------------------------------------------------------------------------------------------
class OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line (--help shows the usage)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def count_arg(text: str) -> int:
    """An argparse type: a whole number of 1 or more."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number of 1 or more, got {text!r}")
    return value


def parse_args(argv):
    """The options of the command line."""
    parser = OneLineParser(
        prog="AppWorkbench.py",
        description="Estimate an integral over the hemisphere with classic and Bayesian "
                    "Monte Carlo, many times for each number of samples N, and plot the "
                    "average absolute error against N beside theory's (or the GP's "
                    "belief). With no options: Assignment 2.1, the integral of cos (pi), "
                    "sampled uniformly (MC) and by the cosine (MC IS).")
    parser.add_argument("--practice", type=int, choices=(2, 3, 4), default=2,
                        help="2: MC and MC IS (Assignment 2.1); 3: MC against BMC with "
                             "p = 1 (Assignment 3.2); 4: MC, MC IS, BMC and BMC IS on the "
                             "integral of cos^3 times cos, 2 pi / 5 (default: 2)")
    parser.add_argument("--integrand", choices=INTEGRANDS, default="cos",
                        help="Practices 2 and 3: cos: L_i * BRDF * cos with L_i = kd = 1, "
                             "pi (Assignment 2.1); cos4: L_i * cos^4, 2 pi / 5 (the "
                             "course's figure); constant: 1, 2 pi (default: cos)")
    parser.add_argument("--pdf", choices=PDFS, default="uniform",
                        help="Practices 2 and 3: the pdf of the MC curve: uniform, cos "
                             "(CosinePDF(1)) or cos4 (CosinePDF(4)); MC IS samples "
                             "CosinePDF(1) (default: uniform)")
    parser.add_argument("--ns-min", type=count_arg, default=20,
                        help="the smallest number of samples (default 20)")
    parser.add_argument("--ns-max", type=count_arg, default=101,
                        help="the numbers of samples stop below this (default 101)")
    parser.add_argument("--ns-step", type=count_arg, default=20,
                        help="the step between numbers of samples (default 20)")
    parser.add_argument("--estimates", type=count_arg, default=1000,
                        help="estimates averaged for each number of samples (default 1000)")
    parser.add_argument("--bmc-estimates", type=count_arg, default=100,
                        help="BMC estimates averaged for each number of samples, each with "
                             "a fresh sample set and GP (default 100)")
    parser.add_argument("--weights", action="store_true",
                        help="Practices 3 and 4: also plot the weights of one GP of the "
                             f"N closest to {WEIGHTS_SAMPLES} (visualize_sample_set), as "
                             f"{WEIGHTS_STEM}_practice<3 or 4>.png")
    parser.add_argument("--seed", type=int, default=0,
                        help="the seed of Python's random numbers (default 0)")
    parser.add_argument("--out", type=Path, default=DIRECTORY,
                        help="folder for the plot (default: out/ next to this script)")
    parser.add_argument("--no-window", action="store_true",
                        help="save the plot without showing it")
    args = parser.parse_args(argv)
    if args.practice == 4 and (args.integrand, args.pdf) != ("cos", "uniform"):
        parser.error("argument --practice: Practice 4 has the course's integrand and pdfs "
                     "(cos^3 times cos; uniform and cosine samples): leave out --integrand "
                     "and --pdf")
    if args.weights and args.practice == 2:
        parser.error("argument --weights: the weights are a GP's; use --practice 3 or 4")
    if args.ns_min >= args.ns_max:
        parser.error(f"argument --ns-max: the numbers of samples run from --ns-min "
                     f"{args.ns_min} to below --ns-max, which must be larger, got "
                     f"{args.ns_max}")
    return args


def refuse(message: str) -> int:
    """Prints a one-line error of the command line; returns the exit status 1."""
    print(f"AppWorkbench.py: error: {message}", file=sys.stderr)
    return 1


def main(argv=None) -> int:
    """Runs the workbench as the command line asks; returns the exit status."""
    args = parse_args(argv)
    try:  # the folder first: a wrong --out is said before the estimates, not after them
        args.out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        return refuse(f"cannot make the folder {args.out} for the plot: {error.strerror}")
    random.seed(args.seed)

    # The integrand, the methods and the experimental set-up, as the course names them
    integrand = INTEGRANDS[args.integrand]
    methods = [Method("MC", "o", PDFS[args.pdf], args.pdf),
               Method("MC IS", "v", PDFS[IMPORTANCE_PDF], IMPORTANCE_PDF)]
    if args.practice == 3:
        methods = practice3_methods(args.pdf)
    elif args.practice == 4:
        integrand, methods = PRACTICE4_INTEGRAND, practice4_methods()
    ns_min, ns_max, ns_step = args.ns_min, args.ns_max, args.ns_step
    ns_vector = np.arange(start=ns_min, stop=ns_max, step=ns_step)
    n_estimates = args.estimates
    print("Ground truth: " + str(integrand.ground_truth))

    start = time.perf_counter()
    measured = measure(integrand, methods, ns_vector, n_estimates, args.bmc_estimates)
    results = measured.results
    counts = f"{n_estimates}"
    if args.practice != 2:
        counts = f"{n_estimates} MC and {args.bmc_estimates} BMC"
    print(f"{counts} estimates per number of samples in {time.perf_counter() - start:.1f} s")
    sigmas = [None if method.is_bmc else standard_deviation(integrand.functions, method.pdf)
              for method in methods]
    for m, (method, sigma) in enumerate(zip(methods, sigmas)):
        print(describe(method, sigma, results[:, m]))
    print(error_table(ns_vector, results, methods, sigmas, measured.believed))

    suffix = "" if args.practice == 2 else f"_practice{args.practice}"
    figures = {FILENAME.replace(".png", suffix + ".png"): plot_errors(
        ns_vector, results, methods, sigmas, integrand, n_estimates, measured.believed,
        args.bmc_estimates)}
    if args.weights:
        bmc = [method for method in methods if method.is_bmc][-1]
        ns = int(ns_vector[np.argmin(np.abs(ns_vector - WEIGHTS_SAMPLES))])
        figures[f"{WEIGHTS_STEM}{suffix}.png"] = plot_weights(bmc, ns)
    for name, figure in figures.items():
        path = args.out / name
        try:
            figure.savefig(path, dpi=100)
        except OSError as error:
            return refuse(f"cannot save the plot as {path}: {error.strerror}")
        print(f"Saved {path}")
    if not args.no_window:
        if has_screen():
            plt.show()
        else:
            print("No screen: the plot is saved, not shown.")
    for figure in figures.values():
        plt.close(figure)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
