"""Your checks of Practice 4: one test per check, named after its assignment step.

    python -m pytest                 all of them
    python -m pytest -k 4_2          Assignment 4.2 only

Assignment 4.1's check renders a white furnace with classic Monte Carlo and cosine
sampling (CMCIntegrator(n, filename_, pdf=CosinePDF(1)), or your CMCISIntegrator), where
every term of the estimate is the same: the answer is exact. 4.2's renders it with your
BMCISIntegrator given a GP of the kit (p = cos, known weights). practice3_checks.py says
how; a failing test names the mistake when it recognises it and writes your image and the
expected one into out/checks/.
"""
import pytest

from practice3_checks import run_check


def passes(name):
    check = run_check(name)
    if not check.passed:
        pytest.fail(check.report(), pytrace=False)


def test_assignment_4_1_importance_sampling_furnace():
    passes("cmcis_furnace")


def test_assignment_4_2_bmc_importance_sampling_furnace():
    passes("bmcis_furnace")


def test_optional_4_1_and_4_2_workbench_methods():
    """The workbench's MC IS and BMC IS (practice4_methods): checked, not graded."""
    passes("workbench4")
