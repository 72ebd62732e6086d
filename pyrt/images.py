"""PyRT image files: the course's tonemapper, and the PNG, .npy and .hdr of a render.

Scene.save_image writes three files per image: the PNG to look at (the linear image
mapped for display by the course's tonemapper, or clipped to [0, 1]), the raw linear image
(.npy) and a Radiance HDR file (.hdr). Every file appears whole or not at all
(write_atomically), the .npy first: it needs numpy alone, so a render is never lost to a
broken OpenCV (opencv_problem).
"""
import os
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from math import isfinite
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

# What repairs OpenCV. With opencv-python and opencv-python-headless both installed (the
# course asks for the first, PyRT's requirements for the second), uninstalling either
# removes files they share: cv2 is then gone, or an empty folder without what PyRT uses.
OPENCV_FIX = ("as happens when one of opencv-python and opencv-python-headless is "
              "uninstalled while both are installed. Fix it with\n    pip install "
              "--force-reinstall opencv-python-headless\n(or opencv-python, which also has "
              "OpenCV's windows)")
try:
    import cv2
except ImportError as error:
    raise ImportError(f"PyRT needs OpenCV, and import cv2 fails ({error}), {OPENCV_FIX}"
                      ) from None


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


# What PyRT takes from OpenCV (cv2.utils for its log level)
OPENCV_NAMES = ("createTonemap", "imencode", "imread", "cvtColor", "utils")


def opencv_problem():
    """What is wrong with the installed OpenCV, with the command that fixes it, or None when
    cv2 has everything PyRT uses."""
    missing = [name for name in OPENCV_NAMES if not hasattr(cv2, name)]
    if not missing:
        return None
    where = getattr(cv2, "__file__", None) or ", ".join(getattr(cv2, "__path__", []))
    return (f"OpenCV is broken: the cv2 package ({where}) has no {', '.join(missing)}, "
            + OPENCV_FIX)


def native_path(filename):
    """filename (a str) as a name of this system's files; says so when it changes it. A
    name written with Windows's separators ('.\\out\\rendered_image', as the 2025-26
    handout has it) means the same folders on Linux and macOS, where a backslash is no
    separator but part of a file's name."""
    name = str(filename)
    if os.sep == "/" and "\\" in name:
        native = name.replace("\\", "/")
        print(f"PyRT: {name!r} is written with Windows's separators; on this system it is "
              f"{native!r}", file=sys.stderr)
        return native
    return name


def write_image_files(image, full_filename, tonemap=True):
    """Writes full_filename + '.npy' (the linear float image), '.png' (display_image) and
    '.hdr' (Radiance HDR, float32, in OpenCV's BGR order); creates the folder if needed.
    Returns the path of the PNG."""
    base = Path(native_path(full_filename))
    base.parent.mkdir(parents=True, exist_ok=True)
    npy = _with_suffix(base, ".npy")
    write_atomically(npy, lambda f: np.save(f, image))
    try:
        problem = opencv_problem()
        if problem:
            raise RuntimeError(f"Scene.save_image: {problem}")
        # The HDR file is written on a second thread meanwhile: the encoders, numpy's
        # arithmetic and the writes all run without holding Python's global lock.
        with ThreadPoolExecutor(1) as pool:
            hdr = pool.submit(_write_hdr_file, image, base)
            display = display_image(image, tonemap)
            # 8 bits as matplotlib makes them from floats, floor(255 v), written with
            # zlib's fastest level: a slightly larger file, written sooner.
            pixels = np.multiply(display, 255.0, out=display).astype(np.uint8)
            png = _with_suffix(base, ".png")
            write_atomically(png, lambda f: plt.imsave(
                f, pixels, format="png", pil_kwargs={"compress_level": 1}))
            hdr.result()
    except Exception:
        print(f"PyRT: the image is saved in {npy.absolute()} (np.load reads it), but the "
              "PNG or HDR file could not be written:", file=sys.stderr)
        raise
    return png


def _write_hdr_file(image, base):
    """Writes the .hdr file of the linear image."""
    # Single precision, as the HDR format holds it: larger values are its largest.
    largest = np.finfo(np.float32).max
    ok, hdr = cv2.imencode(".hdr", np.clip(image[:, :, ::-1], -largest, largest).astype(
        np.float32))
    if not ok:
        raise RuntimeError("Scene.save_image: OpenCV could not encode the HDR image")
    write_atomically(_with_suffix(base, ".hdr"), lambda f: f.write(hdr))


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
