"""A picture of a pixel's rays: the scene's objects, the camera ray, the hit with its
normal and each shadow ray to its light, blocked or visible, seen from the side and from
above. It draws a PixelHistory of pyrt/explain.py:

    history = explain_pixel(integrator, 250, 400)
    save_picture(history, integrator.scene, "out/pixel_250_400.png")

The picture is drawn by matplotlib's Agg canvas directly, without pyplot, so that it
neither opens a window nor disturbs the one that shows the rendered image.
"""
import math
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Polygon

from pyrt.explain import PixelHistory, number, vector

# (horizontal, vertical) components of each view, with their labels: the camera looks
# down -z, drawn to the right in both views; from above, +x (the image's right) is down.
VIEWS = (("side view", (2, 1), "z (the camera looks towards -z)", "y (up)"),
         ("top view", (2, 0), "z (the camera looks towards -z)", "x (to the image's right)"))
COLORS = {"object": "0.35", "camera": "tab:blue", "normal": "tab:purple",
          "visible": "tab:green", "blocked": "tab:red", "light": "orange"}
# The colour of each kind of label; a label merged from several kinds is black
LABEL_COLORS = {"object": COLORS["object"], "camera": COLORS["camera"], "light": "black",
                "acne": COLORS["blocked"]}
# Labels of points closer than this fraction of a view's extent are written as one label,
# "camera, light 0": written apart they would be printed over each other
LABEL_MERGE_FRACTION = 0.03


def save_picture(history: PixelHistory, scene, path) -> Path:
    """Draws the rays of history through scene's objects and lights into the PNG at path
    (its folder made if needed); returns the path."""
    path = Path(path)
    figure = Figure(figsize=(11, 5), dpi=90)
    FigureCanvasAgg(figure)
    color = "?" if history.color is None else ", ".join(f"{c:.3g}" for c in history.color)
    figure.suptitle(f"Pixel ({history.x}, {history.y}) of {history.integrator}: "
                    f"colour ({color})")
    shapes = _shapes(scene)
    lights = [vector(getattr(light, "pos", None)) for light in getattr(scene, "pointLights", ())]
    for column, (name, axes_of, xlabel, ylabel) in enumerate(VIEWS):
        ax = figure.add_subplot(1, 2, column + 1)
        _draw_view(ax, history, shapes, lights, axes_of)
        ax.set_title(name)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_aspect("equal", adjustable="datalim")
        ax.invert_xaxis()  # -z to the right
        if axes_of[1] == 0:
            ax.invert_yaxis()  # from above, +x down
    handles = [ax.plot([], [], color=COLORS[kind], label=label)[0] for kind, label in
               (("camera", "camera ray"), ("normal", "normal at the hit"),
                ("visible", "shadow ray, light visible"), ("blocked", "shadow ray, blocked"))]
    figure.legend(handles=handles, loc="lower center", ncol=4, frameon=False)
    figure.subplots_adjust(bottom=0.2, top=0.86, wspace=0.3)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path)
    return path


def _shapes(scene):
    """Each object of the scene that can be drawn: ("sphere", index, centre, radius) or
    ("polygon", index, corners), from the attributes the course's primitives have."""
    shapes = []
    for index, obj in enumerate(getattr(scene, "object_list", ())):
        centre, radius = vector(getattr(obj, "origin", None)), number(getattr(obj, "radius", None))
        point = vector(getattr(obj, "point", None))
        s1, s2 = vector(getattr(obj, "s1", None)), vector(getattr(obj, "s2", None))
        if centre is not None and radius is not None:
            shapes.append(("sphere", index, centre, radius))
        elif None not in (point, s1, s2):
            corners = [point, _add(point, s1), _add(_add(point, s1), s2), _add(point, s2)]
            shapes.append(("polygon", index, corners))
    return shapes


def _add(a, b):
    return tuple(p + q for p, q in zip(a, b))


def _draw_view(ax, history, shapes, lights, axes_of):
    """Draws one view: the components axes_of = (horizontal, vertical) of everything."""
    h, v = axes_of

    def flat(p):
        return p[h], p[v]

    # (point, kind, text), written once everything is drawn; the objects' numbers last, so
    # that a label merged with one stands at its point, not at the object's centre
    numbers = []
    for shape in shapes:
        if shape[0] == "sphere":
            _, index, centre, radius = shape
            ax.add_patch(Circle(flat(centre), radius, fill=False, color=COLORS["object"]))
            numbers.append((flat(centre), "object", str(index)))
        else:
            _, index, corners = shape
            outline = [flat(c) for c in corners]
            ax.add_patch(Polygon(outline, closed=True, fill=False, color=COLORS["object"]))
            # A polygon seen face on covers the others' labels: only edge-on ones get one
            if _area(outline) <= 1e-9:
                numbers.append((tuple(sum(c) / 4 for c in zip(*outline)), "object",
                                str(index)))
    ax.plot(0.0, 0.0, marker="s", color=COLORS["camera"])
    labels = [((0.0, 0.0), "camera", "camera")]
    for k, position in enumerate(lights):
        if position is not None:
            ax.plot(*flat(position), marker="*", markersize=12, color=COLORS["light"],
                    zorder=4)
            labels.append((flat(position), "light", f"light {k}"))
    labels += _draw_rays(ax, history, flat, lights, _size(shapes, lights))
    _write_labels(ax, labels + numbers)


def merged_labels(labels, extent, fraction=LABEL_MERGE_FRACTION):
    """The labels [(point, label)] of a view grouped as [(point, [label, ...])]: a label
    closer than fraction * extent to the point of an earlier group joins that group."""
    groups = []
    for point, label in labels:
        for at, members in groups:
            if math.dist(at, point) < fraction * extent:
                members.append(label)
                break
        else:
            groups.append((point, [label]))
    return groups


def _write_labels(ax, labels):
    """Writes the labels [(point, kind, text)] of a view, those that coincide as one."""
    extent = max(ax.dataLim.width, ax.dataLim.height)
    for at, members in merged_labels([(p, (kind, text)) for p, kind, text in labels],
                                     extent):
        members = list(dict.fromkeys(members))  # two rays' "acne" at one point: once
        kinds = {kind for kind, _ in members}
        if kinds == {"object"}:  # the objects' numbers, boxed at their centres
            ax.annotate(", ".join(text for _, text in members), at, fontsize=9,
                        color=COLORS["object"], ha="center", va="center",
                        bbox={"boxstyle": "round", "fc": "white", "ec": "0.8"})
            continue
        # beside other labels a bare number would read as part of them
        text = ", ".join(f"object {text}" if kind == "object" else text
                         for kind, text in members)
        color = LABEL_COLORS[kinds.pop()] if len(kinds) == 1 else "black"
        # set off up and to the right, clear of the point's marker
        ax.annotate(text, at, xytext=(6, 4), textcoords="offset points", fontsize=8,
                    color=color, zorder=6)


def _area(outline):
    """The area of a polygon given by its corners (the shoelace formula)."""
    return abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1)
                   in zip(outline, outline[1:] + outline[:1]))) / 2.0


def _size(shapes, lights):
    """About how large the scene is: the largest coordinate of its objects and lights."""
    values = [1.0]
    for shape in shapes:
        points = [shape[2]] if shape[0] == "sphere" else shape[2]
        values += [abs(c) + (shape[3] if shape[0] == "sphere" else 0.0)
                   for p in points for c in p]
    values += [abs(c) for p in lights if p is not None for c in p]
    return max(values)


def _draw_rays(ax, history, flat, lights, size):
    """Draws the camera ray, its hit and normal, and the shadow rays; returns the labels
    [(point, kind, text)] of what it drew."""
    labels = []
    camera = history.camera_ray
    hit = history.camera_hit.hit if history.camera_hit else None
    if hit is not None:
        end = hit.point
    elif camera.direction is not None:  # a miss: the ray leaves the scene
        length = math.sqrt(sum(c * c for c in camera.direction)) or 1.0
        end = tuple(2.0 * size * c / length for c in camera.direction)
    else:
        return labels
    ax.plot(*zip(flat(camera.origin or (0.0, 0.0, 0.0)), flat(end)), color=COLORS["camera"])
    if hit is None:
        return labels
    ax.plot(*flat(hit.point), marker="o", color=COLORS["camera"])
    if hit.normal is not None:
        tip = tuple(p + 0.15 * size * n for p, n in zip(hit.point, hit.normal))
        ax.annotate("", flat(tip), flat(hit.point), zorder=5,
                    arrowprops={"arrowstyle": "->", "color": COLORS["normal"], "lw": 1.5})
    for query in history.shadow_rays():
        start, light = query.ray.origin, query.light
        target = lights[light]  # the story found the ray pointing at it
        if query.blocked:
            blocker = query.blocker
            stop = blocker.answer.point if blocker and blocker.answer.point else target
            # drawn over the visible ones, which may run along the same line in a view
            ax.plot(*zip(flat(start), flat(stop)), color=COLORS["blocked"], zorder=3)
            ax.plot(*zip(flat(stop), flat(target)), color=COLORS["blocked"], linestyle=":",
                    zorder=3)
            ax.plot(*flat(stop), marker="x", markersize=9, color=COLORS["blocked"], zorder=3)
            if query.acne:
                labels.append((flat(stop), "acne", "acne"))
        else:
            ax.plot(*zip(flat(start), flat(target)), color=COLORS["visible"])
    return labels

