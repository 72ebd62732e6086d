"""Why is this pixel this colour? The history of one pixel, told as a short story.

``explain_pixel(integrator, x, y)`` runs ``integrator.compute_color`` once more for the ray
from the camera through the centre of pixel (x, y), and records what it asks the scene:
every ``closest_hit`` and ``any_hit`` with its ray and its answer, and inside each the
answer of every object's ``intersect``; then the colour returned. Printed, the result
reads like this (pixel (250, 453) of Figure 1, on the floor below the sphere):

    camera ray -> closest_hit: object 2 (Parallelogram) at distance 2.02, normal (0, 1, 0)
    shadow ray to light 0 -> any_hit True: blocked by object 0 (Sphere) at 0.75
    shadow ray to light 1 -> any_hit False: visible, adds (0.0482, 0.0482, 0.0482) ...
    shadow ray to light 2 -> any_hit False: visible, adds (0.0484, 0.0484, 0.0484) ...
    -> colour (0.351, 0.351, 0.173)

It works on any integrator with a ``scene`` and a ``compute_color``, yours included, and
on whatever your compute_color, any_hit, closest_hit and primitives do: while it runs,
the scene's two queries and every object's ``intersect`` are wrapped (as attributes of
the objects themselves) by recorders that pass every call on unchanged, and afterwards
they are taken off again. Nothing else of the scene, and nothing of the image, changes.
pyrt/explain_picture.py draws the rays of a history.
"""
import math
import numbers
import sys
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

import cv2
import numpy as np

try:  # the framework's model of what a light adds: it computes Assignment 1.4's answer,
    # so the handout has none (the grader's feedback tells it beside the student's story)
    from pyrt.course_model import phong_term
except ImportError:
    phong_term = None

Vec = Tuple[float, float, float]

QUERIES = ("closest_hit", "any_hit")
# A ray starting this close to a hit point (relative to the point's size, at least 1)
# starts on that surface: students move shadow rays off it by EPSILON (1e-4) or less.
ON_SURFACE = 1e-3
# A ray points at a light when the cosine of the angle between them is this close to 1.
AIMED = 1e-6
# A shadow ray that hits the surface it starts on closer than this (relative, as
# ON_SURFACE) hits it only through rounding: shadow acne.
ACNE_DISTANCE = 1e-3
# A normal whose length differs from 1 by more than this is not of unit length.
UNIT_TOLERANCE = 1e-6


# ------------------------------------------------------------------------------------------
# The records: copies of what was asked and answered, taken when it happened
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RayRecord:
    """A ray as it was when it was asked about: origin, direction, t_min and t_max (None
    for what it does not have, or what is not a number)."""

    origin: Optional[Vec]
    direction: Optional[Vec]
    t_min: Optional[float]
    t_max: Optional[float]


@dataclass(frozen=True)
class HitRecord:
    """An answer of closest_hit or intersect (a HitData) as it was returned."""

    has_hit: bool
    point: Optional[Vec] = None
    normal: Optional[Vec] = None
    distance: Optional[float] = None
    index: Optional[int] = None


@dataclass
class IntersectEvent:
    """One object's intersect(ray): the object's index in object_list and class name."""

    index: int
    kind: str
    ray: RayRecord
    answer: HitRecord


@dataclass
class QueryEvent:
    """One scene.closest_hit(ray) or scene.any_hit(ray), with the intersects and queries it
    made itself, and what the story makes of it: the role of its ray ("camera ray",
    "shadow ray" or "ray"), the light a shadow ray points at, whether that light is
    blocked, by which object, and whether that is shadow acne."""

    method: str
    ray: RayRecord
    hit: Optional[HitRecord] = None  # the answer of closest_hit
    answer: object = None            # the answer of any_hit (True/False, or what it gave)
    intersects: List[IntersectEvent] = field(default_factory=list)
    nested: List["QueryEvent"] = field(default_factory=list)
    role: str = "ray"
    light: Optional[int] = None
    blocked: Optional[bool] = None
    blocker: Optional[IntersectEvent] = None
    acne: bool = False
    phong_term: Optional[Vec] = None  # the course's Phong term of a visible light

    def walk(self):
        """This query and every query inside it, in the order they were asked."""
        yield self
        for query in self.nested:
            yield from query.walk()


@dataclass
class PixelHistory:
    """Everything compute_color asked the scene for pixel (x, y), in order, and the colour
    it returned; ``str()`` tells it as a story, ``notes`` holds its warnings."""

    x: int
    y: int
    integrator: str
    camera_ray: RayRecord
    events: list = field(default_factory=list)  # QueryEvents and IntersectEvents
    color: Optional[Vec] = None
    color_text: str = ""
    image_color: Optional[Vec] = None  # the pixel in scene.rendered_image, once rendered
    error: str = ""
    camera_hit: Optional[QueryEvent] = None
    unlit: List[Tuple[int, Optional[float]]] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)

    def queries(self):
        """Every query, nested ones included, in the order they were asked."""
        for event in self.events:
            if isinstance(event, QueryEvent):
                yield from event.walk()

    def shadow_rays(self):
        """The queries whose ray goes from the camera ray's hit towards a light."""
        return [query for query in self.queries() if query.role == "shadow ray"]

    def __str__(self):
        return "\n".join(story_lines(self))


# ------------------------------------------------------------------------------------------
# Reading the objects of any edition of the course
# ------------------------------------------------------------------------------------------
def vector(v) -> Optional[Vec]:
    """(x, y, z) of a Vector3D, or of the numpy array that some editions' defaults are;
    None when it is neither."""
    try:
        parts = (v.x, v.y, v.z)
    except AttributeError:
        try:
            parts = (v[0], v[1], v[2])
        except (TypeError, IndexError, KeyError):
            return None
    try:
        return tuple(float(part) for part in parts)
    except (TypeError, ValueError):
        return None


def number(value) -> Optional[float]:
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def ray_record(ray) -> RayRecord:
    return RayRecord(vector(getattr(ray, "o", None)), vector(getattr(ray, "d", None)),
                     number(getattr(ray, "t_min", None)), number(getattr(ray, "t_max", None)))


def hit_record(answer) -> HitRecord:
    if not getattr(answer, "has_hit", False):
        return HitRecord(False)
    index = getattr(answer, "primitive_index", None)
    return HitRecord(True, vector(getattr(answer, "hit_point", None)),
                     vector(getattr(answer, "normal", None)),
                     number(getattr(answer, "hit_distance", None)),
                     index if isinstance(index, int) else None)


def plain_method(obj, name):
    """obj's own method `name`: an attribute of the object itself (a student may assign
    one), unless pyrt.acceleration put it there for a render, else its class's."""
    own = getattr(obj, "__dict__", {}).get(name)
    put_by = type(getattr(own, "__self__", None)).__module__
    if own is not None and not put_by.startswith("pyrt.acceleration."):
        return own
    return getattr(type(obj), name).__get__(obj)  # an AttributeError when it has none


# ------------------------------------------------------------------------------------------
# Recording
# ------------------------------------------------------------------------------------------
class _Recorder:
    """Stands between compute_color and the scene while it runs: the scene's queries and
    each object's intersect, wrapped, record their calls into ``events`` (into the query
    being answered, when there is one) and pass them on unchanged."""

    def __init__(self, scene):
        self.scene = scene
        self.events = []
        self.open = []     # the queries being answered, innermost last
        self.undo = []     # (object, attribute name, whether it had its own, its own)

    def __enter__(self):
        try:
            for name in QUERIES:
                if hasattr(self.scene, name):  # a scene of the course's may lack any_hit
                    self._wrap(self.scene, name,
                               self._query(name, plain_method(self.scene, name)))
            wrapped = set()
            for index, obj in enumerate(self.scene.object_list):
                if id(obj) not in wrapped:  # an object listed twice is recorded once
                    wrapped.add(id(obj))
                    self._wrap(obj, "intersect", self._intersect(index, obj, obj.intersect))
        except BaseException:  # e.g. an object without intersect: leave nothing wrapped
            self.__exit__()
            raise
        return self

    def __exit__(self, *exc_info):
        for owner, name, had_own, own in reversed(self.undo):
            if had_own:
                setattr(owner, name, own)
            else:
                delattr(owner, name)
        return False

    def _wrap(self, owner, name, recorder):
        own = getattr(owner, "__dict__", None)
        if own is None:  # an object with __slots__ only cannot be watched
            return
        self.undo.append((owner, name, name in own, own.get(name)))
        setattr(owner, name, recorder)

    def _add(self, event):
        (self.open[-1].nested if self.open else self.events).append(event)

    def _query(self, method, plain):
        def recorded(ray, *args, **kwargs):
            event = QueryEvent(method, ray_record(ray))
            self._add(event)
            self.open.append(event)
            try:
                answer = plain(ray, *args, **kwargs)
            finally:
                self.open.pop()
            if method == "closest_hit":
                event.hit = hit_record(answer)
            else:
                event.answer = _truth(answer)
            return answer
        return recorded

    def _intersect(self, index, obj, plain):
        kind = type(obj).__name__

        def recorded(ray, *args, **kwargs):
            before = ray_record(ray)
            answer = plain(ray, *args, **kwargs)
            event = IntersectEvent(index, kind, before, hit_record(answer))
            (self.open[-1].intersects if self.open else self.events).append(event)
            return answer
        return recorded


def _truth(answer):
    """any_hit's answer: True or False when it is one (numpy's booleans too), else its
    repr, which the story shows as it is."""
    if isinstance(answer, (bool, np.bool_)):
        return bool(answer)
    return repr(answer)


def course_class(scene, name):
    """The class `name` (Ray, Vector3D) of the modules the scene was made with: a
    student's own, when the scene is a student's."""
    for obj in (scene, scene.camera):
        found = getattr(sys.modules.get(type(obj).__module__), name, None)
        if found is not None:
            return found
    raise LookupError(f"explain_pixel: found no {name} beside {type(scene).__name__}")


def explain_pixel(integrator, x, y) -> PixelHistory:
    """The PixelHistory of pixel (x, y) (x to the right, y down) of integrator's scene:
    compute_color run once more on the ray that the course's render loop makes for it,
    Ray(Vector3D(0.0, 0.0, 0.0), scene.camera.get_direction(x, y)), with every query it
    makes recorded. Raises ValueError for a pixel outside the image."""
    scene = integrator.scene
    if scene is None or getattr(scene, "camera", None) is None:
        raise ValueError("explain_pixel: the integrator has no scene with a camera yet; "
                         "call integrator.add_scene(scene) first")
    width, height = scene.camera.width, scene.camera.height
    if not (_whole(x) and _whole(y) and 0 <= x < width and 0 <= y < height):
        raise ValueError(f"explain_pixel: pixel ({x!r}, {y!r}) is not in the {width} x "
                         f"{height} image: x goes from 0 to {width - 1}, y from 0 to "
                         f"{height - 1}")
    x, y = int(x), int(y)
    Ray, Vector3D = course_class(scene, "Ray"), course_class(scene, "Vector3D")
    ray = Ray(Vector3D(0.0, 0.0, 0.0), scene.camera.get_direction(x, y))
    history = PixelHistory(x, y, type(integrator).__name__, ray_record(ray))
    compute_color = plain_method(integrator, "compute_color")
    with _Recorder(scene) as recorder:
        try:
            color = compute_color(ray)
        except Exception as error:  # the story tells it, with what was asked before it
            history.error = f"{type(error).__name__}: {error}"
            color = None
    history.events = recorder.events
    if not history.error:
        history.color_text = repr(color)
        history.color = _color_channels(color)
    image = getattr(scene, "rendered_image", None)
    if isinstance(image, np.ndarray) and image.shape[:2] == (height, width) and image.any():
        history.image_color = tuple(float(c) for c in image[y, x][:3])
    interpret(history, scene, Vector3D)
    return history


def opencv_click(integrator):
    """A mouse callback for OpenCV's window: after
    cv2.setMouseCallback(window_name, opencv_click(integrator)), a left click on the image
    that cv2.imshow shows in that window prints the history of the pixel clicked (OpenCV
    gives the click in the image's own pixels)."""
    def clicked(event, x, y, flags, param):
        if event == cv2.EVENT_LBUTTONDOWN:
            print(explain_pixel(integrator, x, y))
    return clicked


def _whole(value) -> bool:
    """Whether value is a whole number of pixels (an int or numpy integer, not a bool)."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _color_channels(color) -> Optional[Vec]:
    try:
        return tuple(float(channel) for channel in (color.r, color.g, color.b))
    except (AttributeError, TypeError, ValueError):
        return None


# ------------------------------------------------------------------------------------------
# What the records mean
# ------------------------------------------------------------------------------------------
def _size(p: Vec) -> float:
    return max(1.0, max(abs(c) for c in p))


def hit_object(query: QueryEvent) -> Optional[IntersectEvent]:
    """The intersect that gave query its answer: for closest_hit the object of its
    primitive_index (else the intersect that hit at its distance), for any_hit the first
    intersect that hit, which is where the course's any_hit stops."""
    hits = [event for query_ in query.walk() for event in query_.intersects
            if event.answer.has_hit]
    if query.method == "closest_hit" and query.hit is not None and query.hit.has_hit:
        for event in hits:
            if event.index == query.hit.index:
                return event
        return next((event for event in hits if event.answer.distance == query.hit.distance),
                    None)
    return hits[0] if hits else None


def _aimed_light(ray: RayRecord, lights) -> Tuple[Optional[int], Optional[float]]:
    """The index of the light the ray points at, and its distance; (None, None) if none."""
    if ray.origin is None or ray.direction is None:
        return None, None
    d_length = math.sqrt(sum(c * c for c in ray.direction))
    best = (None, None, 1.0 - AIMED)
    for k, light in enumerate(lights):
        position = vector(getattr(light, "pos", None))
        if position is None or d_length == 0.0:
            continue
        to_light = [p - o for p, o in zip(position, ray.origin)]
        distance = math.sqrt(sum(c * c for c in to_light))
        if distance > 0.0:
            cosine = sum(a * b for a, b in zip(to_light, ray.direction)) / distance / d_length
            if cosine > best[2]:
                best = (k, distance, cosine)
    return best[0], best[1]


def interpret(history: PixelHistory, scene, Vector3D):
    """Names each query's ray, finds the shadow rays, their lights, blockers and acne, the
    course's Phong term of each visible light, and writes the notes."""
    lights = list(getattr(scene, "pointLights", ()))
    anchor = None  # the closest_hit whose surface the next shadow rays leave
    for query in history.queries():
        ray = query.ray
        if ray == history.camera_ray:
            query.role = "camera ray"
        elif anchor is not None and ray.origin is not None:
            point = anchor.hit.point
            if max(abs(a - b) for a, b in zip(ray.origin, point)) <= ON_SURFACE * _size(point):
                light, distance = _aimed_light(ray, lights)
                if light is not None:
                    _shadow(query, light, distance, anchor, point)
        if (query.method == "closest_hit" and query.role != "shadow ray"
                and query.hit is not None and query.hit.has_hit and query.hit.point is not None):
            anchor = query
            if history.camera_hit is None and query.role == "camera ray":
                history.camera_hit = query
    if history.camera_hit is not None:
        _lights(history, scene, lights, Vector3D)
    _notes(history)


def _shadow(query, light, distance, anchor, point):
    query.role, query.light = "shadow ray", light
    query.blocker = hit_object(query)
    if query.method == "any_hit":
        query.blocked = query.answer is True
    else:
        query.blocked = query.hit.has_hit and (query.hit.distance or 0.0) < distance
    own = hit_object(anchor)
    blocker = query.blocker
    query.acne = bool(query.blocked and blocker is not None and own is not None
                      and blocker.index == own.index and blocker.answer.distance is not None
                      and blocker.answer.distance < ACNE_DISTANCE * _size(point))


def _lights(history, scene, lights, Vector3D):
    """The course's Phong term of every light a shadow ray found visible (where the
    framework's model is there), and the lights no shadow ray went to, with n . wi (negative: the light is behind the surface)."""
    hit = history.camera_hit.hit
    asked = {query.light for query in history.shadow_rays()}
    for query in history.shadow_rays():
        if phong_term is not None and not query.blocked and query.light is not None:
            query.phong_term = phong_term(scene, hit, lights[query.light],
                                          history.camera_ray, Vector3D)
    for k, light in enumerate(lights):
        if k not in asked:
            position = vector(getattr(light, "pos", None))
            cosine = None
            if position is not None and hit.normal is not None:
                to_light = [p - q for p, q in zip(position, hit.point)]
                length = math.sqrt(sum(c * c for c in to_light)) or 1.0
                cosine = sum(n * c for n, c in zip(hit.normal, to_light)) / length
            history.unlit.append((k, cosine))


def _notes(history):
    notes = history.notes
    for query in history.shadow_rays():
        if query.acne:
            notes.append(
                f"shadow acne: the shadow ray to light {query.light} hits object "
                f"{query.blocker.index}, the very surface it starts on, at "
                f"{_n(query.blocker.answer.distance)}: the hit point lies on the surface, or "
                "by rounding a hair below it. Start the ray EPSILON along, e.g. "
                "Ray(hit_point, wi, distance), whose t_min is EPSILON, so that it cannot "
                "hit its own start.")
    hit = history.camera_hit.hit if history.camera_hit else None
    if hit is not None and hit.normal is not None:
        length = math.sqrt(sum(c * c for c in hit.normal))
        if abs(length - 1.0) > UNIT_TOLERANCE:
            notes.append(f"the normal {_v(hit.normal)} of the camera ray's hit has length "
                         f"{_n(length)}, not 1: a normal must be of unit length (Normalize)")
    if history.error:
        return  # the story ends with the error
    if history.color is None:
        notes.append(f"the colour {history.color_text} is not an RGBColor: compute_color "
                     "must return one" + (" (a `pass` left in returns None)"
                                          if history.color_text == "None" else ""))
    elif any(math.isnan(c) for c in history.color):
        notes.append(f"the colour {history.color_text} has NaN (not a number) in it: "
                     "0/0, or the square root of a negative number, somewhere before")
    elif history.image_color is not None and not all(
            math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
            for a, b in zip(history.color, history.image_color)):
        notes.append(f"the rendered image holds {_v(history.image_color)} at this pixel, not "
                     "this colour: render() gave the pixel another one (a colour of its own, "
                     "x and y swapped in set_pixel, or several rays per pixel averaged)")


# ------------------------------------------------------------------------------------------
# Telling
# ------------------------------------------------------------------------------------------
def _n(value) -> str:
    return "?" if value is None else f"{value + 0.0:.3g}"  # + 0.0 turns -0.0 into 0


def _v(values) -> str:
    return "?" if values is None else "(" + ", ".join(_n(c) for c in values) + ")"


def _answer(query: QueryEvent) -> str:
    """What a query answered, in a few words."""
    obj = hit_object(query)
    if query.method == "closest_hit":
        if query.hit is None:
            return "closest_hit: raised an error"
        if not query.hit.has_hit:
            return "closest_hit: no hit"
        named = f"object {obj.index} ({obj.kind})" if obj else f"object {query.hit.index}"
        return (f"closest_hit: {named} at distance {_n(query.hit.distance)}, "
                f"normal {_v(query.hit.normal)}")
    text = f"any_hit {query.answer}"
    if query.answer is True and obj is not None:
        text += f": object {obj.index} ({obj.kind}) at {_n(obj.answer.distance)}"
    return text


def _asked(query: QueryEvent) -> str:
    """The objects asked by the query itself, each with its answer."""
    parts = [f"{event.index} {event.kind} " + (_n(event.answer.distance)
                                                 if event.answer.has_hit else "missed")
             for event in query.intersects]
    if not parts:
        return "no object's intersect was asked"
    if not any(event.answer.has_hit for event in query.intersects):
        return f"every object missed ({len(parts)} asked)"
    return "objects asked: " + ", ".join(parts)


def _query_lines(query: QueryEvent, depth: int) -> List[str]:
    pad = "  " * depth
    if query.role == "shadow ray":
        head = f"shadow ray to light {query.light} -> "
        if query.blocked:
            blocker = query.blocker
            verdict = "blocked" + (f" by object {blocker.index} ({blocker.kind}) at "
                                   f"{_n(blocker.answer.distance)}" if blocker else "")
            if query.acne:
                verdict += ", its own surface: SHADOW ACNE"
        else:
            verdict = "visible" + (f", adds {_v(query.phong_term)} in the course's Phong "
                                   "model" if query.phong_term else "")
        if query.method == "any_hit":
            answer = f"any_hit {query.answer}"
        else:
            answer = "closest_hit " + (f"at {_n(query.hit.distance)}" if query.hit.has_hit
                                       else "no hit")
        lines = [f"{pad}{head}{answer}: {verdict}"]
    else:
        lines = [f"{pad}{query.role} -> {_answer(query)}"]
    lines.append(f"{pad}    {_asked(query)}")
    for inner in query.nested:
        lines += _query_lines(inner, depth + 1)
    return lines


def story_lines(history: PixelHistory) -> List[str]:
    ray = history.camera_ray
    lines = [f"Pixel ({history.x}, {history.y}) of {history.integrator}: the camera ray "
             f"from {_v(ray.origin)} along {_v(ray.direction)}"]
    for event in history.events:
        if isinstance(event, QueryEvent):
            lines += _query_lines(event, 1)
        else:
            lines.append(f"  intersect of object {event.index} ({event.kind}) -> "
                         + (f"hit at {_n(event.answer.distance)}" if event.answer.has_hit
                            else "missed"))
    if not history.events:
        lines.append("  no question was asked of the scene")
    for k, cosine in history.unlit:
        where = ("behind the surface" if cosine is not None and cosine <= 0.0
                 else "in front of the surface")
        lines.append(f"  light {k}: no shadow ray (n . wi = {_n(cosine)}, {where})")
    if history.error:
        lines.append(f"  -> compute_color raised {history.error}")
    else:
        lines.append("  -> colour " + (_v(history.color) if history.color is not None
                                        else history.color_text))
    lines += [f"  NOTE: {note}" for note in history.notes]
    return lines
