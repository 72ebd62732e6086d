"""Your checks of Practice 4: one test per check, named after its assignment step.

    python -m pytest                 all of them
    python -m pytest -k 4_2          Assignment 4.2 only

Each assignment has a check of the workbench's method (your practice4_methods(): MC IS
samples from the cosine; BMC IS has p = cos and models f = cos^3 alone; a workbench written
as the course's script, with no function to call, is read for the course's calls), and
one of the renderer's integrator. Assignment 4.1's renders a white furnace with classic Monte Carlo and cosine
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


def test_assignment_4_1_workbench_mc_is():
    passes("workbench_mc_is")


def test_assignment_4_2_workbench_bmc_is():
    passes("workbench_bmc_is")
