"""The grader's judge: a step's checks decided in the grader's own process, which never
imports a student's code, from the data the step's process hands back.

For each step the step server (course_kit/isolation.py) runs the student's code in a
process of its own, confined as course_kit/sandbox.py says, on the inputs of a Trial (the
size and place of the scenes, the any_hit cases); that process renders and answers, and
hands back data only (course_kit/handback.py). Here the data is read with its limits and
judged against the trial's expected data by the rules of the students' own checks
(practice1_checks.py, run here on data alone). The process that ran the student's code
decides nothing and never sees the expected data or the answers. A wrong image's first
wrong pixel gets its story from a second, fresh run of the student's code (the "story"
task), beside the finished framework's story, which the trial tells.
"""
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Mapping, Tuple

import course_kit.handback
import course_kit.handout

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice1_checks as checks  # noqa: E402  (found through the line above)
import practice1_render as render  # noqa: E402


# The inputs drawn at grading time: the sizes of the images, and how far the course's
# scenes may move along each axis (their objects stay in view and keep their order).
# Only sizes above the published one. At the published size the Lazy image and the rays
# of render(), which depend on the size alone, would be the published arrays. Below it
# every pixel lies inside the published images, and the Lazy image, (x/size, y/size, 0),
# is the published one's corner times 40/size: the rule of a scaled image, which must
# admit a student's colours running to 255 where PyRT's run to 1, would admit a copy.
# Above it a copy leaves pixels with nothing to copy (tests/test_course_judging.py).
DRAWN_SIZES = tuple(range(render.SIZE + 1, render.SIZE + 9))
DRAWN_OFFSET = 0.15
ANY_HIT_SETS = 2  # the published six cases, twice, each around a sphere of its own


@dataclass(frozen=True)
class Trial:
    """What a grading asks of the student's code and what it expects: the Draw handed to
    the step's process, any_hit's cases with their right answers, the expected data of
    the draw (practice1_checks' form: a mapping), and the finished framework's story of a
    pixel, story(name, x, y)."""

    draw: render.Draw
    cases: Tuple
    data: Mapping
    story: Callable


def draw_inputs(random):
    """(the Draw, any_hit's cases with their right answers) drawn with random (a
    random.Random): the scenes at a size of DRAWN_SIZES, moved by up to DRAWN_OFFSET
    along each axis, and ANY_HIT_SETS sets of any_hit's cases, each around a sphere at a
    distance and in a direction of its own, shuffled."""
    size = random.choice(DRAWN_SIZES)
    offset = tuple(round(random.uniform(-DRAWN_OFFSET, DRAWN_OFFSET), 6) for _ in range(3))
    cases = []
    for _ in range(ANY_HIT_SETS):
        direction = _unit([random.gauss(0.0, 1.0) for _ in range(3)])
        across = _unit(_cross(direction, _unit([random.gauss(0.0, 1.0) for _ in range(3)])))
        cases += render.any_hit_cases(round(random.uniform(4.0, 9.0), 3), direction,
                                      tuple(3.0 * a for a in across))
    random.shuffle(cases)  # no answer follows from a case's place
    return render.Draw(size, offset, tuple(case for _, case, _ in cases)), tuple(cases)


def drawn_trial(random, folder):
    """A Trial drawn with random (see draw_inputs) at grading time, its expected data made
    now by the finished framework (course_kit/references.py), its renders in folder."""
    import course_kit.references  # loads the framework
    draw, cases = draw_inputs(random)

    def story(name, x, y):
        return course_kit.references.framework_story(name, x, y, draw)

    return Trial(draw, cases, course_kit.references.GradingData(draw, folder), story)


def draw_record(draw):
    """What the grader's record keeps of a draw: the size and the offset."""
    return {"size": draw.size, "offset": list(draw.offset)}


def _unit(v):
    length = sum(a * a for a in v) ** 0.5 or 1.0
    return tuple(a / length for a in v)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rendered_from(name, arrays, texts):
    """A practice1_render.Rendered made of what course_kit.handback read."""
    return render.Rendered(name, arrays, texts["error"], texts["first_color"],
                           texts["not_bool"])


class NoData(Exception):
    """A step's process that handed back no data to judge: why, and what it printed."""

    def __init__(self, why, output):
        super().__init__(why)
        self.why, self.output = why, output


def _collect(label, names, traced, trial, server, workdir, scratch, limits):
    """({name: Rendered}, the rest of meta.json, what it printed) of the checks `names`
    run by a step's process (with compute_color traced on its own when traced). Raises
    NoData."""
    task = {"kind": "collect", "names": list(names), "draw": trial.draw, "traced": traced}
    path, why, output = server.run_step(workdir, scratch, label, task, limits)
    if path is None:
        raise NoData(why, output)
    try:
        rendered, meta = course_kit.handback.read(path, names, trial.draw, rendered_from)
    except course_kit.handback.Malformed as error:
        raise NoData(f"refused: the step's process {error}", output) from None
    return {one.name: one for one in rendered}, meta, output


def judge_step(step, trial, server, workdir, scratch, limits):
    """(the step's checks as dicts, the refusals, the limits not set, why there is no
    result or "", what the step printed) of step on the working copy workdir."""
    names = checks.STEPS[step]
    asked = names + (("probe",) if step == "1.1" else ())  # a black Lazy image needs it
    run = (trial, server, workdir, scratch, limits)
    try:
        by_name, meta, output = _collect(step, asked, False, *run)
        judged = {name: _judge(by_name, name, trial, scratch) for name in names}
        # compute_color on its own, for a wrong image only: a mistake of render() counts
        # in the check of its rays, not in every image (practice1_checks.judge_rendered)
        again = [name for name, check in judged.items() if not check.passed
                 and checks.ray_traced(name) and by_name[name].arrays.get("image") is not None]
        if again:
            retraced, more, _ = _collect(f"{step}_traced", again, True, *run)
            by_name.update(retraced)
            meta["refused"] = meta.get("refused", []) + more.get("refused", [])
            judged.update((name, _judge(by_name, name, trial, scratch)) for name in again)
    except NoData as error:
        return [], [], [], error.why, error.output
    results = []
    for name in names:
        check = judged[name]
        framework_story = ""
        if check.story_pixel:
            framework_story = _tell_story(check, step, trial, server, workdir, scratch,
                                          limits)
        results.append(dict(check_record(check, step, Path(scratch) / "images"),
                            framework_story=framework_story))
    return results, meta.get("refused", []), meta.get("limits_not_set", []), "", output


def _judge(by_name, name, trial, scratch):
    """The Check of the Rendered by_name[name]."""
    return checks.judge_rendered(by_name[name], trial.data, trial.cases,
                                 Path(scratch) / "checks" / name, by_name.get("probe"))


def _tell_story(check, step, trial, server, workdir, scratch, limits):
    """Sets check.story from a fresh run of the student's code (nothing when that run
    fails: a story never changes a verdict); returns the finished framework's story of
    the same pixel, or "" when the student's is not told."""
    task = {"kind": "story", "name": check.name, "pixel": list(check.story_pixel),
            "draw": trial.draw}
    path, _, _ = server.run_step(workdir, scratch, f"{step}_{check.name}_story", task,
                                 limits)
    history = ""
    if path is not None:
        try:
            _, meta = course_kit.handback.read(path, (), trial.draw, rendered_from)
            history = meta.get("story", "")
        except course_kit.handback.Malformed:
            pass
    check.story = checks.story(check, trial.data[check.name], history)
    return trial.story(check.name, *check.story_pixel) if check.story else ""


@dataclass(frozen=True)
class DataTrial:
    """What a grading asks of the student's code in a practice whose checks judge data
    alone (Practices 2 to 4): the Draw handed to the step's process, drawn at grading time
    (what is expected follows from it)."""

    draw: object


def data_trial_drawer(draw_inputs, sizes):
    """The drawn_trial(random, folder=None) of a practice whose checks judge data alone: a
    DataTrial of draw_inputs(random, size), drawn with random (a random.Random) at grading
    time at a size of sizes; folder: unused (the closed forms need no renders)."""
    def drawn_trial(random, folder=None):
        return DataTrial(draw_inputs(random, random.choice(sizes)))
    return drawn_trial


def judge_data_step(checks, render_name, rendered_from, expected_arrays, step, trial,
                    server, workdir, scratch, limits):
    """judge_step of a practice whose checks judge data alone (Practices 2 to 4): the
    checks of step (checks.STEPS[step]) collected by the step's process with its render
    module render_name, read as expected_arrays(name, draw) says and made Rendered by
    rendered_from, judged by checks.judge_rendered against the trial's draw. Returns what
    judge_step returns; a check that hands back neither its arrays nor an error is
    refused."""
    names = checks.STEPS[step]
    task = {"kind": "collect", "names": list(names), "draw": trial.draw, "traced": False,
            "render": render_name}
    path, why, output = server.run_step(workdir, scratch, step, task, limits)
    try:
        if path is None:
            raise NoData(why, output)
        try:
            rendered, meta = course_kit.handback.read(path, names, trial.draw, rendered_from,
                                                      expected_arrays)
        except course_kit.handback.Malformed as error:
            raise NoData(f"refused: the step's process {error}", output) from None
    except NoData as error:
        return [], [], [], error.why, error.output
    results = []
    for one in rendered:
        missing = set(expected_arrays(one.name, trial.draw)) - set(one.arrays)
        if one.error is None and one.first_color is None and missing:
            check = checks.new_check(one.name).fail(
                "refused: the step's process handed back no " + ", ".join(sorted(missing)))
        else:
            check = checks.judge_rendered(one, trial.draw,
                                          Path(scratch) / "checks" / one.name)
        results.append(dict(check_record(check, step, Path(scratch) / "images"),
                            framework_story=""))
    return results, meta.get("refused", []), meta.get("limits_not_set", []), "", output


def check_record(check, step, images):
    """check as the grader's record keeps it, its PNGs copied into images/ as
    <step>_<check>_<kind>.png."""
    kept = {}
    for kind, path in check.images.items():
        target = images / f"{step}_{check.name}_{kind}.png"
        images.mkdir(exist_ok=True)
        shutil.copyfile(path, target)
        kept[kind] = f"images/{target.name}"
    return {"name": check.name, "title": check.title, "passed": check.passed,
            "reason": check.reason, "note": check.note, "message": check.message,
            "error": check.error, "images": kept, "story": check.story,
            "story_pixel": list(check.story_pixel)}
