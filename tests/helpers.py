"""Helpers shared by test_integrators.py, test_app.py and test_references.py."""
import os
import subprocess
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

REPO = Path(__file__).resolve().parent.parent
APP = REPO / "AppRenderer.py"
# matplotlib stores a PNG channel v as floor(255 v) / 255: up to one 8-bit step below v
# (plus float32 rounding when it is read back).
PNG_TOLERANCE = 1.0 / 255.0 + 1e-6
SUBPROCESS_TIMEOUT = 300  # seconds; only there so that a hung child cannot hang the suite


def render_image(integrator, scene, **render_options):
    """Attaches scene to integrator, renders it without a progress bar and returns the
    linear image it saved (the .npy file)."""
    integrator.add_scene(scene)
    integrator.render(progress=False, **render_options)
    return np.load(integrator.get_filename() + ".npy")


def read_png(path):
    """The RGB channels of a PNG as floats in [0, 1], as matplotlib reads them."""
    return plt.imread(str(path))[:, :, :3].astype(float)


def headless_env():
    """The environment for a child Python: no display, matplotlib's Agg backend, and the
    repository on the import path."""
    env = {name: value for name, value in os.environ.items() if name != "DISPLAY"}
    env["MPLBACKEND"] = "Agg"
    env["PYTHONPATH"] = os.pathsep.join(
        [str(REPO)] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    return env


def run_python(args, cwd):
    """Runs `python *args` headless in cwd and returns the CompletedProcess (text output)."""
    return subprocess.run([sys.executable, *map(str, args)], cwd=cwd, env=headless_env(),
                          capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT)
