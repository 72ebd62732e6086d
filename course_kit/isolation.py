"""One step of the students' checks run on one submission's working copy, in a process of
its own, for the grader (course_kit/grader.py).

The processes are forked by a step server, `python -I -B course_kit/isolation.py [--core N]`
(the other options: see Confinement), that has loaded what every course module loads
(numpy, OpenCV, matplotlib) once, so that a step's process starts at once; each is still
new, and shares nothing with the others. A server given a core runs on that core alone,
and so do its steps' processes: the grader gives each server a core of its own, and PyRT's
own render() (the finished framework graded as a submission) then stays in its process
instead of starting workers. The server reads one request per line on its standard input
(JSON: workdir, task, result, log, limits), forks the step's process, waits for it at most
the step's wall-clock limit (killing it then), and answers one line: {"code": its exit
code, negative for a signal, "timed_out": true or false}.

Before the student's code is imported, the step's process
- sends what it prints into the log file, outside the working copy,
- lowers its limits of processor time, address space and file size (what it prints
  included: a process that prints without end is killed), and writes no core file,
- keeps on its import path only the working copy and Python's own libraries,
- installs an audit hook that refuses, and notes, every write outside the working copy or
  into a tests/ folder in it, every start of another process, and every opening of the
  framework's answers of Practice 3 (FRAMEWORK_ANSWERS: its GaussianProcess.py, pyrt/gp_*).
Then it runs its task with the student's code: "collect" renders and answers for the
checks named (with the practice's render module the task names: checks/practice1_render.py
or checks/practice2_render.py, loaded by the server before any step), "story" tells a
pixel's history. It hands back data only, no verdict, into the result file
outside the working copy (course_kit/handback.py): the grader reads it with limits and
judges it in its own process (course_kit/judging.py), so nothing the student's code does
in its process changes how it is judged. A process that ends before that (os._exit, a
crash, a limit) or with another exit code than 0 hands back nothing, and the grader says
why.

This keeps a submission from disturbing the others by accident. It is no security
sandbox: code that sets out to escape can (see docs/course-kit.md). A Confinement adds
what course_kit/sandbox.py chooses: the server run inside bubblewrap, the steps run as a user
of their own with a limit on their processes, and whatever a step leaves running killed
when it ends.
"""
import argparse
import importlib.util
import json
import os
import signal
import subprocess
import sys
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

try:
    import resource
except ImportError:  # Windows: no process limits, and no fork either (see unsupported)
    resource = None

# What every course module imports, loaded once by the step server
PRELOADED = ("numpy", "cv2", "matplotlib.pyplot")
# What a step runs besides the student's code, loaded by the step server from the kit, in
# this order (each may import those before it): what the student's code makes, as data
# (each practice's render module), and how it goes back
KIT = Path(__file__).resolve().parent
STEP_MODULES = tuple(KIT / "checks" / name for name in (
    "practice1_render.py", "practice2_scenes.py", "practice2_render.py",
    "practice3_scenes.py", "practice3_render.py")) + (
    KIT / "handback.py",)
DEFAULT_RENDER = "practice1_render"  # the render module of a task that names none
# The step server's environment: a few of the grader's variables, no window, and one
# thread for the numerical libraries, as each submission has processes of its own
KEPT_VARIABLES = ("PATH", "HOME", "LANG", "LC_ALL", "TMPDIR")
ENVIRONMENT = {"MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
               "MKL_NUM_THREADS": "1"}
MAX_REFUSALS = 20  # refusals noted by a step, the first ones
OUTPUT_READ = 64 * 1024  # bytes of the end of a step's output that the grader reads
POLL_SECONDS = 0.01  # how often the server looks whether a step's process has ended
# Audit events that write, with the number of paths they name first, and that start a
# process
WRITING_EVENTS = {"os.remove": 1, "os.rmdir": 1, "os.mkdir": 1, "os.rename": 2,
                  "os.link": 2, "os.symlink": 2, "os.truncate": 1, "os.chmod": 1,
                  "os.chown": 1, "os.utime": 1, "shutil.rmtree": 1}
PROCESS_EVENTS = {"subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn",
                  "os.fork", "os.forkpty"}
# The framework's answers of Practice 3 (its GaussianProcess.py and PyRT's exact z, Q and
# weights beneath it), which a step may not even read: (folder, file name prefix) pairs
FRAMEWORK_ANSWERS = ((KIT.parent, "GaussianProcess."), (KIT.parent / "__pycache__",
                     "GaussianProcess."), (KIT.parent / "pyrt", "gp_"),
                     (KIT.parent / "pyrt" / "__pycache__", "gp_"))
READ_ANSWERS = "read the framework's answers"  # how a refusal to read them begins
WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_APPEND | os.O_CREAT | os.O_TRUNC
PR_SET_CHILD_SUBREAPER, PR_SET_NO_NEW_PRIVS = 36, 38  # Linux's prctl options


# ------------------------------------------------------------------------------------------
# In the step's process
# ------------------------------------------------------------------------------------------
def set_limits(limits):
    """Lowers this process's limits: processor time, address space, the size of any file
    it writes (its output included), no core files. Returns a line for each limit that
    the system refused (macOS often refuses one of the address space): the step runs
    without it, and the grader tells the teaching assistant."""
    cpu = int(limits["cpu_seconds"])
    memory = int(limits["memory_mib"]) * 1024 * 1024
    output = int(limits["output_kib"]) * 1024
    refused = []
    for setting, name, values in (
            (f"cpu_seconds = {cpu}", "RLIMIT_CPU", (cpu, cpu + 1)),
            (f"memory_mib = {limits['memory_mib']}", "RLIMIT_AS", (memory, memory)),
            (f"output_kib = {limits['output_kib']}", "RLIMIT_FSIZE", (output, output)),
            ("no core files", "RLIMIT_CORE", (0, 0))):
        try:
            resource.setrlimit(getattr(resource, name), values)
        except (ValueError, OSError) as error:
            refused.append(f"{setting} ({name}: {type(error).__name__}: {error})")
    return refused


def guard(workdir, refused):
    """An audit hook that refuses, with a PermissionError, writes to paths outside workdir
    or inside its tests/ (the checks and their expected images) and the start of
    processes, and notes each refusal in the list `refused`."""
    root = os.path.realpath(workdir)
    checks = os.path.join(root, "tests")

    def forbidden(path):
        """Why writing path is refused, or None when it is not."""
        if isinstance(path, int) or path is None:  # a file descriptor, already open
            return None
        name = os.path.realpath(os.fsdecode(path))
        if name == os.devnull:
            return None
        if os.path.commonpath([name, root]) != root:
            return f"wrote outside its working copy: {name}"
        if os.path.commonpath([name, checks]) == checks:
            return f"wrote into the checks: {name}"
        return None

    def note(refusal):
        """Notes a refusal once (code that repeats one, pixel after pixel, says it once),
        and at most MAX_REFUSALS of them."""
        if refusal not in refused and len(refused) < MAX_REFUSALS:
            refused.append(refusal)

    def framework_answer(path):
        """Whether path is one of FRAMEWORK_ANSWERS."""
        if isinstance(path, int) or path is None:
            return False
        name = os.path.realpath(os.fsdecode(path))
        return any(os.path.dirname(name) == os.path.realpath(folder)
                   and os.path.basename(name).startswith(prefix)
                   for folder, prefix in FRAMEWORK_ANSWERS)

    def hook(event, args):
        if event == "open" and framework_answer(args[0]):
            note(f"{READ_ANSWERS}: {os.fsdecode(args[0])} (open)")
            raise PermissionError("grading: refused, the framework's answers are not "
                                  "readable while grading")
        if event == "open":
            paths = [args[0]] if args[2] & WRITE_FLAGS else []
        elif event in WRITING_EVENTS:
            paths = list(args[:WRITING_EVENTS[event]])
        elif event in PROCESS_EVENTS:
            note(f"started a process ({event})")
            raise PermissionError(f"grading: {event} is not allowed while grading")
        else:
            return
        for path in paths:
            why = forbidden(path)
            if why is not None:
                note(f"{why} ({event})")
                raise PermissionError(f"grading: refused, the code {why}")

    return hook


def _python_paths():
    """The entries of sys.path that hold Python's own libraries and installed packages."""
    prefixes = {os.path.realpath(sys.prefix), os.path.realpath(sys.base_prefix)}
    return [path for path in sys.path if path and any(
        os.path.realpath(path).startswith(prefix + os.sep) for prefix in prefixes)]


def _prctl(option, value):
    """Linux's prctl(option, value), which Python's os module does not offer."""
    import ctypes
    if ctypes.CDLL(None, use_errno=True).prctl(option, value, 0, 0, 0) != 0:
        raise OSError(ctypes.get_errno(), f"prctl({option}, {value}) failed")


def become(user, processes):
    """Makes this process user's (a number, with no groups, and no way back to more
    privileges: a set-user-ID program keeps it), when it is not None, and limits the
    processes (threads included) of its user to `processes`, when not None."""
    if user is not None:
        _prctl(PR_SET_NO_NEW_PRIVS, 1)
        os.setgroups([])
        os.setgid(user)
        os.setuid(user)
    if processes is not None:
        resource.setrlimit(resource.RLIMIT_NPROC, (processes, processes))


def step_process(workdir, task, result_path, log_path, limits, user=None, processes=None):
    """The body of a step's process: see the module's docstring; user and processes as
    become takes them, once its log and result files are open."""
    log = os.open(log_path, os.O_WRONLY | os.O_APPEND)
    os.dup2(log, 1)
    os.dup2(log, 2)
    signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # Python ignores it: a write would fail
    result = os.open(result_path, os.O_WRONLY)
    become(user, processes)
    limits_not_set = set_limits(limits)
    os.chdir(workdir)
    sys.path[:] = [workdir] + _python_paths()
    refused = []
    sys.addaudithook(guard(workdir, refused))
    render = sys.modules[task.get("render", DEFAULT_RENDER)]
    handback = sys.modules["handback"]
    draw = render.draw_from_json(task["draw"])
    out = os.path.join(workdir, "out", "checks")
    if task["kind"] == "story":
        rendered, extra = [], {"story": render.pixel_history(task["name"], draw,
                                                             *task["pixel"])}
    else:
        rendered, extra = [render.collect(name, draw, out, task["traced"])
                           for name in task["names"]], {}
    extra.update(refused=refused, limits_not_set=limits_not_set)
    with os.fdopen(result, "wb") as file:
        handback.write(file, rendered, extra)


# ------------------------------------------------------------------------------------------
# The step server
# ------------------------------------------------------------------------------------------
def serve(core=None, user=None, processes=None, sweep=False):
    """The step server's loop: see the module's docstring. user, processes: as become
    takes them, for each step's process; sweep: whether to kill what a step leaves
    running."""
    if core is not None and hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {core})
    if sweep:  # what a step leaves running becomes this server's, and is waited for
        _prctl(PR_SET_CHILD_SUBREAPER, 1)
    for name in PRELOADED:
        __import__(name)
    for path in STEP_MODULES:  # the steps' own code, loaded before they lose the kit
        spec = importlib.util.spec_from_file_location(path.stem, path)
        sys.modules[path.stem] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys.modules[path.stem])
    for line in sys.stdin:
        request = json.loads(line)
        pid = os.fork()
        if pid == 0:
            _child(request, user, processes)
        code, timed_out = _wait(pid, request["limits"]["wall_seconds"])
        if sweep:
            _sweep(user)
        print(json.dumps({"code": code, "timed_out": timed_out}), flush=True)


def _sweep(user):
    """Kills every process that the step left running, and waits until they are gone,
    so that they count no more against the limit on processes: those of its user, when
    it has one of its own, else every process of the server's namespace but the server."""
    if user is None:
        try:
            os.kill(-1, signal.SIGKILL)  # spares this process and the namespace's first
        except ProcessLookupError:  # nothing was left running
            pass
    elif os.fork() == 0:  # as the step's user, whose processes only it may signal
        try:
            become(user, None)
            if os.getuid() == user != 0:
                os.kill(-1, signal.SIGKILL)
        finally:
            os._exit(0)
    while True:  # the helper, and the killed, which are this server's as it is subreaper
        try:
            os.waitpid(-1, 0)
        except ChildProcessError:
            return


def _child(request, user, processes):
    """The forked step's process: runs step_process and ends, never returning."""
    code = 1
    try:
        os.dup2(os.open(os.devnull, os.O_RDONLY), 0)
        step_process(request["workdir"], request["task"], request["result"],
                     request["log"], request["limits"], user, processes)
        code = 0
    except SystemExit as error:
        code = error.code if isinstance(error.code, int) else 1
    except BaseException:
        traceback.print_exc()
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(code)


def _wait(pid, seconds):
    """(exit code, timed out) of the process pid, killed after seconds."""
    deadline = time.monotonic() + seconds
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            return os.waitstatus_to_exitcode(status), False
        if time.monotonic() > deadline:
            os.kill(pid, signal.SIGKILL)
            _, status = os.waitpid(pid, 0)
            return os.waitstatus_to_exitcode(status), True
        time.sleep(POLL_SECONDS)


# ------------------------------------------------------------------------------------------
# In the grader
# ------------------------------------------------------------------------------------------
def unsupported():
    """Why the grader cannot run on this system, in one sentence, or None when it can."""
    if resource is None or not hasattr(os, "fork"):
        return ("the grader runs on Linux, macOS, WSL or Gradescope: it needs process "
                "limits (the resource module) and os.fork, which this system lacks (the "
                "handout and its checks run anywhere)")
    return None


# What a step server runs: this file (the tests run one that changes the system first)
SERVER_SCRIPT = Path(__file__).resolve()


@dataclass(frozen=True)
class Confinement:
    """What confines a step server and its steps besides this module's guard (chosen by
    course_kit/sandbox.py): the command line the server runs inside, with its variables; the
    user its steps run as and the limit on that user's processes (None: the grader's
    user, no limit); whether what a step leaves running is killed; the folder in which the
    working copies must lie (None: anywhere)."""

    wrapper: tuple = ()
    variables: dict = field(default_factory=dict)
    user: Optional[int] = None
    processes: Optional[int] = None
    sweep: bool = False
    cell: Optional[str] = None


class StepServer:
    """A step server process (see the module's docstring), used by one thread at a time;
    core: the core it runs on, or None for any; confinement: a Confinement."""

    def __init__(self, core=None, confinement=Confinement()):
        environment = {name: os.environ[name] for name in KEPT_VARIABLES
                       if name in os.environ}
        environment.update(ENVIRONMENT, **confinement.variables)
        options = [] if core is None else ["--core", str(core)]
        if confinement.user is not None:
            options += ["--user", str(confinement.user)]
        if confinement.processes is not None:
            options += ["--processes", str(confinement.processes)]
        options += ["--sweep"] if confinement.sweep else []
        self.confinement = confinement
        self.process = subprocess.Popen(
            [*confinement.wrapper, sys.executable, "-I", "-B", str(SERVER_SCRIPT), *options],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=environment, text=True)

    def close(self):
        try:
            self.process.stdin.close()
        except BrokenPipeError:  # the server has ended already: nothing is left to say
            pass
        self.process.wait()

    def run_step(self, workdir, scratch, label, task, limits):
        """Runs task (see step_process) on workdir in a process of its own, its log and
        result in scratch, named after label; returns (the path of its result, or None;
        why there is none; what it printed). The result is as the student's code left
        it: course_kit/handback.py reads it."""
        result_path = Path(scratch) / f"{label}.result"
        log_path = Path(scratch) / f"{label}.log"
        result_path.write_bytes(b"")
        log_path.write_bytes(b"")
        request = {"workdir": str(workdir), "task": task, "result": str(result_path),
                   "log": str(log_path), "limits": limits}
        try:
            self.process.stdin.write(json.dumps(request) + "\n")
            self.process.stdin.flush()
            answer = self.process.stdout.readline()
        except BrokenPipeError:
            answer = ""
        if not answer:
            raise RuntimeError("the grader's step server ended unexpectedly")
        answer = json.loads(answer)
        output = log_path.read_bytes()[-OUTPUT_READ:].decode("utf-8", "replace")
        if answer["timed_out"]:
            return None, (f"did not finish within {limits['wall_seconds']} s, the time "
                          "limit of a step: the code hangs or is far too slow"), output
        if answer["code"] == 0 and result_path.stat().st_size:
            return result_path, None, output
        return None, _why_no_result(answer["code"], limits, output), output


def _why_no_result(code, limits, output):
    if code in (-signal.SIGXCPU, -signal.SIGKILL):
        return (f"used more than {limits['cpu_seconds']} s of processor time, the limit of "
                "a step: the code hangs or is far too slow")
    if code == -signal.SIGXFSZ:
        return (f"printed more than {limits['output_kib']} KiB, the limit of a step's "
                "output (or wrote a file that large): the code prints without end")
    if "MemoryError" in output:
        return f"ran out of memory: a step may use {limits['memory_mib']} MiB"
    if code < 0:
        return f"the process was killed by {signal.Signals(-code).name}"
    if code == 0:
        return "the process ended before the checks were done, handing back nothing"
    return (f"the process ended (exit code {code}) before the checks were done: the code "
            "called os._exit, or ended the process some other way")


def cores():
    """The cores this process may run on, for the step servers (None where the system
    does not tell)."""
    if hasattr(os, "sched_getaffinity"):
        return sorted(os.sched_getaffinity(0))
    return [None]


def main(argv=None):
    """The step server's command line: serve with the options StepServer gives it."""
    parser = argparse.ArgumentParser(description="The step server (see the docstring).")
    parser.add_argument("--core", type=int)
    parser.add_argument("--user", type=int)
    parser.add_argument("--processes", type=int)
    parser.add_argument("--sweep", action="store_true")
    arguments = parser.parse_args(argv)
    serve(arguments.core, arguments.user, arguments.processes, arguments.sweep)


if __name__ == "__main__":
    main()
