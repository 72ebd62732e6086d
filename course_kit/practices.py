"""The practices the kit hands out, checks and grades: what each one's handout holds, its
graded steps, its checks and the judge of its grading.

A practice's handout is the finished framework with the solution blocks of its own steps
and of every later practice's replaced by the course's stubs, and those of the earlier
practices kept (without their markers): Practice 2's handout is Practice 1 finished. Each
practice ships its own checks (course_kit/checks/practice<N>_*.py, with what they share),
and its grading runs each step in a process of its own with the practice's render module
(the checks' code that runs the student's code and hands back data) and judges the data
with the practice's judge module (course_kit/judging*.py). Adding a practice is adding a
Practice here, its checks and its judge.
"""
from dataclasses import dataclass
from typing import Dict, Tuple

# The four modules of every practice, and Practice 2's workbench script beside them
FRAMEWORK_MODULES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py",
                     "AppRenderer.py")
WORKBENCH = "AppWorkbench.py"
GAUSSIAN_PROCESS = "GaussianProcess.py"  # Practice 3's module, beside the workbench


@dataclass(frozen=True)
class Practice:
    """One practice of the course: its number; the course modules its handout holds (and
    students hand in); its graded steps, {step: title}, in order (optional steps have
    checks in the handout but no points); the checks' files (course_kit/checks/<name> goes
    to tests/<name> in the handout) and expected data (course_kit/checks/expected/<name>);
    the packages its handout installs; the check module that runs the student's code in a
    step's process (render: course_kit/isolation.py loads it, with what it imports, before
    any step); and the module of the grader's judge."""

    number: int
    modules: Tuple[str, ...]
    steps: Dict[str, str]
    check_files: Tuple[str, ...]
    expected: Tuple[str, ...]
    packages: Tuple[str, ...]
    render: str
    judge: str


def practice_of(step):
    """The number of the practice a step belongs to: 2 for "2.3", 1 for "1.1-1.2"."""
    return int(step.split(".", 1)[0])


# Practices 3 and 4 share their checks' modules (practice3_*.py), which use Practice 2's
BAYESIAN_CHECK_FILES = ("monte_carlo_check.py", "practice1_checks.py", "practice1_render.py",
                        "practice2_scenes.py", "practice2_checks.py", "practice2_render.py",
                        "practice3_scenes.py", "practice3_checks.py", "practice3_render.py")

PRACTICES = {
    1: Practice(
        number=1,
        modules=FRAMEWORK_MODULES,
        steps={
            "1.1": "Assignment 1.1: the render loop (Lazy integrator)",
            "1.2": "Assignment 1.2: any_hit and the Intersection integrator",
            "1.3": "Assignment 1.3: the Depth and Normal integrators",
            "1.4": "Assignment 1.4: the Phong integrator",
        },
        check_files=("practice1_checks.py", "practice1_render.py", "test_practice1.py"),
        expected=("practice1.npz",),
        packages=("numpy", "opencv-python-headless", "matplotlib", "pytest"),
        render="practice1_render", judge="course_kit.judging"),
    2: Practice(
        number=2,
        # the workbench imports GaussianProcess.py, handed out with Practice 3's stubs, as
        # the base code carries the integrators of later practices as stubs
        modules=FRAMEWORK_MODULES + (WORKBENCH, GAUSSIAN_PROCESS),
        steps={
            "2.1": "Assignment 2.1: the classic Monte Carlo estimate (the workbench)",
            "2.3": "Assignment 2.3: the classic Monte Carlo integrator",
        },
        # Practice 1's checks lend their verdicts, images and error reports
        check_files=("monte_carlo_check.py", "practice1_checks.py", "practice1_render.py",
                     "practice2_scenes.py", "practice2_checks.py", "practice2_render.py",
                     "test_practice2.py"),
        expected=(),
        packages=("numpy", "opencv-python-headless", "matplotlib", "tqdm", "pytest"),
        render="practice2_render", judge="course_kit.judging_practice2"),
    3: Practice(
        number=3,
        modules=FRAMEWORK_MODULES + (WORKBENCH, GAUSSIAN_PROCESS),
        steps={
            "3.1": "Assignment 3.1: the Gaussian process (compute_inv_Q, compute_z, "
                   "compute_integral_BMC)",
            "3.2": "Assignment 3.2: the workbench's BMC estimate",
            "3.3": "Assignment 3.3: the Bayesian Monte Carlo integrator",
            "3.3.2": "Assignment 3.3.2: a random rotation and a pool of GPs per hit",
        },
        # 3.2: the handout's compute_estimate_bmc called, or a course-style workbench (a
        # script with no function to call) read for its calls. Practices 1 and 2's checks
        # lend their verdicts, images and scenes
        check_files=BAYESIAN_CHECK_FILES + ("test_practice3.py",),
        expected=(),
        packages=("numpy", "opencv-python-headless", "matplotlib", "tqdm", "pytest"),
        render="practice3_render",
        judge="course_kit.judging_practice3"),
    4: Practice(
        number=4,
        modules=FRAMEWORK_MODULES + (WORKBENCH, GAUSSIAN_PROCESS),
        steps={
            "4.1": "Assignment 4.1: classic Monte Carlo with importance sampling (the "
                   "workbench's MC IS and the integrator)",
            "4.2": "Assignment 4.2: Bayesian Monte Carlo with importance sampling (the "
                   "workbench's BMC IS and the integrator)",
        },
        check_files=BAYESIAN_CHECK_FILES + ("test_practice4.py",),
        expected=(),
        packages=("numpy", "opencv-python-headless", "matplotlib", "tqdm", "pytest"),
        render="practice3_render",
        judge="course_kit.judging_practice3"),
}


def practice(number):
    """The Practice of that number; ValueError saying which there are otherwise."""
    try:
        return PRACTICES[int(number)]
    except (KeyError, ValueError, TypeError):
        raise ValueError(f"there is no practice {number!r} in the kit; it has practices "
                         + ", ".join(str(n) for n in PRACTICES)) from None


def all_steps():
    """Every graded step of every practice, in order."""
    return [step for one in PRACTICES.values() for step in one.steps]
