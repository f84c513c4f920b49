"""hits and t_sum of scene.intersect's results as `quiver trace` adds them
(app/trace_command.h): per tile of quiver.camera_rays, the hit distances in
ray order in double, then the tiles in order. The Python benchmark and
tests/python_intersect_test.py compare them with trace's JSON line."""
import numpy as np


def trace_totals(result, tile_starts):
    """(hits, t_sum) of intersect's result dict over the tiles of tile_starts."""
    hit = result["kind"] >= 0
    t = result["t"].astype(np.float64)
    t_sum = 0.0
    for a, b in zip(tile_starts[:-1], tile_starts[1:]):
        tile = t[a:b][hit[a:b]]
        if tile.size:
            t_sum += float(np.cumsum(tile)[-1])  # cumsum adds in order, as trace does
    return int(hit.sum()), t_sum
