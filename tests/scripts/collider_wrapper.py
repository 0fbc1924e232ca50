#!/usr/bin/env python3
"""A collider for `boxpile conform` made from another one (usually `boxpile contacts --serve`)
with one mistake or one limitation added on purpose, for the tests of docs/conform.md:

  collider_wrapper.py [--float32] [--depth-scale F] [--flip-edge-edge] [--point-offset F] -- CMD...

--float32         every number of the query rounded to single precision before CMD sees it, and
                  every number of the answer after: a collider that reads, computes and writes floats
--depth-scale F   every depth times F (0.9: 10% short)
--flip-edge-edge  the normals of an edge-edge answer reversed (the kind read from the feature id)
--point-offset F  every point moved F times its depth along its normal

One query per input line, one answer per output line, flushed, as the protocol asks."""
import argparse
import json
import struct
import subprocess
import sys

EDGE_EDGE = 2  # FeatureKind::EdgeEdge, the top byte of a feature id (sim/collision/contact.hpp)


def float32(x):
    if isinstance(x, float) or (isinstance(x, int) and not isinstance(x, bool)):
        return struct.unpack("f", struct.pack("f", float(x)))[0]
    if isinstance(x, list):
        return [float32(v) for v in x]
    if isinstance(x, dict):
        return {k: (v if k in ("name", "feature") else float32(v)) for k, v in x.items()}
    return x


def altered(answer, args):
    contacts = answer["contacts"]
    edge_edge = bool(contacts) and (contacts[0].get("feature", 0) >> 24) == EDGE_EDGE
    for c in contacts:
        c["depth"] *= args.depth_scale
        if args.flip_edge_edge and edge_edge:
            c["normal"] = [-v for v in c["normal"]]
        if args.point_offset:
            c["position"] = [p + args.point_offset * c["depth"] * n for p, n in zip(c["position"], c["normal"])]
    return float32(answer) if args.float32 else answer


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--float32", action="store_true")
    parser.add_argument("--depth-scale", type=float, default=1.0)
    parser.add_argument("--flip-edge-edge", action="store_true")
    parser.add_argument("--point-offset", type=float, default=0.0)
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    inner = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    for line in sys.stdin:
        if not line.strip():
            continue
        query = json.loads(line)
        inner.stdin.write(json.dumps(float32(query) if args.float32 else query) + "\n")
        inner.stdin.flush()
        answer = json.loads(inner.stdout.readline())
        print(json.dumps(altered(answer, args)), flush=True)
    inner.stdin.close()
    return inner.wait()


if __name__ == "__main__":
    sys.exit(main())
