#!/usr/bin/env python3
"""An engine that breaks docs/engine-protocol.md in one way, for the tests of boxpile's answers.

    broken_engine.py MODE [PIDFILE]

It answers hello and load correctly and keeps every body where the scene put it, until MODE
breaks it: exit-at-step-3 (exits with status 3 at the third step, after a line on stderr),
garbage (prints a line that is no JSON at step 2), wrong-count (one body too few at step 2),
nan (a NaN position at step 2), sleep (never answers step 1), not-ok (answers step 2 with
ok: false), bad-version (says protocol 2 in its hello). One mode keeps the protocol: timed
(announces timing and reports engine_seconds of exactly SECONDS_PER_STEP a step, whatever the
wall time, so that a test can tell the reported time from the round trip's). With PIDFILE it writes its process id
there first, so that a test can check it is gone afterwards.
"""
import json
import os
import sys
import time

mode = sys.argv[1]
if len(sys.argv) > 2:
    with open(sys.argv[2], "w") as f:
        f.write(str(os.getpid()))

SECONDS_PER_STEP = 0.5

bodies = []
steps = 0
dt = 0.0
for line in sys.stdin:
    request = json.loads(line)
    op = request["op"]
    if op == "hello":
        reply = {"ok": True, "protocol": 2 if mode == "bad-version" else 1, "name": "broken", "version": mode,
                 "precision": "float64", "contacts": False, "timing": mode == "timed"}
    elif op == "load":
        scene = request["scene"]
        dt = scene["dt"]
        bodies = [{"position": b["position"], "orientation": b["orientation"], "velocity": [0, 0, 0],
                   "angular_velocity": [0, 0, 0]} for b in scene["bodies"]]
        reply = {"ok": True}
    elif op == "step":
        n = request.get("n", 1)
        steps += n
        reply = {"ok": True, "time": steps * dt, "bodies": bodies}
        if mode == "timed":
            reply["engine_seconds"] = SECONDS_PER_STEP * n
        if mode == "exit-at-step-3" and steps == 3:
            sys.stderr.write("broken engine: giving up at step 3\n")
            sys.stderr.flush()
            sys.exit(3)
        if mode == "sleep":
            time.sleep(3600)
        if steps == 2:
            if mode == "garbage":
                sys.stdout.write("this is \x01 not JSON\n")
                sys.stdout.flush()
                continue
            if mode == "wrong-count":
                reply["bodies"] = bodies[1:]
            if mode == "nan":
                reply["bodies"] = [dict(bodies[0], position=[float("nan"), 0, 0])] + bodies[1:]
            if mode == "not-ok":
                reply = {"ok": False, "error": "the solver diverged"}
    else:
        reply = {"ok": True}
    sys.stdout.write(json.dumps(reply) + "\n")
    sys.stdout.flush()
    if op == "quit":
        break
