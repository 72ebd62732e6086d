"""Your checks of Practice 3: one test per check, named after its assignment step.

    python -m pytest                 all of them
    python -m pytest -k 3_1          Assignment 3.1 only

Assignment 3.1's checks call your GaussianProcess.py on given positions, weights and
values; 3.2's, your workbench's compute_estimate_bmc (a workbench written as the
course's script, with no function to call, is read for the course's calls); 3.3's and 3.3.2's render small scenes
with your BayesianMonteCarloIntegrator, given GPs of the kit whose weights are known, so
that each assignment is judged on its own (practice3_checks.py says how). A failing test
says what differs, names the mistake when it recognises it, and writes your image and the
expected one into out/checks/.
"""
import pytest

from practice3_checks import run_check


def passes(name):
    check = run_check(name)
    if not check.passed:
        pytest.fail(check.report(), pytrace=False)


def test_assignment_3_1_compute_inv_Q():
    passes("inv_q")


def test_assignment_3_1_compute_z():
    passes("z")


def test_assignment_3_1_compute_integral_BMC():
    passes("bmc_sum")


def test_assignment_3_2_workbench_estimate():
    passes("workbench")


def test_assignment_3_3_white_furnace():
    passes("bmc_furnace")


def test_assignment_3_3_emitting_walls():
    passes("bmc_box")


def test_assignment_3_3_2_rotation_and_pool():
    passes("bmc_pool")
