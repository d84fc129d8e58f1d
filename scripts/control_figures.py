"""The figures of docs/control.md: run in a folder holding g.gmg (the graph), A.bvh (a
reenactment), B.bvh (A kept outside --range 20:30) and P.bvh (--pin 40=27:28.6), with the module
on PYTHONPATH (build/python). Positions are in the files' units (BEAT2: metres)."""
import numpy as np

import gmg

g = gmg.load("g.gmg")
fps = g.fps
ref = g.motion
A, B, P = (gmg.read_motion(n + ".bvh") for n in "ABP")


def steps(x):
    """Per frame, the largest joint displacement."""
    return np.linalg.norm(np.diff(x, axis=0), axis=2).max(axis=1)


def heading_relative(m, first, count):
    """Joint positions relative to the root, turned into the root's heading (Y-up)."""
    p = m.positions[first:first + count]
    w, x, y, z = m.rotations[first:first + count, 0].T
    yaw = -np.arctan2(2 * (w * y + x * z), 1 - 2 * (x * x + y * y))
    r = p - p[:, :1]
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    out = r.copy()
    out[..., 0] = c * r[..., 0] + s * r[..., 2]
    out[..., 2] = -s * r[..., 0] + c * r[..., 2]
    return out


a, b = round(20 * fps), round(30 * fps)
variation = np.linalg.norm(np.diff(ref.positions, axis=0), axis=2).mean()
distance = np.linalg.norm(B.positions[a:b] - A.positions[a:b], axis=2).mean()
print(f"range [20, 30) s: mean joint distance B-A {distance:.4f} = {distance / variation:.2f}x the reference's "
      f"mean frame-to-frame joint step {variation:.4f}")
p999 = np.percentile(steps(ref.positions), 99.9)
sb = steps(B.positions)
print(f"largest step of B {sb.max() / p999:.2f}x the reference's 99.9th percentile ({p999:.4f}); "
      f"within 0.1 s of 20 s {sb[a - 3:a + 3].max() / p999:.2f}x, of 30 s {sb[b - 3:b + 3].max() / p999:.2f}x")
o0, o1, r0 = round(40.2 * fps), round(41.4 * fps), round(27.2 * fps)
gap = np.linalg.norm(heading_relative(P, o0, o1 - o0) - heading_relative(ref, r0, o1 - o0), axis=2)
print(f"pin: output 40.2-41.4 s against reference 27.2-28.4 s: largest joint gap {gap.max():.5f}, mean {gap.mean():.5f}")
