"""What the course's Phong model adds for a visible light, for the stories of
pyrt/explain.py: part of Assignment 1.4's answer, so it is the framework's only, never in
the students' handout nor in the grader's working copies (course_kit/grader.py)."""
import math
from typing import Optional, Tuple

Vec = Tuple[float, float, float]


def phong_term(scene, hit, light, camera_ray, Vector3D) -> Optional[Vec]:
    """intensity (x) BRDF.get_value(wi, wo, n) / r^2 of the object hit (a HitRecord of
    pyrt/explain.py), as the course's Phong model adds it for a visible light; None when
    the scene's classes cannot tell."""
    try:
        brdf = scene.object_list[hit.index].get_BRDF()
        to_light = light.pos - Vector3D(*hit.point)
        r2 = to_light.x ** 2 + to_light.y ** 2 + to_light.z ** 2
        wi = to_light * (1.0 / math.sqrt(r2))
        wo = Vector3D(*(-c for c in camera_ray.direction))
        term = light.intensity.multiply(brdf.get_value(wi, wo, Vector3D(*hit.normal)))
        return tuple(channel / r2 for channel in (term.r, term.g, term.b))
    except Exception:  # a student's classes may lack any of these; the story does without
        return None
