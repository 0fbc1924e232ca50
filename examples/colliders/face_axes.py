#!/usr/bin/env python3
"""A box collider in 30 lines, for `boxpile conform` (docs/conform.md): exact for a box on a plane;
box-box tests the six face axes only and reports the vertices inside the other box, so crossing
edges go unseen. One query per input line, one answer per output line."""
import itertools, json, sys

def dot(u, v): return sum(a * b for a, b in zip(u, v))
def box(b):  # centre, the three unit axes (columns of the rotation of [w, x, y, z]), half extents
    w, x, y, z = b.get("orientation", [1, 0, 0, 0])
    axes = [[1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)],
            [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)],
            [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)]]
    return b["position"], axes, b["half_extents"]
def corners(c, axes, h): return [[c[i] + sum(s[k] * h[k] * axes[k][i] for k in range(3)) for i in range(3)]
                                 for s in itertools.product((-1, 1), repeat=3)]
def radius(axes, h, n): return sum(h[k] * abs(dot(axes[k], n)) for k in range(3))
def inside(p, c, axes, h): return all(abs(dot(axes[k], [p[i] - c[i] for i in range(3)])) <= h[k] for k in range(3))
def point(p, n, s): return {"position": [p[i] + s * n[i] for i in range(3)], "normal": n}
def contacts(q):
    a, b = box(q["a"]), None if "plane" in q["b"] else box(q["b"])
    if b is None:  # box on a plane: every corner below it, midway between corner and plane
        n, d = q["b"]["plane"].get("normal", [0, 0, 1]), q["b"]["plane"].get("offset", 0)
        return [dict(point(v, n, (d - dot(n, v)) / 2), depth=d - dot(n, v)) for v in corners(*a) if dot(n, v) < d]
    gap = [a[0][i] - b[0][i] for i in range(3)]
    depth, n = min((radius(a[1], a[2], u) + radius(b[1], b[2], u) - abs(dot(gap, u)), u) for u in a[1] + b[1])
    if depth <= 0: return []
    n = n if dot(gap, n) > 0 else [-x for x in n]  # from B toward A
    return ([dict(point(v, n, depth / 2), depth=depth) for v in corners(*a) if inside(v, *b)] +
            [dict(point(v, n, -depth / 2), depth=depth) for v in corners(*b) if inside(v, *a)])[:8]
for line in sys.stdin:
    print(json.dumps({"contacts": contacts(json.loads(line))}), flush=True)
