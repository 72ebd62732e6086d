"""The course kit of Practices 1 to 4, for teaching assistants: the students' handout made
from this framework, the grader of what they hand in and Gradescope's autograder.

    practices    what each practice hands out, grades and checks (practices.py)
    handout      the handout: the course modules with the solutions cut out (handout.py)
    grader       grades a folder of submissions (grader.py), each step's student code
                 in a process of its own (isolation.py, the step server) inside a sandbox
                 (sandbox.py), handing back data only (handback.py), judged in the
                 grader's process (judging.py; Practice 2's: judging_practice2.py; Practices
                 3 and 4's: judging_practice3.py); and
                 writes the reports (feedback.py)
    autograder   Gradescope's zip and its run (autograder.py)
    references   the checks' expected images, stored and made at grading time
                 (references.py, with the course's own arithmetic: arithmetic.py)
    checks/      the students' checks, shipped in the handout's tests/
    grading.toml points, limits and visibilities

The kit sits on top of everything: it imports PyRT and the course modules, never the other
way. Its command line is `python -m course_kit` (__main__.py); docs/course-kit.md is the
guide.
"""
