"""The command line of the course kit: `python -m course_kit handout|grade|autograder|expected`.

    python -m course_kit handout DIR        writes the students' base code into DIR
    python -m course_kit grade SUBMISSIONS --out RESULTS [--jobs N] [--force] [--config F]
                                            [--isolation MODE]
    python -m course_kit autograder ZIP     writes Gradescope's autograder zip [--config F]
    (handout, grade and autograder take --practice N: 1, the default, to 4)
    python -m course_kit expected           remakes the checks' expected images, on
                                            purpose only (course_kit/checks/expected/)

docs/course-kit.md is the teaching assistants' guide.
"""
import argparse
import sys

from course_kit import handout, sandbox
from course_kit.practices import PRACTICES


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="python -m course_kit", description="The course kit of Practices 1 to 4: the "
        "students' handout and the grader. See docs/course-kit.md.")
    commands = parser.add_subparsers(dest="command", required=True)
    handout_command = commands.add_parser("handout", help="write the students' base code into DIR")
    handout_command.add_argument("directory", metavar="DIR", help="a new or empty folder")
    add_practice(handout_command)
    grade = commands.add_parser("grade", help="grade every submission in a folder")
    grade.add_argument("submissions", metavar="SUBMISSIONS",
                       help="a folder of submissions, each a folder or a .zip")
    grade.add_argument("--out", required=True, metavar="RESULTS",
                       help="where grades.csv and a folder per submission go")
    grade.add_argument("--jobs", type=int, default=None,
                       help="submissions graded at once (default: one per core)")
    grade.add_argument("--force", action="store_true",
                       help="grade again the submissions already graded")
    grade.add_argument("--config", default=None, metavar="FILE",
                       help="points and limits (default: course_kit/grading.toml)")
    sandbox.add_argument(grade)
    add_practice(grade)
    autograder_command = commands.add_parser("autograder",
                                             help="write Gradescope's autograder zip")
    autograder_command.add_argument("zip", metavar="ZIP", help="the zip file to write")
    autograder_command.add_argument("--config", default=None, metavar="FILE",
                            help="points, limits and visibilities (default: "
                            "course_kit/grading.toml)")
    add_practice(autograder_command)
    commands.add_parser("expected", help="remake course_kit/checks/expected/practice1.npz "
                        "from the finished framework (only when its images change on purpose)")
    return parser.parse_args(argv)


def add_practice(command):
    command.add_argument("--practice", type=int, choices=sorted(PRACTICES), default=1,
                         help="the practice (default: 1)")


def main(argv=None):
    args = parse_args(argv)
    if args.command == "handout":
        try:
            print(f"Wrote the handout of Practice {args.practice} into "
                  f"{handout.write_handout(args.directory, args.practice)}")
        except (handout.MarkerError, FileExistsError) as error:
            sys.exit(f"course_kit handout: {error}")
    elif args.command == "grade":
        from course_kit import grader
        return grader.main(args)
    elif args.command == "autograder":
        from course_kit import autograder
        try:
            print(f"Wrote {autograder.write_zip(args.zip, args.config, args.practice)}: "
                  "upload it as "
                  "the autograder of a Gradescope assignment (docs/course-kit.md)")
        except (ValueError, OSError) as error:
            sys.exit(f"course_kit autograder: {error}")
    else:
        # the references load the finished framework: only this command needs it
        from course_kit import references
        print(f"Wrote {references.write_expected(handout.EXPECTED)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
