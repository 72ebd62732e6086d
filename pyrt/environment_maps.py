"""PyRT's own environment maps, made by code: latitude-longitude images whose radiance is
a simple function of the direction, so that what they give is known in closed form.

An environment map of PyRT_Common.EnvironmentMap looks the direction d up at the texel
(floor(u (width - 1)), floor(v (height - 1))), with v = acos(d.y)/pi. Texel row j therefore
answers the directions whose v lies in [j/(height - 1), (j + 1)/(height - 1)), and each
map below stores in row j its radiance at the middle of that band. The maps are grey
(r = g = b), as the course reads every map.
"""
import numpy as np

# The sky map: radiance SKY_HORIZON + SKY_ZENITH_GAIN * d.y above the horizon (brightest
# straight up), GROUND below it.
SKY_HORIZON = 0.6
SKY_ZENITH_GAIN = 1.4
GROUND = 0.3
SKY_WIDTH, SKY_HEIGHT = 512, 256


def band_heights(height: int) -> np.ndarray:
    """d.y at the middle of the band of directions each texel row answers (see above)."""
    v = (np.arange(height) + 0.5) / (height - 1)
    return np.cos(np.minimum(v, 1.0) * np.pi)


def constant_map(radiance: float, width: int = 8, height: int = 4) -> np.ndarray:
    """A map of the same radiance in every direction (a "white furnace" when it lights a
    white object): the float32 texels, shape (height, width, 3)."""
    return np.full((height, width, 3), radiance, dtype=np.float32)


def sky_map(width: int = SKY_WIDTH, height: int = SKY_HEIGHT) -> np.ndarray:
    """A sky and a ground: L(d) = SKY_HORIZON + SKY_ZENITH_GAIN d.y where d.y >= 0, GROUND
    below. A surface facing straight up receives the irradiance
    E = integral of L cos over the upper hemisphere = pi SKY_HORIZON + 2 pi SKY_ZENITH_GAIN / 3,
    as sky_irradiance gives. The float32 texels, shape (height, width, 3)."""
    y = band_heights(height)
    radiance = np.where(y >= 0.0, SKY_HORIZON + SKY_ZENITH_GAIN * y, GROUND)
    rows = np.broadcast_to(radiance[:, None, None], (height, width, 3))
    return rows.astype(np.float32)


def sky_irradiance() -> float:
    """The irradiance sky_map's continuous radiance gives a surface facing straight up,
    pi SKY_HORIZON + 2 pi SKY_ZENITH_GAIN / 3."""
    return np.pi * SKY_HORIZON + 2.0 * np.pi * SKY_ZENITH_GAIN / 3.0
