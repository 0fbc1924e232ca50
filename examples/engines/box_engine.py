#!/usr/bin/env python3
"""A small rigid-body engine speaking boxpile's engine protocol (docs/engine-protocol.md).

Python 3 alone, no packages. What it simulates:
  - bodies of one or more boxes, with the mass properties boxpile sends (mass, centre of mass,
    inertia), moving under gravity (semi-implicit Euler: velocities first, then positions);
  - contacts of box vertices with the ground half-space, and of each box's vertices that lie
    below the face of another body's box facing it (the face the line of centres leaves through;
    the normal that face's), which is enough for stacks, walls and piles of boxes resting face on
    face; edge-edge contacts are not found;
  - sequential impulses over the step's contacts (ITERATIONS passes): a normal impulse that is
    never negative, with restitution on approach faster than RESTITUTION_SPEED and a bias that
    pushes out overlaps deeper than SLOP, and Coulomb friction (|tangent impulse| <= mu times the
    normal impulse) along two tangent directions;
  - linear and angular damping when the scene turns damping on.
What it leaves out (so say its results): wires (a body on a wire falls freely), the gyroscopic
term (as the lab text's own method), static friction apart from mu.

Run by boxpile:  boxpile compare SCENE --engines own,pybox --engine-cmd pybox="python3 box_engine.py"
"""
import json
import math
import sys
import time

ITERATIONS = 10            # impulse passes over the contacts per step
FACE_TOLERANCE = 0.01      # a vertex up to 1% of the half extent past a face's edge still rests on it (aligned stacks)
BAUMGARTE = 0.2            # fraction of an overlap pushed out per step
SLOP = 1e-4                # m: overlaps this shallow are left alone
RESTITUTION_SPEED = 0.05   # m/s: slower approaches do not bounce (no jitter at rest)


# --- small vector helpers (3-vectors as lists, 3x3 matrices as lists of rows) -----------------
def add(a, b): return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
def sub(a, b): return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
def scale(a, s): return [a[0] * s, a[1] * s, a[2] * s]
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def matvec(m, v): return [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
def transpose(m): return [[m[j][i] for j in range(3)] for i in range(3)]
def matmul(a, b):
    bt = transpose(b)
    return [[dot(a[i], bt[j]) for j in range(3)] for i in range(3)]


def inverse(m):
    a, b, c = m[0]; d, e, f = m[1]; g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    inv = [[e * i - f * h, c * h - b * i, b * f - c * e],
           [f * g - d * i, a * i - c * g, c * d - a * f],
           [d * h - e * g, b * g - a * h, a * e - b * d]]
    return [[x / det for x in row] for row in inv]


def quat_mul(p, q):
    pw, px, py, pz = p; qw, qx, qy, qz = q
    return [pw * qw - px * qx - py * qy - pz * qz, pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx, pw * qz + px * qy - py * qx + pz * qw]


def quat_matrix(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def tangents(n):
    """Two unit vectors perpendicular to n and to each other."""
    t = [0.0, -n[2], n[1]] if abs(n[0]) < 0.57 else [-n[1], n[0], 0.0]
    t = scale(t, 1.0 / math.sqrt(dot(t, t)))
    return t, cross(n, t)


class Body:
    def __init__(self, b):
        self.fixed = b["fixed"]
        self.com_local = b["center_of_mass"]
        self.q = list(b["orientation"])
        rot = quat_matrix(self.q)
        self.x = add(b["position"], matvec(rot, self.com_local))  # centre of mass, world
        self.v = list(b["velocity"])
        self.w = list(b["angular_velocity"])
        self.inv_mass = 0.0 if self.fixed else 1.0 / b["mass"]
        self.inv_inertia_body = [[0.0] * 3 for _ in range(3)] if self.fixed else inverse(b["inertia"])
        self.friction = b["friction"]
        self.restitution = b["restitution"]
        # Each box: centre relative to the centre of mass (body axes), its rotation, its half extents.
        self.boxes = []
        for box in b["boxes"]:
            self.boxes.append((sub(box["position"], self.com_local), quat_matrix(box["orientation"]), box["half_extents"]))
        self.radius = max(math.sqrt(dot(c, c)) + math.sqrt(dot(h, h)) for c, _, h in self.boxes)
        self.update()

    def update(self):
        self.rot = quat_matrix(self.q)
        self.inv_inertia = matmul(matmul(self.rot, self.inv_inertia_body), transpose(self.rot))

    def placed_boxes(self):
        """Each box's world centre, world axes (columns as rows of the transpose) and half extents."""
        for centre, rot, half in self.boxes:
            axes = transpose(matmul(self.rot, rot))  # axes[k]: the box's k-th axis in world
            yield add(self.x, matvec(self.rot, centre)), axes, half

    def vertices(self):
        for centre, axes, half in self.placed_boxes():
            for sx in (-1, 1):
                for sy in (-1, 1):
                    for sz in (-1, 1):
                        yield add(centre, add(add(scale(axes[0], sx * half[0]), scale(axes[1], sy * half[1])),
                                              scale(axes[2], sz * half[2])))

    def velocity_at(self, p):
        return add(self.v, cross(self.w, sub(p, self.x)))

    def apply_impulse(self, j, p):
        self.v = add(self.v, scale(j, self.inv_mass))
        self.w = add(self.w, matvec(self.inv_inertia, cross(sub(p, self.x), j)))

    def state(self):
        frame = sub(self.x, matvec(self.rot, self.com_local))
        return {"position": frame, "orientation": self.q, "velocity": self.v, "angular_velocity": self.w}


class Contact:
    def __init__(self, a, b, point, normal, depth, friction, restitution):
        self.a, self.b, self.point, self.normal, self.depth = a, b, point, normal, depth
        self.friction, self.restitution = friction, restitution
        self.tangents = tangents(normal)
        self.jn = 0.0
        self.jt = [0.0, 0.0]
        self.target = 0.0


class World:
    def __init__(self, scene):
        self.dt = scene["dt"]
        self.gravity = scene["gravity"]
        self.ground = scene["ground"]
        self.ground_material = scene["ground_material"]
        self.damping = scene["damping"] if scene["effects"]["damping"] else {"linear": 0.0, "angular": 0.0}
        self.bodies = [Body(b) for b in scene["bodies"]]
        self.time = 0.0
        self.contacts = []

    def find_contacts(self):
        contacts = []
        if self.ground is not None:
            n, offset = self.ground["normal"], self.ground["offset"]
            g = self.ground_material
            for i, body in enumerate(self.bodies):
                if body.fixed:
                    continue
                for p in body.vertices():
                    d = dot(n, p) - offset
                    if d < 0.0:
                        contacts.append(Contact(i, -1, add(p, scale(n, -d / 2)), n, -d,
                                                math.sqrt(body.friction * g["friction"]),
                                                max(body.restitution, g["restitution"])))
        for i, a in enumerate(self.bodies):
            for k in range(i + 1, len(self.bodies)):
                b = self.bodies[k]
                if (a.fixed and b.fixed) or dot(sub(a.x, b.x), sub(a.x, b.x)) > (a.radius + b.radius) ** 2:
                    continue
                mu = math.sqrt(a.friction * b.friction)
                e = max(a.restitution, b.restitution)
                # Vertices of a inside a box of b (normal from b toward a), then the other way round.
                for (ia, bodya), (ib, bodyb) in (((i, a), (k, b)), ((k, b), (i, a))):
                    for centre, axes, half in bodyb.placed_boxes():
                        # The face of b's box that faces a: the axis along which the line of
                        # centres leaves the box soonest (relative to the box's size).
                        d = [dot(axes[m], sub(bodya.x, centre)) for m in range(3)]
                        m = max(range(3), key=lambda j: abs(d[j]) / half[j])
                        sign = 1.0 if d[m] > 0 else -1.0
                        normal = scale(axes[m], sign)
                        for p in bodya.vertices():
                            local = [dot(axes[j], sub(p, centre)) for j in range(3)]
                            depth = half[m] - sign * local[m]
                            inside = all(abs(local[j]) <= half[j] * (1 + FACE_TOLERANCE) for j in range(3) if j != m)
                            if depth <= 0.0 or depth > 2 * half[m] or not inside:
                                continue
                            contacts.append(Contact(ia, ib, add(p, scale(normal, depth / 2)), normal, depth, mu, e))
        return contacts

    def relative_velocity(self, c):
        v = self.bodies[c.a].velocity_at(c.point)
        if c.b >= 0:
            v = sub(v, self.bodies[c.b].velocity_at(c.point))
        return v

    def inverse_effective_mass(self, c, d):
        """1 / (the impulse along d that changes the relative velocity along d by 1)."""
        k = 0.0
        for index in (c.a, c.b):
            if index < 0:
                continue
            body = self.bodies[index]
            r = sub(c.point, body.x)
            rd = cross(r, d)
            k += body.inv_mass + dot(rd, matvec(body.inv_inertia, rd))
        return k

    def push(self, c, j):
        self.bodies[c.a].apply_impulse(j, c.point)
        if c.b >= 0:
            self.bodies[c.b].apply_impulse(scale(j, -1.0), c.point)

    def solve(self, contacts):
        for c in contacts:
            vn = dot(self.relative_velocity(c), c.normal)
            bounce = -c.restitution * vn if vn < -RESTITUTION_SPEED else 0.0
            c.target = max(bounce, BAUMGARTE * max(c.depth - SLOP, 0.0) / self.dt)
            c.kn = self.inverse_effective_mass(c, c.normal)
            c.kt = [self.inverse_effective_mass(c, t) for t in c.tangents]
        for _ in range(ITERATIONS):
            for c in contacts:
                vr = self.relative_velocity(c)
                # Normal: the accumulated impulse stays >= 0.
                dj = (c.target - dot(vr, c.normal)) / c.kn
                new = max(c.jn + dj, 0.0)
                self.push(c, scale(c.normal, new - c.jn))
                c.jn = new
                # Friction: each tangent impulse within mu times the normal impulse.
                limit = c.friction * c.jn
                vr = self.relative_velocity(c)
                for m, t in enumerate(c.tangents):
                    dj = -dot(vr, t) / c.kt[m]
                    new = min(max(c.jt[m] + dj, -limit), limit)
                    self.push(c, scale(t, new - c.jt[m]))
                    c.jt[m] = new

    def step(self):
        dt = self.dt
        for body in self.bodies:
            if body.fixed:
                continue
            body.v = add(body.v, scale(self.gravity, dt))
            body.v = scale(body.v, 1.0 - self.damping["linear"] * dt)
            body.w = scale(body.w, 1.0 - self.damping["angular"] * dt)
        self.contacts = self.find_contacts()
        self.solve(self.contacts)
        for body in self.bodies:
            if body.fixed:
                continue
            body.x = add(body.x, scale(body.v, dt))
            spin = quat_mul([0.0] + body.w, body.q)
            body.q = [body.q[m] + 0.5 * dt * spin[m] for m in range(4)]
            norm = math.sqrt(sum(x * x for x in body.q))
            body.q = [x / norm for x in body.q]
            body.update()
        self.time += dt


def answer(world, request):
    op = request["op"]
    if op == "hello":
        return {"ok": True, "protocol": 1, "name": "pybox",
                "version": "box_engine.py (Python %d.%d)" % sys.version_info[:2],
                "precision": "float64", "contacts": True, "timing": True}, world
    if op == "load":
        return {"ok": True}, World(request["scene"])
    if op == "step":
        if world is None:
            raise ValueError("step before load")
        start = time.perf_counter()
        for _ in range(request.get("n", 1)):
            world.step()
        reply = {"ok": True, "time": world.time, "engine_seconds": time.perf_counter() - start}
        if request.get("state", True):
            reply["bodies"] = [b.state() for b in world.bodies]
        if request.get("contacts", False):
            reply["contacts"] = [{"a": c.a, "b": c.b, "position": c.point, "normal": c.normal, "depth": c.depth}
                                 for c in world.contacts]
        return reply, world
    if op == "quit":
        return {"ok": True}, world
    raise ValueError("unknown op %r" % op)


def main():
    world = None
    for line in sys.stdin:
        request = {}
        try:
            request = json.loads(line)
            reply, world = answer(world, request)
        except Exception as error:  # every failure is answered, never a silent exit
            reply = {"ok": False, "error": "%s: %s" % (type(error).__name__, error)}
        sys.stdout.write(json.dumps(reply, allow_nan=False) + "\n")
        sys.stdout.flush()
        if request.get("op") == "quit":
            return


if __name__ == "__main__":
    main()
