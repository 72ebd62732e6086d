# The student's Scene.any_hit and Scene.closest_hit of Assignments 1.2 and 1.3, as written in
# the course's PyRT_Core.py; render_all.py puts them in place of PyRT's own.
from PyRT_Common import *


def any_hit(self, ray):
    for obj in self.object_list:
        hit_data = obj.intersect(ray)
        if hit_data.has_hit:
            return True
    return False


def closest_hit(self, ray):
    closest = HitData()
    min_distance = HUGEVALUE
    for index, obj in enumerate(self.object_list):
        hit_data = obj.intersect(ray)
        if hit_data.has_hit and hit_data.hit_distance < min_distance:
            min_distance = hit_data.hit_distance
            closest = hit_data
            closest.primitive_index = index
    return closest
