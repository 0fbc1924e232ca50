#!/usr/bin/env python3
"""Drives one node adapter of reference/ (docs/engine-protocol.md) directly over its pipes and
checks its conventions against analytic results: hello's fields, a resting box's contacts, free
flight (the integrator's discrete path), the centre of mass and angular velocity conventions, the
pair friction law, damping, a wire, a stack of 5, bad input answered with ok: false, and exit at
end of input.

usage: protocol_engines_test.py ENGINE REFERENCE_DIR   (ENGINE: jolt, rapier, mujoco-wasm)
"""
import json
import math
import os
import subprocess
import sys
import time

DT = 1 / 240
G = 9.81
# How long an adapter may take to exit at the end of its input (s). node waits at exit for V8's
# background optimising compile of the WebAssembly hot functions: Rapier's largest took 13-30 s
# on this shared 2-core machine under a load of 12.
kExitWait = 120

# What each engine gives by design, measured on this machine (docs/reference-engines.md).
# rest_depth: the deepest a resting unit box may sink into the ground (m), and its shallowest;
# stack_top: [low, high] of the top box's centre of a stack of 5 unit boxes after 5 s (m);
# fall_tol: how far the free-fall path may stray from the discrete (semi-implicit Euler) one,
# which is the float32 rounding of ~1 m positions over 240 steps, or float64's;
# substeps: semi-implicit Euler substeps per step (Rapier's solver takes num_solver_iterations
# substeps of dt / 4 each step, velocity then position);
# bounce_e: the restitution a box dropped 1 m with e = 0.5 shows (sqrt of rebound / drop height);
# com_tol: how far the frame of a spinning body with an offset centre of mass may stray (MuJoCo
# integrates the free joint at the body's origin, holding the origin's velocity over a step while
# it circles the centre of mass: first order in dt, r w^2 dt t / 2 = 4.2e-4 m in that test, and it
# halves with dt; the others integrate the centre of mass).
ENGINES = {
    'jolt': {
        'script': 'jolt/jolt_engine.mjs', 'precision': 'float32',
        'rest_depth': (0.0, 1e-6),     # Jolt starts at exact touch and holds it (no soft contact)
        'stack_top': (4.4997, 4.5),     # measured 4.499854
        'bounce_e': (0.49, 0.53),       # measured 0.514
        'fall_tol': 2e-5, 'substeps': 1, 'com_tol': 1e-4, 'gyroscopic_switch': True,
        'compound_contacts': 4,  # manifold reduction merges the two boxes' manifolds: the bar's 4 corners
    },
    'rapier': {
        'script': 'rapier/rapier_engine.mjs', 'precision': 'float32',
        'rest_depth': (3e-5, 1.2e-4),  # Rapier's soft contacts settle inside: measured 6.8e-5
        'stack_top': (4.493, 4.497),    # measured 4.495014: about 1.2 mm per interface
        'bounce_e': (0.46, 0.50),       # measured 0.476
        'fall_tol': 2e-5, 'substeps': 4, 'com_tol': 1e-4,
        'gyroscopic_switch': False,  # always on: the JS API has no switch (the adapter says so on stderr)
        'compound_contacts': 6,  # a manifold per box; the two corners they share kept once
    },
    'mujoco-wasm': {
        'script': 'mujoco_wasm/mujoco_wasm_engine.mjs', 'precision': 'float64',
        'rest_depth': (5e-6, 5e-5),    # soft contacts (solref/solimp) sink by design: measured 1.7e-5
        'stack_top': (4.4993, 4.4998),  # measured 4.499578
        # no coefficient of restitution: the damping ratio of a linear spring that returns e
        # (mujoco_wasm_engine.mjs) gives 0.42 for e = 0.5, MuJoCo's contact spring being nonlinear
        'bounce_e': (0.40, 0.44),
        'fall_tol': 1e-9, 'substeps': 1, 'com_tol': 5e-4,
        'gyroscopic_switch': True,  # MuJoCo always has the term: the adapter cancels it when off
        'compound_contacts': 8,  # 4 per box geom, the shared corners once for each box
    },
}

failures = []


def check(ok, what):
    print(('ok    ' if ok else 'FAIL  ') + what, flush=True)
    if not ok:
        failures.append(what)


class Adapter:
    def __init__(self, script, reference):
        self.proc = subprocess.Popen(['node', os.path.join(reference, script)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True, cwd=reference)

    def ask(self, message):
        self.proc.stdin.write(json.dumps(message) + '\n')
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f'the adapter closed its output after {message["op"]}')
        return json.loads(line)

    def close(self):
        self.proc.stdin.close()
        try:
            return self.proc.wait(timeout=kExitWait)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return None


def unit_box(name, z, x=0.0, friction=0.5, restitution=0.0, mass=1.0, com=(0, 0, 0)):
    i = mass / 6
    return {'name': name, 'fixed': False, 'mass': mass, 'center_of_mass': list(com),
            'inertia': [[i, 0, 0], [0, i, 0], [0, 0, i]], 'position': [x, 0, z],
            'orientation': [1, 0, 0, 0], 'velocity': [0, 0, 0], 'angular_velocity': [0, 0, 0],
            'friction': friction, 'restitution': restitution,
            'boxes': [{'half_extents': [0.5, 0.5, 0.5], 'position': [0, 0, 0], 'orientation': [1, 0, 0, 0]}]}


def make_scene(bodies, ground=True, gravity=-G, ground_friction=0.5, damping=None):
    return {'name': 'test', 'dt': DT, 'gravity': [0, 0, gravity],
            'ground': {'normal': [0, 0, 1], 'offset': 0} if ground else None,
            'effects': {'friction': True, 'restitution': True, 'damping': damping is not None, 'gyroscopic': True},
            'damping': {'linear': damping or 0, 'angular': damping or 0},
            'bodies': bodies, 'ground_material': {'friction': ground_friction, 'restitution': 0}}


_shared = {}


def run(adapter, scene, steps, settings=None):
    """Loads the scene and steps it; the answer. One adapter process serves every scene of the
    test (each load replaces the world), so that the WebAssembly module is compiled once."""
    a = _shared.get(adapter['script'])
    if a is None:
        a = _shared[adapter['script']] = Adapter(adapter['script'], REFERENCE)
        a.ask({'op': 'hello', 'protocol': 1})
    loaded = a.ask({'op': 'load', 'settings': settings or {}, 'scene': scene})
    if not loaded.get('ok'):
        raise RuntimeError(f'load failed: {loaded}')
    reply = a.ask({'op': 'step', 'n': steps, 'state': True, 'contacts': True})
    if not reply.get('ok'):
        raise RuntimeError(f'step failed: {reply}')
    return reply


def test_hello(engine, adapter):
    a = Adapter(adapter['script'], REFERENCE)
    h = a.ask({'op': 'hello', 'protocol': 1})
    check(h.get('ok') is True and h.get('protocol') == 1, 'hello: ok, protocol 1')
    check(h.get('name') == engine, f'hello: name {h.get("name")!r} is {engine!r}')
    check(h.get('precision') == adapter['precision'], f'hello: precision {h.get("precision")} is {adapter["precision"]}')
    check(h.get('contacts') is True and h.get('timing') is True, 'hello: contacts and timing announced')
    check(isinstance(h.get('version'), str) and 'node' in h['version'], f'hello: version {h.get("version")!r}')
    settings = h.get('settings', [])
    check(len(settings) >= 5, f'hello: {len(settings)} settings')
    for s in settings:
        kind, default = s.get('kind'), s.get('default')
        good = isinstance(s.get('what'), str) and s['what'] and 'unit' in s
        if kind in ('integer', 'number'):
            good = good and s['min'] <= default <= s['max'] and (kind == 'number' or isinstance(default, int))
        elif kind == 'choice':
            good = good and default in s.get('choices', [])
        elif kind == 'boolean':
            good = good and isinstance(default, bool)
        else:
            good = False
        check(good, f'hello: setting {s.get("key")} ({kind}, default {default}) well formed')
    # Loading every default explicitly is accepted.
    r = a.ask({'op': 'load', 'settings': {s['key']: s['default'] for s in settings}, 'scene': make_scene([unit_box('b', 0.5)])})
    check(r == {'ok': True}, f'load with every default given: {r}')
    check(a.close() == 0, 'exits with status 0 at end of input')
    return settings


def test_resting_box(adapter):
    r = run(adapter, make_scene([unit_box('box', 0.5)]), 240)
    contacts = r['contacts']
    check(len(contacts) == 4, f'resting box: {len(contacts)} contacts (4: its bottom corners)')
    lo, hi = adapter['rest_depth']
    corners = {(sx * 0.5, sy * 0.5) for sx in (-1, 1) for sy in (-1, 1)}
    for c in contacts:
        check(c['a'] == 0 and c['b'] == -1, f'resting box: contact between a={c["a"]} and b={c["b"]} (0, -1)')
        check(all(abs(n - e) < 1e-6 for n, e in zip(c['normal'], (0, 0, 1))), f'resting box: normal {c["normal"]} is (0, 0, 1), from the ground toward the box')
        check(lo <= c['depth'] <= hi, f'resting box: depth {c["depth"]:.3g} in [{lo}, {hi}]')
        near = min(corners, key=lambda k: math.hypot(c['position'][0] - k[0], c['position'][1] - k[1]))
        check(math.hypot(c['position'][0] - near[0], c['position'][1] - near[1]) < 1e-4 and abs(c['position'][2] + c['depth'] / 2) < 1e-5,
              f'resting box: contact at {c["position"]} is a bottom corner, the midpoint of the overlap')
    z = r['bodies'][0]['position'][2]
    check(0.5 - hi - 1e-6 <= z <= 0.5 + 1e-6, f'resting box: centre at z = {z:.7f}')
    check(0 < r['engine_seconds'] < 10, f'engine_seconds {r["engine_seconds"]:.3g} s for 240 steps')


def test_compound_on_fixed(adapter):
    """A bar of two unit boxes (a compound, 2 kg) resting on a fixed slab whose top is at z = 1:
    every contact is between the bar (a = 1) and the slab (b = 0), none with the ground (the slab
    and the ground never move), normal (0, 0, 1), the points on the bar's bottom face."""
    slab = unit_box('slab', 0.5)
    slab.update({'fixed': True, 'boxes': [{'half_extents': [2, 2, 0.5], 'position': [0, 0, 0], 'orientation': [1, 0, 0, 0]}]})
    bar = unit_box('bar', 1.5, mass=2.0)
    bar['inertia'] = [[2 * 2 / 12, 0, 0], [0, 2 * 5 / 12, 0], [0, 0, 2 * 5 / 12]]
    bar['boxes'] = [{'half_extents': [0.5, 0.5, 0.5], 'position': [x, 0, 0], 'orientation': [1, 0, 0, 0]} for x in (-0.5, 0.5)]
    r = run(adapter, make_scene([slab, bar]), 240)
    lo, hi = adapter['rest_depth']
    contacts = r['contacts']
    check(len(contacts) == adapter['compound_contacts'], f'compound on a fixed body: {len(contacts)} contacts ({adapter["compound_contacts"]})')
    check(all(c['a'] == 1 and c['b'] == 0 for c in contacts), f'compound on a fixed body: pairs {sorted({(c["a"], c["b"]) for c in contacts})} are (1, 0)')
    check(all(max(abs(n - e) for n, e in zip(c['normal'], (0, 0, 1))) < 1e-6 for c in contacts), 'compound on a fixed body: normals (0, 0, 1)')
    check(all(abs(abs(c['position'][0]) - 0.5) < 0.5 + 1e-4 and abs(abs(c['position'][1]) - 0.5) < 1e-4
              and abs(c['position'][2] - 1) < 1e-4 for c in contacts), 'compound on a fixed body: points on the bar\'s bottom face edges')
    z = r['bodies'][1]['position'][2]
    check(1.5 - 2 * hi - 1e-6 <= z <= 1.5 + 1e-6, f'compound on a fixed body: bar at z = {z:.7f}')
    check(r['bodies'][0]['position'] == [0, 0, 0.5] and r['bodies'][0]['velocity'] == [0, 0, 0], f'the fixed body stays: {r["bodies"][0]}')


def test_free_fall(adapter):
    """No ground: semi-implicit Euler with s substeps of h = dt / s gives after N = n s substeps
    v = v0 + g N h, x = x0 + v0 N h + g h^2 N (N + 1) / 2."""
    box = unit_box('box', 10)
    box['velocity'] = [1.0, 0, 2.0]
    n = 240
    r = run(adapter, make_scene([box], ground=False), n)
    b = r['bodies'][0]
    h, N = DT / adapter['substeps'], n * adapter['substeps']
    x = [1.0 * n * DT, 0, 10 + 2.0 * n * DT - G * h * h * N * (N + 1) / 2]
    v = [1.0, 0, 2.0 - G * n * DT]
    err = max(abs(p - e) for p, e in zip(b['position'], x))
    check(err < adapter['fall_tol'], f'free fall: position off the discrete path by {err:.2g} m (< {adapter["fall_tol"]})')
    verr = max(abs(p - e) for p, e in zip(b['velocity'], v))
    check(verr < adapter['fall_tol'] * 10, f'free fall: velocity off by {verr:.2g} m/s')
    check(abs(r['time'] - n * DT) < 1e-9, f'time {r["time"]} is {n * DT}')


def test_offset_centre_of_mass(adapter):
    """Zero gravity, centre of mass 0.2 m off the frame's origin, spinning about z at 1 rad/s while
    it drifts: the centre of mass moves in a straight line, the frame circles it."""
    box = unit_box('box', 5, com=(0.2, 0, 0))
    box['velocity'] = [0.5, 0, 0]
    box['angular_velocity'] = [0, 0, 1.0]
    n = 240
    r = run(adapter, make_scene([box], ground=False, gravity=0), n)
    b = r['bodies'][0]
    t = n * DT
    com = [0.2 + 0.5 * t, 0, 5]
    angle = 1.0 * t
    frame = [com[0] - 0.2 * math.cos(angle), -0.2 * math.sin(angle), 5]
    err = max(abs(p - e) for p, e in zip(b['position'], frame))
    tol = adapter['com_tol']
    check(err < tol, f'offset centre of mass: body frame at {b["position"]}, expected {frame} (off {err:.2g} m)')
    verr = max(abs(p - e) for p, e in zip(b['velocity'], [0.5, 0, 0]))
    check(verr < tol, f'offset centre of mass: reported velocity {b["velocity"]} is the centre of mass\'s (0.5, 0, 0)')
    werr = max(abs(p - e) for p, e in zip(b['angular_velocity'], [0, 0, 1]))
    check(werr < 1e-4, f'offset centre of mass: angular velocity {b["angular_velocity"]} (0, 0, 1)')
    q = b['orientation']
    qe = [math.cos(angle / 2), 0, 0, math.sin(angle / 2)]
    qerr = min(max(abs(p - e) for p, e in zip(q, qe)), max(abs(p + e) for p, e in zip(q, qe)))
    check(qerr < 1e-4, f'offset centre of mass: orientation {q} is [w, x, y, z] = {qe}')


def test_friction_law(adapter):
    """A box sliding at 2 m/s on the ground: box friction 0.25, ground 1, so the pair's
    mu = sqrt(0.25 * 1) = 0.5 and it stops after v^2 / (2 mu g) = 0.408 m (max would give
    0.204 m, the mean 0.326 m)."""
    box = unit_box('box', 0.5, friction=0.25)
    box['velocity'] = [2.0, 0, 0]
    r = run(adapter, make_scene([box], ground_friction=1.0), 240)
    x = r['bodies'][0]['position'][0]
    expected = 2.0 ** 2 / (2 * 0.5 * G)
    check(abs(x - expected) < 0.03 * expected, f'friction sqrt(mu_a mu_b): slid {x:.4f} m, expected {expected:.4f} m (3 %)')


def quat_matrix(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def test_gyroscopic(adapter):
    """Zero gravity, a box of principal inertia (0.1, 0.2, 0.3) spinning at (1, 1, 0) rad/s:
    with the gyroscopic term its world angular momentum (0.1, 0.2, 0) stays and its angular
    velocity turns; without it (w x I w left out) the angular velocity stays (1, 1, 0)."""
    for gyroscopic in (True, False):
        if not gyroscopic and not adapter['gyroscopic_switch']:
            print('note  the gyroscopic term cannot be turned off in this engine')
            continue
        box = unit_box('box', 5)
        box['inertia'] = [[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.3]]
        box['boxes'][0]['half_extents'] = [0.8, 0.5, 0.2]
        box['angular_velocity'] = [1.0, 1.0, 0]
        scene = make_scene([box], ground=False, gravity=0)
        scene['effects']['gyroscopic'] = gyroscopic
        b = run(adapter, scene, 240)['bodies'][0]
        R = quat_matrix(b['orientation'])
        w = b['angular_velocity']
        w_body = [sum(R[j][i] * w[j] for j in range(3)) for i in range(3)]
        L_body = [0.1 * w_body[0], 0.2 * w_body[1], 0.3 * w_body[2]]
        L = [sum(R[i][j] * L_body[j] for j in range(3)) for i in range(3)]
        if gyroscopic:
            err = max(abs(p - e) for p, e in zip(L, [0.1, 0.2, 0]))
            check(err < 5e-4, f'gyroscopic on: angular momentum {L} stays (0.1, 0.2, 0) (off {err:.2g})')
        else:
            err = max(abs(p - e) for p, e in zip(w, [1, 1, 0]))
            check(err < 1e-4, f'gyroscopic off: angular velocity {w} stays (1, 1, 0) (off {err:.2g})')


def test_restitution(adapter):
    """A box (e = 0.5) dropped from 1 m onto the ground (e = 0): the pair's max(e_a, e_b) = 0.5
    sends it back up e^2 = 0.25 m."""
    box = unit_box('box', 1.5, restitution=0.5)
    run(adapter, make_scene([box]), 1)  # loads the scene; the first step is part of the fall
    a = _shared[adapter['script']]
    peak, rising = 0.0, False
    for _ in range(239):
        b = a.ask({'op': 'step', 'n': 1, 'state': True})['bodies'][0]
        rising = rising or b['velocity'][2] > 0
        if rising:
            peak = max(peak, b['position'][2] - 0.5)
    e = math.sqrt(peak / 1.0)
    lo, hi = adapter['bounce_e']
    check(lo <= e <= hi, f'restitution max(e_a, e_b) = 0.5: rebound {peak:.4f} m, e = {e:.3f} in [{lo}, {hi}]')


def test_damping(adapter):
    """Zero gravity, damping 0.5/s on a box moving at 1 m/s: after 1 s, exp(-0.5) = 0.607 m/s
    to first order in dt (each engine's discrete factor differs from it by about c^2 dt / 2)."""
    box = unit_box('box', 5)
    box['velocity'] = [1.0, 0, 0]
    box['angular_velocity'] = [0, 0, 1.0]
    r = run(adapter, make_scene([box], ground=False, gravity=0, damping=0.5), 240)
    b = r['bodies'][0]
    expected = math.exp(-0.5)
    check(abs(b['velocity'][0] - expected) < 1e-3, f'damping: velocity {b["velocity"][0]:.5f} m/s, expected {expected:.5f}')
    check(abs(b['angular_velocity'][2] - expected) < 1e-3, f'damping: angular velocity {b["angular_velocity"][2]:.5f} rad/s, expected {expected:.5f}')


def test_wire(adapter):
    """A box hangs from a horizontal wire 2 m long by the middle of its top face, pushed at
    1.5 m/s along it from the middle: frictionless, it reaches the end (1 m) after 0.67 s and stops
    there; its anchor never leaves the wire."""
    box = unit_box('box', 1.5)
    box['velocity'] = [1.5, 0, 0]
    box['wire'] = {'from': [-1, 0, 2], 'to': [1, 0, 2], 'anchor': [0, 0, 0.5]}
    r = run(adapter, make_scene([box], ground=False), 240)
    b = r['bodies'][0]
    w, x, y, z = b['orientation']
    # the anchor (0, 0, 0.5) in the world: position + R anchor (R's third column times 0.5)
    anchor = [b['position'][0] + 0.5 * (2 * (x * z + w * y)),
              b['position'][1] + 0.5 * (2 * (y * z - w * x)),
              b['position'][2] + 0.5 * (1 - 2 * (x * x + y * y))]
    check(abs(anchor[1]) < 1e-3 and abs(anchor[2] - 2) < 1e-3, f'wire: anchor {anchor} stays on the wire (y 0, z 2)')
    check(abs(anchor[0] - 1) < 0.01, f'wire: anchor stopped at the end x = 1 (at {anchor[0]:.4f})')

    # A slanted wire (rising 1 m over 3) and a body turned 30 degrees about z, pushed mostly
    # across the wire: the anchor stays on the wire's line (the joints' axes are placed in the
    # right frames) and slides down to the low end, which stops it (MuJoCo's soft limit lets it
    # pass by 1.8 mm at that speed, Jolt's anchor leaves the line by 0.2 mm at the stop).
    c, s_ = math.cos(math.pi / 12), math.sin(math.pi / 12)
    box = unit_box('box', 2.0)
    box['orientation'] = [c, 0, 0, s_]
    box['velocity'] = [0.5, -0.5, 0.2]
    box['wire'] = {'from': [-1, -1, 2], 'to': [1, 1, 3], 'anchor': [0, 0, 0.5]}
    b = run(adapter, make_scene([box], ground=False), 240)['bodies'][0]
    R = quat_matrix(b['orientation'])
    anchor = [b['position'][i] + 0.5 * R[i][2] for i in range(3)]
    u = [2 / 3, 2 / 3, 1 / 3]
    rel = [anchor[0] + 1, anchor[1] + 1, anchor[2] - 2]
    along = sum(r * k for r, k in zip(rel, u))
    off = math.sqrt(max(sum(r * r for r in rel) - along * along, 0))
    check(off < 5e-4, f'slanted wire: anchor {off:.2g} m off the line')
    check(abs(along) < 5e-3, f'slanted wire: anchor slid to the low end ({along:.4f} m along the wire)')


def test_stack(adapter):
    """Five unit boxes stacked exactly, 5 s: each engine settles where its contact model puts it."""
    r = run(adapter, make_scene([unit_box(f'box{i}', 0.5 + i) for i in range(5)]), 1200)
    top = r['bodies'][4]['position']
    lo, hi = adapter['stack_top']
    check(lo <= top[2] <= hi, f'stack of 5: top at z = {top[2]:.6f} in [{lo}, {hi}]')
    drift = math.hypot(top[0], top[1])
    check(drift < 0.005, f'stack of 5: top drifted {drift:.2g} m sideways')
    pairs = {(c['a'], c['b']) for c in r['contacts']}
    check(pairs == {(0, -1), (1, 0), (2, 1), (3, 2), (4, 3)} or pairs == {(0, -1), (0, 1), (1, 2), (2, 3), (3, 4)},
          f'stack of 5: touching pairs {sorted(pairs)}')
    check(len(r['contacts']) == 20, f'stack of 5: {len(r["contacts"])} contacts (4 per interface)')
    for c in r['contacts']:
        if c['b'] >= 0:
            upper = max(c['a'], c['b'])
            sign = 1 if c['a'] == upper else -1
            check(abs(c['normal'][2] - sign) < 1e-4, f'stack of 5: normal {c["normal"]} points from b={c["b"]} toward a={c["a"]}')
            break


def max_depth(reply):
    return max(c['depth'] for c in reply['contacts'])


# One setting per engine whose effect is known, given at load: it must change the run as the
# engine's model says (a setting passed through but not applied would leave it unchanged).
def setting_jolt(adapter):
    """A box started 1 cm inside the ground: Jolt leaves penetration_slop (0.02 m) uncorrected,
    so it stays 1 cm deep; with a slop of 1 mm it is pushed out to 1 mm."""
    scene = make_scene([unit_box('box', 0.49)])
    default, tight = max_depth(run(adapter, scene, 240)), max_depth(run(adapter, scene, 240, {'penetration_slop': 0.001}))
    check(abs(default - 0.01) < 1e-4 and abs(tight - 0.001) < 1e-4,
          f'penetration_slop: depth {default:.5f} m at the default 0.02, {tight:.5f} m at 0.001 (0.01, 0.001)')


def setting_rapier(adapter):
    """A stack of 5 after 2 s: a contact spring four times as stiff (120 Hz instead of 30) sinks
    the top box by far less (the soft contact's compression goes as 1 / frequency^2)."""
    scene = make_scene([unit_box(f'box{i}', 0.5 + i) for i in range(5)])
    sink = [4.5 - run(adapter, scene, 480, s)['bodies'][4]['position'][2] for s in ({}, {'contact_natural_frequency': 120})]
    check(sink[1] < sink[0] / 4, f'contact_natural_frequency: stack sinks {sink[0] * 1e3:.2f} mm at 30 Hz, {sink[1] * 1e3:.2f} mm at 120 Hz (< a quarter)')


def setting_mujoco(adapter):
    """A resting box: halving solref's time constant makes the soft contact four times as stiff
    (stiffness ~ 1 / timeconst^2), so it sinks a quarter as deep."""
    scene = make_scene([unit_box('box', 0.5)])
    default, half = max_depth(run(adapter, scene, 240)), max_depth(run(adapter, scene, 240, {'solref_timeconst': 0.01}))
    check(0.22 < half / default < 0.28, f'solref_timeconst: depth {default:.3g} m at 0.02 s, {half:.3g} m at 0.01 s (ratio {half / default:.3f}, 1/4)')


SETTING_CHECKS = {'jolt': setting_jolt, 'rapier': setting_rapier, 'mujoco-wasm': setting_mujoco}


def test_bad_input(adapter, settings):
    a = Adapter(adapter['script'], REFERENCE)
    check(a.ask({'op': 'hello', 'protocol': 2}).get('ok') is False, 'hello with protocol 2: ok false')
    r = a.ask({'op': 'step', 'n': 1})
    check(r.get('ok') is False and 'load' in r.get('error', ''), f'step before load: {r}')
    numeric = next(s for s in settings if s['kind'] == 'integer')
    r = a.ask({'op': 'load', 'settings': {numeric['key']: numeric['max'] + 1}, 'scene': make_scene([unit_box('b', 0.5)])})
    check(r.get('ok') is False and numeric['key'] in r.get('error', ''), f'{numeric["key"]} above its max: {r}')
    r = a.ask({'op': 'load', 'settings': {'no_such_setting': 1}, 'scene': make_scene([unit_box('b', 0.5)])})
    check(r.get('ok') is False and 'no_such_setting' in r.get('error', ''), f'unknown setting: {r}')
    bad = make_scene([unit_box('b', 0.5)])
    bad['bodies'][0]['mass'] = -1
    r = a.ask({'op': 'load', 'scene': bad})
    check(r.get('ok') is False and 'bodies[0].mass' in r.get('error', ''), f'negative mass: {r}')
    r = a.ask({'op': 'frobnicate'})
    check(r.get('ok') is False, f'unknown op: {r}')
    a.proc.stdin.write('this is not json\n')
    a.proc.stdin.flush()
    r = json.loads(a.proc.stdout.readline())
    check(r.get('ok') is False, f'a line that is not JSON: {r}')
    r = a.ask({'op': 'load', 'scene': make_scene([unit_box('b', 0.5)])})
    check(r == {'ok': True}, f'still serving after errors: {r}')
    r = a.ask({'op': 'step', 'n': 0})
    check(r.get('ok') is False, f'step n = 0: {r}')
    r = a.ask({'op': 'quit'})
    check(r == {'ok': True}, 'quit answers ok')
    try:
        status = a.proc.wait(timeout=kExitWait)
    except subprocess.TimeoutExpired:
        a.proc.kill()
        status = None
    check(status == 0, f'quit exits with status 0 ({status})')


def main():
    global REFERENCE
    if len(sys.argv) != 3 or sys.argv[1] not in ENGINES:
        sys.exit(__doc__)
    engine, REFERENCE = sys.argv[1], os.path.abspath(sys.argv[2])
    if not os.path.isdir(os.path.join(REFERENCE, 'node_modules')):
        print(f'{REFERENCE}/node_modules is missing: run scripts/install-deps (npm ci in reference/)')
        sys.exit(1)
    adapter = ENGINES[engine]
    start = time.time()
    settings = test_hello(engine, adapter)
    test_resting_box(adapter)
    test_compound_on_fixed(adapter)
    test_free_fall(adapter)
    test_offset_centre_of_mass(adapter)
    test_friction_law(adapter)
    test_gyroscopic(adapter)
    test_restitution(adapter)
    test_damping(adapter)
    test_wire(adapter)
    test_stack(adapter)
    SETTING_CHECKS[engine](adapter)
    test_bad_input(adapter, settings)
    for a in _shared.values():
        check(a.close() == 0, 'the shared adapter exits with status 0 at end of input')
    print(f'{engine}: {len(failures)} failures, {time.time() - start:.1f} s')
    sys.exit(1 if failures else 0)


if __name__ == '__main__':
    main()
