"""The grader's judge of Practice 2, in the grader's own process, which never imports a
student's code: Practice 1's trust boundary (course_kit/judging.py), with Practice 2's
checks.

For each step the step server runs the student's code in a process of its own on the
inputs of a Trial, drawn at grading time (practice2_scenes.draw_inputs: the sample sets of
the estimate, the seed of the workbench's curve and of the renders' draws, the scenes'
places, sizes and colours); that process computes and hands back data only (estimates, a
curve, images: course_kit/handback.py), and here the data is judged against the closed
forms of the draw by the students' own rules (practice2_checks.py, on data alone). The
statistical checks of 2.3 hold for any seed: it makes the kit's own tests repeat
themselves, and, drawn at grading time, nothing a submission can foresee.
"""
import sys

import numpy as np

import course_kit.handout
from course_kit.practices import PRACTICES
from course_kit.judging import DataTrial, data_trial_drawer, judge_data_step

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice2_checks as checks  # noqa: E402  (found through the line above)
import practice2_render as render  # noqa: E402
import practice2_scenes as scenes  # noqa: E402

RENDER = PRACTICES[2].render  # the step process's render module
DRAWN_SIZES = tuple(range(scenes.SIZE - 4, scenes.SIZE + 5))


Trial = DataTrial
drawn_trial = data_trial_drawer(scenes.draw_inputs, DRAWN_SIZES)


def draw_record(draw):
    """What the grader's record keeps of a draw: all of it but the sample sets' values."""
    return {"size": draw.size, "n_samples": draw.n_samples, "seed": draw.seed,
            "sample_sets": [len(s.values) for s in draw.sample_sets],
            "furnace": draw.furnace._asdict(), "emitter": draw.emitter._asdict()}


def expected_arrays(name, draw):
    """{array key: (dtype, shape)} that the check `name` may hand back at draw."""
    float64 = np.dtype(np.float64)
    if name == "estimate":
        return {"estimates": (float64, (len(draw.sample_sets),))}
    if name == "curve":
        return {"curve": (float64, (len(scenes.CURVE_NS),))}
    return {"image": (float64, (draw.size, draw.size, 3))}


def rendered_from(name, arrays, texts):
    """A Rendered made of what course_kit.handback read."""
    return render.Rendered(name, arrays, texts["error"], texts["first_color"],
                           texts["not_bool"])


def judge_step(step, trial, server, workdir, scratch, limits):
    """(the step's checks as dicts, the refusals, the limits not set, why there is no
    result or "", what the step printed) of step on the working copy workdir."""
    return judge_data_step(checks, RENDER, rendered_from, expected_arrays, step, trial,
                           server, workdir, scratch, limits)
