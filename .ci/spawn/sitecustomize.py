"""Makes every Python process that finds this folder on PYTHONPATH start its processes
with spawn, as Windows and macOS do: .ci/run runs the whole suite so once, PyRT's worker
processes and every process the tests start included.

    PYTHONPATH="$PWD/.ci/spawn" python -m pytest -q     # from the repository's folder

A script that sets the method itself then needs set_start_method(..., force=True)."""
import multiprocessing

multiprocessing.set_start_method("spawn")
