"""What a step's process hands back to the grader: data only, in one file of bounded size.

The step's process (course_kit/isolation.py) runs the student's code and writes what it
made (practice1_render.Rendered: arrays and a few texts) with `write`: a zip holding one .npy file per array, "<check>/<array>.npy", and "meta.json", the texts.
The grader reads it with `read`, which trusts nothing in it: a file too large, a member
too large or not expected, an array that is not float64 (images) or int64 (any_hit's
answers) of the expected shape, an object array (numpy's allow_pickle=False refuses
it), JSON of another form or texts too long: each makes the file Malformed, and the step
fails with that reason. Nothing is unpickled and nothing of it is run. NaN and infinite
values are kept: they are data, and the judge finds them wrong.

This module is loaded by the step server by its path (it imports nothing of the kit).
"""
import io
import json
import zipfile

import numpy as np

META = "meta.json"
MAX_FILE_BYTES = 8 * 1024 * 1024
MAX_META_BYTES = 256 * 1024
MAX_TEXT = 16000  # characters of one text
NPY_HEADER = 4096  # bytes an .npy file may hold besides its values
TEXT_FIELDS = ("first_color", "not_bool")
ERROR_FIELDS = ("kind", "type", "text", "code", "file", "line", "traceback")


class Malformed(ValueError):
    """A step's file that is not what a step's process writes, with what is wrong."""


def write(path, rendered, extra):
    """Writes the Rendered of the checks `rendered` and the JSON-able dict extra (the
    refusals, the limits not set, a story) into path."""
    meta = {"checks": {}, **extra}
    # compressed: what a step hands back counts against the limit of its files' size
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as archive:
        for one in rendered:
            meta["checks"][one.name] = {"error": one.error, "first_color": one.first_color,
                                        "not_bool": one.not_bool}
            for key, array in one.arrays.items():
                buffer = io.BytesIO()
                np.save(buffer, np.asarray(array), allow_pickle=False)
                archive.writestr(f"{one.name}/{key}.npy", buffer.getvalue())
        archive.writestr(META, json.dumps(meta))


def expected_arrays(name, draw):
    """{array key: (dtype, shape or None for any length up to the cases' + 1)} that the
    check `name` may hand back at draw."""
    if name == "any_hit":
        return {"answers": (np.dtype(np.int64), None)}
    shape = (draw.size, draw.size, 3)
    return {"image": (np.dtype(np.float64), shape), "traced": (np.dtype(np.float64), shape)}


def read(path, names, draw, make_rendered, expected=expected_arrays):
    """(the checks' Rendered, made by make_rendered(name, arrays, texts), in the order of
    names; the rest of meta.json) from the file at path, written for the checks `names`
    at draw, whose arrays expected(name, draw) gives (Practice 1's by default). Raises
    Malformed when the file is not what a step's process writes."""
    try:
        if path.stat().st_size > MAX_FILE_BYTES:
            raise Malformed(f"handed back more than {MAX_FILE_BYTES} bytes")
        with zipfile.ZipFile(path) as archive:
            infos = {info.filename: info for info in archive.infolist()}
            meta = _meta(archive, infos, names)
            arrays = {name: {} for name in names}
            for member, info in infos.items():
                if member == META:
                    continue
                name, _, key = member.partition("/")
                arrays[name][key[:-len(".npy")]] = _array(archive, info, name, key, draw,
                                                          expected)
    except (zipfile.BadZipFile, OSError, EOFError, KeyError) as error:
        raise Malformed(f"handed back a file that is not the grader's format ({error})")
    rendered = [make_rendered(name, arrays[name], meta["checks"][name]) for name in names]
    return rendered, {key: value for key, value in meta.items() if key != "checks"}


def _meta(archive, infos, names):
    """meta.json of the archive, checked: {"checks": {name: texts}, and lists of texts}."""
    info = infos.get(META)
    if info is None or info.file_size > MAX_META_BYTES:
        raise Malformed("handed back no meta.json, or one too large")
    try:
        meta = json.loads(archive.read(info).decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        raise Malformed("handed back a meta.json that is not JSON") from None
    if not isinstance(meta, dict) or not isinstance(meta.get("checks"), dict) or sorted(
            meta["checks"]) != sorted(names):
        raise Malformed("handed back a meta.json without the checks asked for")
    for texts in meta["checks"].values():
        if not isinstance(texts, dict) or sorted(texts) != sorted(("error",) + TEXT_FIELDS):
            raise Malformed("handed back a check's texts of another form")
        for key in TEXT_FIELDS:
            _text(texts[key], key, optional=True)
        error = texts["error"]
        if error is not None:
            if not isinstance(error, dict) or not set(error) <= set(ERROR_FIELDS) or not {
                    "kind", "type", "text", "traceback"} <= set(error):
                raise Malformed("handed back an error of another form")
            for key, value in error.items():
                _text(value, key)
    for key in ("refused", "limits_not_set"):
        values = meta.get(key, [])
        if not isinstance(values, list) or len(values) > 100:
            raise Malformed(f"handed back a {key} of another form")
        for value in values:
            _text(value, key)
    _text(meta.get("story", ""), "story")
    return meta


def _text(value, what, optional=False):
    if (value is None and optional) or (isinstance(value, str) and len(value) <= MAX_TEXT):
        return
    raise Malformed(f"handed back a {what} that is no text of at most {MAX_TEXT} characters")


def _array(archive, info, name, key, draw, expected):
    """The array of the member info, checked against what the check `name` hands back."""
    if not key.endswith(".npy"):
        raise Malformed(f"handed back a file it should not: {info.filename!r}")
    allowed = expected(name, draw).get(key[:-len(".npy")])
    if allowed is None:
        raise Malformed(f"handed back an array it should not: {info.filename!r}")
    dtype, shape = allowed
    length = len(draw.any_hit) + 1 if shape is None else int(np.prod(shape))
    if info.file_size > NPY_HEADER + length * dtype.itemsize:
        raise Malformed(f"handed back an array too large: {info.filename!r}")
    try:
        with archive.open(info) as member:
            array = np.lib.format.read_array(member, allow_pickle=False)
    except ValueError as error:  # an object array, or no .npy file at all
        raise Malformed(f"handed back {info.filename!r}, which is no plain array: "
                        f"{error}") from None
    if array.dtype != dtype or (array.shape != shape if shape is not None
                                else array.ndim != 1 or array.size > length):
        raise Malformed(f"handed back {info.filename!r} as {array.dtype} of shape "
                        f"{array.shape}, where {dtype} of shape "
                        f"{shape or '(at most ' + str(length) + ',)'} is expected")
    return array
