"""What the grader writes from its records (course_kit/grader.py): per submission the student's
feedback page, Gradescope's results.json and the record itself, and grades.csv for all.

The record of a submission (grading.json) holds its name, the fingerprint of what was
graded, where each course module came from, the problems met reading it, and per step:
step, title, points, max_points, passed, reason, output, and checks, each with name,
title, passed, reason, note, message, error and images (kind -> path in the folder).
"""
import csv
import html
import json
from pathlib import Path

RECORD = "grading.json"
FEEDBACK = "feedback.html"
GRADESCOPE = "results.json"
IMAGE_LABELS = {"render": "yours", "expected": "expected", "difference": "difference"}

STYLE = """
body { font-family: sans-serif; max-width: 60em; margin: 2em auto; padding: 0 1em;
       color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 2em; }
.passed { color: #17692b; } .failed { color: #a31919; }
.note { background: #eef4fb; border-left: 3px solid #3a6ea5; padding: 0.4em 0.6em; }
section.step { border-top: 1px solid #ccc; padding-bottom: 1em; }
details { margin: 1em 0; }
pre { background: #f4f4f4; padding: 0.6em; overflow-x: auto; white-space: pre-wrap; }
figure { display: inline-block; margin: 0 1em 1em 0; text-align: center; }
img { width: 240px; height: 240px; image-rendering: pixelated; border: 1px solid #999; }
"""


def write_submission_reports(record, folder, visibility=None):
    """Writes grading.json, feedback.html and results.json of one submission into folder;
    visibility: Gradescope's visibilities (see gradescope_results)."""
    folder = Path(folder)
    (folder / RECORD).write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
    (folder / FEEDBACK).write_text(feedback_html(record), encoding="utf-8")
    (folder / GRADESCOPE).write_text(
        json.dumps(gradescope_results(record, visibility), indent=2) + "\n", encoding="utf-8")


def _verdict(passed):
    return "passed" if passed else "failed"


def _number(value):
    """Points as they read best: 25 rather than 25.0."""
    return int(value) if float(value).is_integer() else value


def feedback_html(record):
    """The student's page: per step the verdict, the reason, and per check its message,
    the error with the student's own traceback lines, and the images beside the expected
    ones with their difference."""
    e = html.escape
    practice = f"Practice {record.get('practice', 1)}"
    parts = [f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
             f"<title>{practice}: {e(record['submission'])}</title><style>{STYLE}</style>"
             f"</head><body>\n<h1>{practice}: {e(record['submission'])}, "
             f"{_number(record['total'])} of {_number(record['max_total'])} points</h1>"]
    parts.append(f"<p>{e(graded_from(record))}</p>")
    parts += [f"<p class=\"failed\">{e(problem)}</p>" for problem in record["problems"]]
    for step in record["steps"]:
        verdict = _verdict(step["passed"])
        parts.append(f"<section class=\"step\"><h2 class=\"{verdict}\">{e(step['title'])}: "
                     f"{verdict}, {_number(step['points'])} of "
                     f"{_number(step['max_points'])} points</h2>")
        if step_note(step):
            parts.append(f"<p>{e(step_note(step))}</p>")
        for check in step["checks"]:
            parts.append(_check_html(check))
        if not step["passed"] and step["output"].strip():
            parts.append("<details><summary>What your code printed (the end)</summary>"
                         f"<pre>{e(step['output'])}</pre></details>")
        parts.append("</section>")
    parts.append("</body></html>\n")
    return "\n".join(parts)


def graded_from(record):
    """The sentence that says which of the student's files were graded."""
    taken = [name for name, origin in record["files"].items() if origin == "submission"]
    return ("Graded from your " + (", ".join(taken) or "no file")
            + "; every other file is the handout's.")


def check_reason(check):
    """The reason of a step that failed first at this check, as course_kit.grader words it."""
    return f"{check['title']}: {check['reason']}"


def step_note(step):
    """The reason a step failed when no check's message tells it (the step's process
    ended without a result, or the guard refused something), else ""."""
    failed = [check for check in step["checks"] if not check["passed"]]
    if failed and step["reason"] == check_reason(failed[0]):
        return ""
    return step["reason"]


def _check_html(check):
    e = html.escape
    verdict = "right" if check["passed"] else "wrong"
    parts = [f"<h3 class=\"{_verdict(check['passed'])}\">{e(check['title'])}: {verdict}</h3>"]
    if not check["passed"]:
        parts.append(f"<pre>{e(check['message'])}</pre>")
    elif check.get("note"):
        parts.append(f"<p class=\"note\">Worth knowing: {e(check['note'])}.</p>")
    if check["error"]:
        parts.append(f"<p>The error, with the lines of your code it passed through:</p>"
                     f"<pre>{e(check['error'])}</pre>")
    for kind, path in check["images"].items():
        parts.append(f"<figure><img src=\"{e(path)}\" alt=\"{e(IMAGE_LABELS[kind])}\">"
                     f"<figcaption>{e(IMAGE_LABELS[kind])}</figcaption></figure>")
    if check.get("story"):
        parts.append(_stories_html(check))
    return "\n".join(parts)


def _stories_html(check):
    """The history of the first wrong pixel as the student's code tells it, beside the
    finished framework's history of the same pixel, told by the grader."""
    e = html.escape
    columns = [("Your code", check["story"]),
               ("The finished framework", check.get("framework_story", ""))]
    return ("<div style=\"display: flex; gap: 1em\">" + "".join(
        f"<div style=\"flex: 1; min-width: 0\"><p>{e(who)}:</p><pre>{e(story)}</pre></div>"
        for who, story in columns) + "</div>")


def gradescope_results(record, visibility=None):
    """The record in the format of Gradescope's autograder results (results.json): the
    total score, the grading's time, what was graded, and one test per step, numbered by
    its step, with its score, max_score, status and output (the checks' messages, the
    likely mistakes among them). visibility: {"visibility": ..., "stdout_visibility": ...},
    by default the tests visible and the grader's output hidden."""
    tests = []
    for step in record["steps"]:
        lines = [step_note(step)] if step_note(step) else []
        lines += [check["message"] + (f"\n{check['error']}" if check["error"] else "")
                  + (f"\n{check['story']}" if check.get("story") else "")
                  for check in step["checks"]]
        tests.append({"name": step["title"], "number": step["step"], "score": step["points"],
                      "max_score": step["max_points"], "status": _verdict(step["passed"]),
                      "output": "\n\n".join(lines)})
    shown = {"visibility": "visible", "stdout_visibility": "hidden", **(visibility or {})}
    return {"score": record["total"], "execution_time": record.get("seconds", 0),
            "output": "\n".join([graded_from(record)] + record["problems"]), **shown,
            "tests": tests}


def write_grades(records, path, reason_length):
    """grades.csv: a row per submission with the points of each step, the total and the
    reason of each failed step (cut to reason_length characters)."""
    steps = [step["step"] for step in records[0]["steps"]] if records else []
    with open(path, "w", newline="", encoding="utf-8") as out:
        writer = csv.writer(out)
        writer.writerow(["submission"] + steps + ["total"]
                        + [f"reason {step}" for step in steps])
        for record in records:
            reasons = [_cut(step["reason"], reason_length) for step in record["steps"]]
            writer.writerow([record["submission"]]
                            + [_number(step["points"]) for step in record["steps"]]
                            + [_number(record["total"])] + reasons)
    return Path(path)


def _cut(text, length):
    text = " ".join(text.split())
    return text if len(text) <= length else text[:length - 3] + "..."
