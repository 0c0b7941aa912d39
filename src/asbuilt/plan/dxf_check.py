#!/usr/bin/python3
"""Independent check of asbuilt's plan.dxf with ezdxf (Debian python3-ezdxf).

usage: dxf_check.py plan.dxf plan.json

Loads the DXF, runs ezdxf's audit (must report no errors), checks units and
layers, and reads back every wall (inner face LINE on WALLS) and every
DIMENSION's measurement against plan.json to 1 mm. Prints one line per
problem and exits 1 if there was any; prints a summary and exits 0 otherwise.
"""
import json
import math
import sys

import ezdxf


def main():
    dxf_path, plan_path = sys.argv[1], sys.argv[2]
    problems = []
    doc = ezdxf.readfile(dxf_path)
    auditor = doc.audit()
    for e in auditor.errors:
        problems.append(f"audit error: {e.message}")
    if doc.dxfversion != "AC1015":
        problems.append(f"version {doc.dxfversion}, expected AC1015")
    if doc.header.get("$INSUNITS") != 6:
        problems.append(f"$INSUNITS {doc.header.get('$INSUNITS')}, expected 6 (metres)")
    for layer in ("WALLS", "DOORS", "WINDOWS", "DIMENSIONS", "TEXT"):
        if layer not in doc.layers:
            problems.append(f"missing layer {layer}")
    plan = json.load(open(plan_path))
    msp = doc.modelspace()

    lines = [e for e in msp.query('LINE[layer=="WALLS"]')]
    used = set()
    for i, w in enumerate(plan["walls"]):
        found = False
        for k, l in enumerate(lines):
            if k in used:
                continue
            s, t = l.dxf.start, l.dxf.end
            if (math.dist((s.x, s.y), w["start"]) < 1e-3 and math.dist((t.x, t.y), w["end"]) < 1e-3):
                used.add(k)
                found = True
                break
        if not found:
            problems.append(f"wall {i} {w['start']} -> {w['end']} not found as a WALLS line")

    expected = [math.dist(w["start"], w["end"]) for w in plan["walls"]]
    expected += [math.dist(o["start"], o["end"]) for o in plan.get("openings", [])]
    dims = list(msp.query("DIMENSION"))
    measured = sorted(d.get_measurement() for d in dims)
    for d in dims:
        if d.dxf.layer != "DIMENSIONS":
            problems.append(f"dimension on layer {d.dxf.layer}")
        if d.get_geometry_block() is None:
            problems.append(f"dimension {d.dxf.handle} has no geometry block")
    if len(measured) != len(expected):
        problems.append(f"{len(measured)} dimensions, expected {len(expected)}")
    else:
        for m, e in zip(measured, sorted(expected)):
            if abs(m - e) > 1e-3:
                problems.append(f"dimension measures {m:.4f} m, expected {e:.4f} m")
    n_hatch = len(msp.query('HATCH[layer=="WALLS"]'))
    n_arcs = len(msp.query('ARC[layer=="DOORS"]'))
    doors = sum(1 for o in plan.get("openings", []) if o["kind"] == "door")
    if n_arcs != doors:
        problems.append(f"{n_arcs} door swing arcs, expected {doors}")
    if n_hatch == 0:
        problems.append("no wall hatches")
    if not msp.query('TEXT[layer=="TEXT"]'):
        problems.append("no room text")

    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"ok: {len(plan['walls'])} walls, {len(dims)} dimensions, {n_hatch} hatches, "
          f"audit fixes {len(auditor.fixes)}, errors {len(auditor.errors)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
