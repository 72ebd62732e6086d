"""The isolation of the steps' processes: which one the grader uses, and what it takes
(bubblewrap's command line, the user of a step, the folders handed to it).

Three modes; the grader takes the strongest that works here, or the one asked for:
- "bubblewrap": each step server (course_kit/isolation.py) runs inside bwrap (Debian and
  Ubuntu package bubblewrap) with no network, its own process, IPC and host-name
  namespaces, and a file system that shows only the system's folders and Python's,
  read-only, an empty /tmp, and its cell read-write: the folder where the grader makes the
  working copy of the submission it grades, one at a time. The other submissions, the
  results and the rest of the machine are not there. What a step leaves running is
  killed when it ends, and its processes are limited in number (below).
- "unprivileged user": where bubblewrap cannot run and the grader runs as root (inside
  Gradescope's container, where namespaces are usually not allowed), each step's
  process runs as a user of its own (a number that no account uses), which may write only
  its working copy, cannot read the grader's folders, and may have MAX_PROCESSES
  processes; what it leaves running is killed when the step ends.
- "process": only what course_kit/isolation.py does by itself: limits of time, memory and
  output, and Python's audit hook.
Under bubblewrap as root the steps run as a user of their own as well; without root,
bubblewrap maps the grader's user into the sandbox, and the limit on processes counts
from the processes that user already has.

Each mode has a limit, said where it is chosen (limit_of): the unprivileged user may read
what all may read, a copy of the finished framework included; in process isolation the
students' code runs as the grader's user. The variable COURSE_KIT_NO_UNPRIVILEGED_USER=1
makes the grader act as where no unprivileged user can run (CI's run of a machine that
cannot sandbox at all).
"""
import fcntl
import functools
import os
import shutil
import stat
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import course_kit.isolation

MODES = ("bubblewrap", "unprivileged user", "process")
# The steps' users when the grader runs as root: numbers from FIRST_USER on, which no
# account of a usual system has, each held by one step server at a time (a lock file in
# LOCKS), so that graders running at once never share one
FIRST_USER = 2_100_000_000
USERS = 4096
LOCKS = "/tmp"
MAX_PROCESSES = 64  # processes and threads a step may have, itself included
# The system's folders that the sandbox shows, read-only
SYSTEM_FOLDERS = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")
NAMESPACES = ("--unshare-net", "--unshare-pid", "--unshare-ipc", "--unshare-uts",
              "--unshare-cgroup-try")
PROBE_SECONDS = 60  # at most, for a trial run of bwrap or of Python as another user
NO_UNPRIVILEGED_USER = "COURSE_KIT_NO_UNPRIVILEGED_USER"  # set: no step runs as another user
INSTALL_BUBBLEWRAP = "apt-get install bubblewrap"
ANOTHER_PYTHON = "a Python outside a private home, such as /usr/bin/python3"
PROCESS_LIMIT = ("in process isolation the students' code runs as the grader's user: it "
                 "can read and change whatever the grader can (the finished framework, the "
                 "expected data, the results)")


class IsolationUnavailable(ValueError):
    """An isolation asked for that cannot run here, with the reason."""


@dataclass(frozen=True)
class Isolation:
    """The mode the grader isolates the steps with, and why no stronger one."""

    mode: str
    why: str = ""

    def describe(self):
        return self.mode + (f" ({self.why})" if self.why else "")


def _as_root():
    return hasattr(os, "geteuid") and os.geteuid() == 0


def bubblewrap_command(cell, root=None):
    """bwrap's command line (to be followed by the server's) for a server whose working
    copies lie in the folder cell; root: whether the grader runs as root (default: ask)."""
    root = _as_root() if root is None else root
    command = ["bwrap", "--die-with-parent", "--new-session", *NAMESPACES]
    if root:  # no user namespace: the server makes its steps another user, and kills them
        command += ["--cap-drop", "ALL", "--cap-add", "CAP_SETUID", "--cap-add",
                    "CAP_SETGID", "--cap-add", "CAP_KILL"]
    else:
        command += ["--unshare-user"]
    # /tmp first: the folders bound after it may lie in it
    command += ["--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--tmpfs", "/tmp"]
    for folder in SYSTEM_FOLDERS:
        if os.path.islink(folder):  # /bin -> usr/bin on systems with a merged /usr
            command += ["--symlink", os.readlink(folder), folder]
        elif os.path.isdir(folder):
            command += ["--ro-bind", folder, folder]
    python = [os.path.realpath(sys.prefix), os.path.realpath(sys.base_prefix),
              os.path.dirname(os.path.realpath(sys.executable))]
    python = sorted({path for path in python if not any(
        Path(path).is_relative_to(other) for other in python + list(SYSTEM_FOLDERS)
        if other != path)})  # each once: those in a folder already shown go with it
    # of the kit, only the server and the code its steps run besides the student's
    kit = [str(Path(course_kit.isolation.__file__).resolve())] + [
        str(path) for path in course_kit.isolation.STEP_MODULES]
    made = {"/", "/tmp", *SYSTEM_FOLDERS}
    for path, option in [(folder, "--ro-bind") for folder in python + kit] + [
            (str(cell), "--bind")]:
        # the folders on the way, which bwrap would make readable by root only
        for parent in reversed(Path(path).parents):
            if str(parent) not in made:
                made.add(str(parent))
                command += ["--perms", "0755", "--dir", str(parent)]
        command += [option, path, path]
    command += ["--chdir", str(cell)]
    return command


def _runs(command, **options):
    """Whether command runs and ends with exit code 0."""
    try:
        return subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True,
                              timeout=PROBE_SECONDS, **options).returncode == 0
    except (OSError, subprocess.SubprocessError):
        return False


@functools.lru_cache(maxsize=None)  # asked once per grader's process
def bubblewrap_runs():
    """Whether bwrap runs here with the sandbox's options: Python inside it, once."""
    if shutil.which("bwrap") is None or not sys.platform.startswith("linux"):
        return False
    with tempfile.TemporaryDirectory(prefix="pyrt-probe-") as cell:
        return _runs(bubblewrap_command(cell) + [sys.executable, "-I", "-c", "pass"])


@functools.lru_cache(maxsize=None)
def other_user_runs_python():
    """Whether a step's user could run this Python and its packages (as root, on Linux,
    whose prctl and /proc the steps' users need)."""
    return _as_root() and sys.platform.startswith("linux") and _runs(
        [sys.executable, "-I", "-c", "import numpy"], user=FIRST_USER, group=FIRST_USER,
        extra_groups=[], cwd="/")


def why_no_bubblewrap():
    """Why bubblewrap cannot isolate the steps here, with what to do about it, or None when
    it can."""
    if not sys.platform.startswith("linux"):
        return "bubblewrap runs on Linux only"
    if shutil.which("bwrap") is None:
        return f"bwrap is not installed ({INSTALL_BUBBLEWRAP})"
    if not bubblewrap_runs():
        return "bwrap is installed but cannot make its sandbox here (namespaces not allowed)"
    return None


def why_no_unprivileged_user():
    """Why the steps cannot run as an unprivileged user here, with what to do about it, or
    None when they can."""
    if os.environ.get(NO_UNPRIVILEGED_USER):
        return f"switched off ({NO_UNPRIVILEGED_USER} is set)"
    if not sys.platform.startswith("linux"):
        return "the unprivileged user's isolation runs on Linux only"
    if not _as_root():
        return "the grader does not run as root"
    if other_user_runs_python():
        return None
    python = os.path.realpath(sys.executable)
    private = private_folder(Path(python).parent)
    if private is not None:
        return (f"this Python ({python}) lies under {private}, which other users cannot "
                f"enter: grade with {ANOTHER_PYTHON}")
    return (f"another user cannot run this Python ({python}) with numpy: grade with "
            f"{ANOTHER_PYTHON}")


def private_folder(path):
    """The outermost folder of path (itself included) that other users may not enter (no
    execute bit for others), or None."""
    for folder in [*reversed(Path(path).parents), Path(path)]:
        try:
            if not folder.stat().st_mode & stat.S_IXOTH:
                return folder
        except OSError:
            return folder
    return None


def choose(requested=None):
    """The Isolation to grade with: requested (one of MODES), or None for the strongest
    that runs here. Raises IsolationUnavailable when the one requested cannot run."""
    if requested is not None and requested not in MODES:
        raise IsolationUnavailable(f"unknown isolation {requested!r}; the isolations are "
                                   + ", ".join(MODES))
    if requested in (None, "bubblewrap"):
        why = why_no_bubblewrap()
        if why is None:
            return Isolation("bubblewrap")
        if requested:
            raise IsolationUnavailable(f"the isolation bubblewrap cannot run: {why}")
    else:
        why = "asked for"
    if requested in (None, "unprivileged user"):
        cannot = why_no_unprivileged_user()
        if cannot is None:
            return Isolation("unprivileged user", why)
        if requested:
            raise IsolationUnavailable(f"the isolation unprivileged user cannot run: {cannot}")
        why += f"; no unprivileged user: {cannot}"
    return Isolation("process", why)


def cannot_sandbox(isolation):
    """One line for a teaching assistant whose machine gives the students' code no sandbox
    (isolation chose process, not asked for): what is missing and how to get it; None
    when isolation is a sandbox or process isolation was asked for."""
    if isolation.mode != "process" or isolation.why == "asked for":
        return None
    return f"this machine cannot sandbox the students' code: {isolation.why}"


def limit_of(isolation):
    """What isolation does not keep from the students' code, in one line (None for
    bubblewrap's)."""
    if isolation.mode == "process":
        return PROCESS_LIMIT
    if isolation.mode == "unprivileged user":
        return ("in the unprivileged user's isolation any copy of the finished framework "
                "that all users may read is in the students' reach (the grader's own is "
                "checked; bubblewrap hides them all): keep your checkouts private "
                "(chmod 700, docs/course-kit.md)")
    return None


def readable_by_steps(paths):
    """Those of paths (files, or folders to look into) that a step's user could read, as
    root finds by asking the system as that user (the shell's test, which any user may
    run): what the unprivileged user's isolation must not leave readable."""
    probe = 'for p; do if [ -r "$p" ] || { [ -d "$p" ] && [ -x "$p" ]; }; then echo "$p"; fi; done'
    ran = subprocess.run(["/bin/sh", "-c", probe, "sh", *map(str, paths)],
                         user=FIRST_USER, group=FIRST_USER, extra_groups=[], cwd="/",
                         capture_output=True, text=True, timeout=PROBE_SECONDS)
    return ran.stdout.splitlines()


def check_unreadable(paths):
    """Raises IsolationUnavailable naming the first of paths that a step's user could
    read (see readable_by_steps)."""
    readable = readable_by_steps(paths)
    if readable:
        raise IsolationUnavailable(
            f"the isolation unprivileged user cannot keep {readable[0]} from the students' "
            "code: make the grader's folders readable by their owner only (chmod 700)")


def _tasks_of(uid):
    """The number of processes and threads of the user uid, from /proc."""
    count = 0
    for entry in os.scandir("/proc"):
        try:
            if entry.name.isdigit() and entry.stat().st_uid == uid:
                count += len(os.listdir(entry.path + "/task"))
        except OSError:  # a process that has just ended
            pass
    return count


_held = {}  # user number -> the descriptor of the lock file that holds it for this process


def _take_user():
    """A user number for one step server's steps that no one else uses: no process has
    it, and no other server holds it (see FIRST_USER); close_confinement gives it back."""
    for user in range(FIRST_USER, FIRST_USER + USERS):
        if user in _held:
            continue
        lock = _lock_user(user)
        if lock is None:
            continue
        if _tasks_of(user) == 0:
            _held[user] = lock
            return user
        _release_user(user, lock)
    raise RuntimeError(f"no free user number for the steps among {USERS} from {FIRST_USER}")


def _lock_path(user):
    return os.path.join(LOCKS, f"pyrt-step-user-{user}.lock")


def _lock_user(user):
    """The descriptor of user's lock file, locked by this process, or None when another
    holds it. The file goes when it is given back (_release_user), so a lock is held only
    while the file locked is the one at the path: one given back meanwhile is not."""
    path = _lock_path(user)
    # O_NOFOLLOW: a link put in the shared folder leads the grader nowhere
    lock = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        if os.stat(path, follow_symlinks=False).st_ino == os.fstat(lock).st_ino:
            return lock
    except OSError:  # held by another, or removed by the one that held it
        pass
    os.close(lock)
    return None


def _release_user(user, lock):
    """Gives back user's lock, removing its file, so that grading leaves /tmp as it was."""
    try:
        os.unlink(_lock_path(user))
    except OSError:
        pass
    os.close(lock)


def confinement(isolation):
    """The course_kit.isolation.Confinement of a new step server under isolation. Its cell, if
    it has one, and its user are its own until close_confinement."""
    Confinement = course_kit.isolation.Confinement
    if isolation.mode == "process":
        return Confinement()
    user = _take_user() if _as_root() else None
    processes = MAX_PROCESSES if user is not None else _tasks_of(os.getuid()) + MAX_PROCESSES
    if isolation.mode == "unprivileged user":
        return Confinement(user=user, processes=processes, sweep=True)
    cell = tempfile.mkdtemp(prefix="pyrt-cell-")
    os.chmod(cell, 0o711)  # the steps' user passes through to its working copy
    return Confinement(tuple(bubblewrap_command(cell)), {"MPLCONFIGDIR": "/tmp"}, user,
                       processes, True, cell)


def close_confinement(confinement):
    """Removes what confinement made (its cell) and gives back its user."""
    if confinement.cell is not None:
        shutil.rmtree(confinement.cell, ignore_errors=True)
    if confinement.user in _held:
        _release_user(confinement.user, _held.pop(confinement.user))


def hand_over(scratch, workdir, user):
    """Lets the step's user (None: the grader's own) into scratch, the submission's
    folder, and write its working copy workdir, but neither change its checks (tests/)
    nor move what the grader put there: the working copy is the grader's, writable by all
    but sticky, and its out/ folder the user's."""
    if user is None:
        return
    os.chmod(scratch, 0o711)
    os.chmod(workdir, 0o1777)
    for folder, _, names in os.walk(Path(workdir) / "out"):
        os.chown(folder, user, user)
        for name in names:
            os.chown(os.path.join(folder, name), user, user)


def add_argument(parser):
    """Adds the option --isolation to an argparse parser."""
    parser.add_argument("--isolation", choices=MODES, default=None,
                        help="how to isolate each step's process (default: the strongest "
                        "that runs here; see docs/course-kit.md)")
