"""The grader's judge of Practices 3 and 4, in the grader's own process, which never
imports a student's code: Practice 1's trust boundary (course_kit/judging.py), with the
checks of practice3_checks.py.

For each step the step server runs the student's code in a process of its own on the
inputs of a Trial, drawn at grading time (practice3_scenes.draw_inputs: the positions and
noise of the GP's checks, the seed of the course's z estimate, the BMC sums' weights and
colours, the sample sets of the GPs handed to the integrators with the weights computed
here, the furnace's and the floor's places and colours). That process hands back data only
(Q^-1, z, sums, images, the rays of 3.3.2, the workbench's estimates and methods, or,
for a workbench written as the course's script, which of the course's calls its source
makes), judged here by the students' own rules.

One mistake costs one step: the integrators' steps (3.3, 3.3.2, 4.2) run with GPs of the
kit whose weights this process computed and handed in as data, never with the student's
GaussianProcess.py, whose mistakes cost 3.1 alone; 3.3.2 is judged on the rays cast and the
GPs used, not on the pixels' values, which are 3.3's; 4.1 needs only the classic Monte
Carlo integrator (Practice 2's) with cosine sampling. The framework's GaussianProcess.py
and PyRT's machinery of z (pyrt/gp_*.py) are not in the working copy.
"""
import sys

import numpy as np

import course_kit.handout
from course_kit.practices import PRACTICES
from course_kit.judging import DataTrial, data_trial_drawer, judge_data_step

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice3_checks as checks  # noqa: E402  (found through the line above)
import practice3_render as render  # noqa: E402
import practice3_scenes as scenes  # noqa: E402

RENDER = PRACTICES[3].render  # the step process's render module
DRAWN_SIZES = tuple(range(scenes.SIZE - 2, scenes.SIZE + 3))


Trial = DataTrial
drawn_trial = data_trial_drawer(scenes.draw_inputs, DRAWN_SIZES)


def draw_record(draw):
    """What the grader's record keeps of a draw."""
    return {"size": draw.size, "seed": draw.seed, "noise": draw.noise,
            "positions": [list(p) for p in draw.positions],
            "sums": [len(case.weights) for case in draw.sums],
            "pool": len(draw.pool), "n_samples": draw.n_samples,
            "furnace": draw.furnace._asdict(), "floor": draw.floor._asdict()}


def expected_arrays(name, draw):
    """{array key: (dtype, shape)} that the check `name` may hand back at draw."""
    float64 = np.dtype(np.float64)
    n = len(draw.positions)
    if name == "inv_q":
        return {"inv_q": (float64, (n, n))}
    if name == "z":
        return {"z_one": (float64, (n,)), "z_cos": (float64, (n,))}
    if name == "bmc_sum":
        return {"sums": (float64, (len(draw.sums), 3))}
    script = {"script": (float64, (len(render.SCRIPT_CALLS),))}
    if name == "workbench":
        return {"estimates": (float64, (len(draw.pool),)), **script}
    if name in render.WORKBENCH_CHECKS:
        n_directions = (len(draw.pool[0].positions),)
        return {**{key: (float64, n_directions) for key in ("pdf", "p", "f")}, **script}
    image = {"image": (float64, (draw.size, draw.size, 3))}
    if name == "bmc_pool":
        image.update(directions=(float64, (draw.size, draw.size, draw.n_samples, 3)),
                     chosen=(float64, (draw.size, draw.size)))
    return image


def rendered_from(name, arrays, texts):
    """A Rendered made of what course_kit.handback read."""
    return render.Rendered(name, arrays, texts["error"], texts["first_color"],
                           texts["not_bool"])


def judge_step(step, trial, server, workdir, scratch, limits):
    """(the step's checks as dicts, the refusals, the limits not set, why there is no
    result or "", what the step printed) of step on the working copy workdir."""
    return judge_data_step(checks, RENDER, rendered_from, expected_arrays, step, trial,
                           server, workdir, scratch, limits)
