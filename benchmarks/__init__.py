"""PyRT's benchmarks: how fast it renders (benchmarks.speed, against the flat loop of
benchmarks.flat_loop) and how fast its error falls with more samples per pixel
(benchmarks.accuracy). Run them as modules from the repository's folder:

    python -m benchmarks.speed
    python -m benchmarks.accuracy
"""
