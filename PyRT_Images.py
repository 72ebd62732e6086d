"""PyRT image files: the course's tonemapper, and the PNG, .npy and .hdr of a render.

Scene.save_image writes three files per image: the PNG to look at (the linear image
mapped for display by the course's tonemapper, or clipped to [0, 1]), the raw linear image
(.npy) and a Radiance HDR file (.hdr). Every file appears whole or not at all
(write_atomically).
"""
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from math import isfinite
from pathlib import Path

import cv2
import matplotlib.pyplot as plt
import numpy as np


def tonemap_image(image, gamma=2.5):
    """The course's display mapping, OpenCV's default tonemapper cv2.createTonemap(gamma):
    the whole image (all pixels and channels) is mapped linearly so that its minimum becomes
    0 and its maximum 1, raised to the power 1/gamma and clipped to [0, 1].

    OpenCV's tonemapper itself computes it, on the image in single precision as the course
    hands it over, so that each value rounds as in the course's PNGs. Unlike OpenCV it
    ignores non-finite values when it looks for the minimum and maximum, so one NaN from a
    buggy integrator does not turn the whole picture black; NaN and -inf pixels are shown
    as the minimum, +inf as the maximum. OpenCV's rounding can make the image's exact
    minimum slightly negative, whose power is NaN (black in the course's PNGs): it is shown
    as 0, the minimum. An image beyond single precision's range gets the same mapping in
    double precision."""
    lo, hi = float(image.min()), float(image.max())  # NaN if any pixel is NaN
    out = image
    if not (isfinite(lo) and isfinite(hi)):
        finite = np.isfinite(image)
        if not finite.any():
            return np.zeros(image.shape, np.float32)
        lo, hi = float(image[finite].min()), float(image[finite].max())
        out = np.nan_to_num(image, nan=lo, posinf=hi, neginf=lo)
    if -SINGLE_MAX <= lo and hi <= SINGLE_MAX:
        display = _opencv_tonemap(out.astype(np.float32), gamma)
        return np.clip(np.nan_to_num(display, nan=0.0, copy=False), 0.0, 1.0, out=display)
    if hi - lo > np.finfo(float).eps:  # OpenCV leaves a flat image as it is
        out = np.subtract(out, lo)
        out /= hi - lo
    display = np.clip(out, 0.0, 1.0, out=np.empty(image.shape, np.float32))
    return np.power(display, np.float32(1.0 / gamma), out=display)


SINGLE_MAX = float(np.finfo(np.float32).max)


def _opencv_tonemap(image, gamma):
    """cv2.createTonemap(gamma).process(image) of a single-precision image, without the
    warning that OpenCV prints on its first call (about how a future version may compute
    expressions on images of several channels, which is no concern here)."""
    level = cv2.utils.logging.getLogLevel()
    cv2.utils.logging.setLogLevel(cv2.utils.logging.LOG_LEVEL_ERROR)
    try:
        return cv2.createTonemap(gamma).process(image)
    finally:
        cv2.utils.logging.setLogLevel(level)


def display_image(image, tonemap=True):
    """The image as its PNG shows it, values in [0, 1]: tonemapped, or (tonemap False, as
    Figure 2 is shown) the linear values clipped, NaN as 0."""
    return tonemap_image(image) if tonemap else np.clip(np.nan_to_num(image), 0.0, 1.0)


def write_image_files(image, full_filename, tonemap=True):
    """Writes full_filename + '.png' (display_image), '.npy' (the linear float image) and
    '.hdr' (Radiance HDR, float32, in OpenCV's BGR order); creates the folder if needed."""
    base = Path(full_filename)
    base.parent.mkdir(parents=True, exist_ok=True)
    # The linear files are written on a second thread meanwhile: the encoders, numpy's
    # arithmetic and the writes all run without holding Python's global lock.
    with ThreadPoolExecutor(1) as pool:
        linear = pool.submit(_write_linear_files, image, base)
        display = display_image(image, tonemap)
        # 8 bits as matplotlib makes them from floats, floor(255 v), written with zlib's
        # fastest level: a slightly larger file, written sooner.
        pixels = np.multiply(display, 255.0, out=display).astype(np.uint8)
        write_atomically(_with_suffix(base, ".png"), lambda f: plt.imsave(
            f, pixels, format="png", pil_kwargs={"compress_level": 1}))
        linear.result()


def _write_linear_files(image, base):
    """Writes the .npy and .hdr files of the linear image."""
    # Single precision, as the HDR format holds it: larger values are its largest.
    largest = np.finfo(np.float32).max
    ok, hdr = cv2.imencode(".hdr", np.clip(image[:, :, ::-1], -largest, largest).astype(
        np.float32))
    if not ok:
        raise RuntimeError("Scene.save_image: OpenCV could not encode the HDR image")
    write_atomically(_with_suffix(base, ".hdr"), lambda f: f.write(hdr))
    write_atomically(_with_suffix(base, ".npy"), lambda f: np.save(f, image))


def _with_suffix(base, suffix):
    return base.parent / (base.name + suffix)


def write_atomically(path, write):
    """Calls write(file) on a temporary file that then replaces path, so that path is
    always either the previous file or the new one, never half written. The temporary
    file is created like any other file (readable by others, as the umask allows), where
    tempfile.mkstemp would make it private to its owner."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{threading.get_ident()}.tmp")
    try:
        with open(tmp, "wb") as f:
            write(f)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
