"""benchmark.py: the measurement protocol and a quick run of the documented command."""
from benchmark import time_renders
from helpers import REPO, run_python


class RecordingIntegrator:
    """Stands in for an integrator: records the worker count of every render() call."""

    def __init__(self):
        self.calls = []

    def render(self, workers=None, samples_per_pixel=1, progress=True):
        self.calls.append(workers)


def test_worker_counts_take_turns_so_drift_slows_them_alike():
    integrator = RecordingIntegrator()
    medians = time_renders(lambda: integrator, [1, 2], repeats=3)
    assert integrator.calls == [1, 2, 1, 2, 1, 2]
    assert len(medians) == 2 and all(m >= 0 for m in medians)


def test_every_render_gets_an_integrator_of_its_own():
    made = []

    def make():
        made.append(RecordingIntegrator())
        return made[-1]

    time_renders(make, [1, 2], repeats=2)
    assert [integrator.calls for integrator in made] == [[1], [2], [1], [2]]


def test_quick_run_writes_the_speed_table_and_the_accuracy_plot(tmp_path):
    result = run_python([REPO / "benchmark.py", "--size", "12", "--repeats", "1",
                         "--accuracy-size", "8", "--samples", "1", "4",
                         "--reference-samples", "16", "--out", tmp_path], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    table = (tmp_path / "benchmark.md").read_text()
    for row in ("Figure 1 | Phong | Cornell box", "Figure 3 | Intersection",
                "StudentPhong | sphere scene", "StudentPhong | Cornell box"):
        assert row in table
    assert "Phong, Cornell box (Figure 1) | 4 |" in (tmp_path / "speed_accuracy.md").read_text()
    assert (tmp_path / "speed_accuracy.png").stat().st_size > 0
