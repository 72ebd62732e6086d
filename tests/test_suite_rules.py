"""The rules the test files keep, so that a red test means what it says: every match=
pattern is a regular expression written as one or quoted text escaped with re.escape,
helpers are defined once (in helpers.py), no test file is over MAX_TEST_FILE_LINES, and
tools/hunt_flaky.py, which hunts for tests that fail by chance, reports every test that
failed with the seed of its run."""
import ast
import io
import multiprocessing
import re
import tokenize

import tools.hunt_flaky as hunt_flaky
from helpers import REPO, run_python

TESTS = REPO / "tests"
TEST_FILES = sorted(TESTS.glob("test_*.py"))
METACHARACTERS = set(".^$*+?{}[]|()\\")
# A test file checks one concern of one module; one that grows past this is split by concern
MAX_TEST_FILE_LINES = 800
FSTRING_START = getattr(tokenize, "FSTRING_START", None)
FSTRING_END = getattr(tokenize, "FSTRING_END", None)


def match_arguments(path):
    """(line, source) of the match= argument of every call in the file."""
    source = path.read_text(encoding="utf-8")
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call):
            for keyword in node.keywords:
                if keyword.arg == "match":
                    yield keyword.value.lineno, ast.get_source_segment(source, keyword.value)


def is_re_escape(node):
    return (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
            and node.func.attr == "escape" and isinstance(node.func.value, ast.Name)
            and node.func.value.id == "re")


def loose_literals(argument):
    """The string literals of the source of a match= argument, outside re.escape(...), that
    hold a metacharacter of regular expressions but are not raw strings: quoted text that
    the pattern matches more loosely than it reads, or a regular expression that does not
    say it is one."""
    source = "(" + argument + ")"
    escaped = [ast.get_source_segment(source, node)
               for node in ast.walk(ast.parse(source, mode="eval")) if is_re_escape(node)]
    for call in escaped:
        source = source.replace(call, "None", 1)
    lines = source.splitlines(keepends=True)
    found = []
    tokens = tokenize.generate_tokens(io.StringIO(source).readline)
    for token in tokens:
        if token.type == tokenize.STRING:
            literal = token.string
        elif token.type == FSTRING_START:  # Python 3.12: an f-string comes in parts
            depth, end = 1, token
            while depth:
                end = next(tokens)
                depth += (end.type == FSTRING_START) - (end.type == FSTRING_END)
            literal = _text_between(lines, token.start, end.end)
        else:
            continue
        prefix = re.match(r"[A-Za-z]*", literal)[0].lower()
        text = literal[len(prefix):]
        if "f" in prefix:  # fields {...} are filled in, not part of the pattern's text
            text = re.sub(r"\{[^{}]*\}", "", text)
        if "r" not in prefix and set(text.strip("\"'")) & METACHARACTERS:
            found.append(literal)
    return found


def _text_between(lines, start, end):
    """The source text from (row, column) start to end, rows counted from 1."""
    (first, column), (last, end_column) = start, end
    if first == last:
        return lines[first - 1][column:end_column]
    return (lines[first - 1][column:] + "".join(lines[first:last - 1])
            + lines[last - 1][:end_column])


def test_match_patterns_are_raw_regular_expressions_or_escaped_text():
    # "Scene.save_image: ..." as a pattern also matches "Scene_save_image: ...": quoted
    # text goes through re.escape, and a real regular expression is a raw string r"..."
    loose = [f"{path.name}:{line}: {literal}"
             for path in TEST_FILES for line, argument in match_arguments(path)
             for literal in loose_literals(argument)]
    assert loose == []


def test_the_rule_on_match_patterns_tells_loose_ones_from_the_others():
    loose = loose_literals
    assert loose('"Scene.save_image"') == ['"Scene.save_image"']
    assert loose('"^Camera: width"') == ['"^Camera: width"']
    assert loose('"first "\n    "(second)"') == ['"(second)"']
    assert loose('f"^{name} must"') == ['f"^{name} must"']
    assert loose('r"^Scene\\.save_image$"') == []
    assert loose('rf"^{name} must"') == []
    assert loose('f"{name} must"') == []
    assert loose('"^" + re.escape("Scene.save_image (all)")') == ['"^"']
    assert loose('re.escape("Scene.save_image (all)")') == []
    assert loose('"zero vector"') == []


def helper_definitions(path):
    """{source of the body, with the arguments renamed by position: name} for the
    functions of a test module that are not tests."""
    definitions = {}
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("test_"):
            arguments = [argument.arg for argument in node.args.args]
            body = node.body
            if ast.get_docstring(node) is not None:
                body = body[1:]
            text = "\n".join(ast.unparse(statement) for statement in body)
            for position, name in enumerate(arguments):
                text = re.sub(rf"\b{name}\b", f"argument{position}", text)
            definitions[text] = node.name
    return definitions


def test_each_helper_is_defined_in_one_test_module_only():
    # a helper that several modules need lives in helpers.py, so that a fix reaches them all
    seen = {}
    for path in sorted(TESTS.glob("*.py")):
        for body, name in helper_definitions(path).items():
            seen.setdefault(body, []).append(f"{path.name}:{name}")
    assert [places for places in seen.values() if len(places) > 1] == []


def test_no_test_file_is_over_the_line_limit():
    lengths = {path.name: len(path.read_text(encoding="utf-8").splitlines())
               for path in sorted(TESTS.glob("*.py"))}
    assert {name: lines for name, lines in lengths.items()
            if lines > MAX_TEST_FILE_LINES} == {}


SAMPLE_TESTS = '''
def test_that_passes():
    assert 1 + 1 == 2


def test_that_fails():
    assert 1 + 1 == 3
'''


def test_hunt_flaky_reports_each_failed_test_with_the_seeds_of_its_runs(tmp_path):
    tests = tmp_path / "test_sample.py"
    tests.write_text(SAMPLE_TESTS)
    # --rootdir: test ids relative to tmp_path, wherever the repository lies
    report = tmp_path / "report.txt"
    result = run_python([REPO / "tools" / "hunt_flaky.py", "--runs", 2, "--load", 0, "--seed",
                         7, "--report", report, f"--rootdir={tmp_path}", tests], cwd=tmp_path)
    output = result.stdout + result.stderr  # what a failure shows: stderr says why
    assert result.returncode == 1, output
    lines = result.stdout.splitlines()
    assert lines and lines[0].startswith("2 run(s) from seed 7, 0 busy process(es) on "), (
        output)
    for run, seed in [(1, 7), (2, 8)]:
        assert any(line.startswith(f"run {run}/2, seed {seed}, --rootdir={tmp_path} {tests}: "
                                   "1 failed, 1 passed ") for line in lines), output
    assert lines.count("    FAILED test_sample.py::test_that_fails (call)") == 2
    assert "2 run(s) in random order with 0 busy process(es): 0 green, 2 red" in lines
    assert "  test_sample.py::test_that_fails: failed in 2 of 2 run(s), seed(s) 7, 8" in lines
    assert "test_that_passes" not in result.stdout
    assert lines[-1] == ("    PYRT_HYPOTHESIS_PROFILE=hunt python -m pytest -q -p no:cacheprovider "
                         "-p no:randomly "
                         "--random-order-bucket=global --random-order-seed=7 "
                         f"--hypothesis-seed=7 --rootdir={tmp_path} {tests}")
    assert report.read_text(encoding="utf-8") == result.stdout  # where git does not look


def test_hunt_flaky_exits_0_when_every_run_is_green_and_stops_its_busy_processes(
        monkeypatch, capsys, tmp_path):
    runs = []

    def green_run(seed, pytest_args, folder):
        runs.append((seed, pytest_args))
        return [], "5 passed in 0.01s", 0.01

    monkeypatch.setattr(hunt_flaky, "run_pytest", green_run)
    assert hunt_flaky.main(["--runs", "2", "--load", "1", "--seed", "3", "--report",
                            str(tmp_path / "report.txt"), "-k", "x"]) == 0
    assert runs == [(3, ["-k", "x"]), (4, ["-k", "x"])]
    out = capsys.readouterr().out
    assert "2 run(s) in random order with 1 busy process(es): 2 green, 0 red" in out
    assert "FAILED" not in out and "failed in" not in out
    assert multiprocessing.active_children() == []
