#!/usr/bin/env python3
"""Write the OpenSees model of an adjoin building-pair scene (README.md here).

    python3 bench/opensees/pair_to_tcl.py bench/opensees/pair.toml OUT [--refine N]
        [--slider-stiffness K] [--steps N] [--no-recorders]

reads the scene (the keys of pair.toml only: two shear buildings with bilinear or elastic
storeys and modal damping, friction links, a PEER AT2 record in g, solver.h and t_end) and
writes OUT/pair.tcl and OUT/ground.txt (the record, one value a line). `OpenSees OUT/pair.tcl`
then writes OUT/disp.out (t and every floor's displacement relative to the ground, A's floors
1..n then B's), OUT/storeys.out (t and every storey's force, A's then B's) and
OUT/links.out (t and each friction link's force F for the deformation x_B - x_A: adjoin's
link force q, for the stroke x_A - x_B, is -F), all at the scene's step h whatever --refine.

--refine N       OpenSees's step is h/N (the output rows stay at h: recorder -dT h)
--slider-stiffness K   the friction links' elastic stiffness [N/m] (OpenSees regularises
                 the Coulomb slider as an elastic-perfectly-plastic spring; default 1e11)
--steps N        analyse N steps of h/refine instead of t_end/h x refine (1: the start-up)
--no-recorders   write nothing (the solve alone, for timing)
Python 3.11 or later (tomllib); nothing outside the standard library.
"""
import argparse
import math
import pathlib
import sys
import tomllib

GRAVITY = 9.80665  # m/s^2, adjoin's kStandardGravity
FIRST_NODE = {"A": 1, "B": 1001}  # floor i of building X is node FIRST_NODE[X] + i (i = 0: the ground)
STOREY_TAG = {"A": 1, "B": 1001}  # storey i of building X is element STOREY_TAG[X] + i - 1
LINK_TAG = 5001


def fail(message):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def expect_keys(table, allowed, where):
    for key in table:
        if key not in allowed:
            fail(f"{where}: key {key} is not supported by this generator (keys: {', '.join(sorted(allowed))})")


def building_of(scene, name, path):
    b = scene.get("building", {}).get(name)
    if b is None:
        fail(f"{path}: building.{name}: missing")
    where = f"{path}: building.{name}"
    expect_keys(b, {"storeys", "mass", "stiffness", "damping", "hysteresis"}, where)
    damping = b.get("damping", {})
    if damping.get("model") != "modal":
        fail(f"{where}.damping: expected {{ model = \"modal\", ratio = ... }}")
    hysteresis = b.get("hysteresis", {"model": "elastic"})
    if hysteresis.get("model") not in ("bilinear", "elastic"):
        fail(f"{where}.hysteresis.model: expected \"bilinear\" or \"elastic\"")
    return {
        "n": int(b["storeys"]),
        "mass": float(b["mass"]),
        "k": float(b["stiffness"]),
        "zeta": float(damping["ratio"]),
        "bilinear": hysteresis["model"] == "bilinear",
        "fy": float(hysteresis.get("yield_force", 0.0)),
        "b": float(hysteresis.get("hardening", 0.0)),
    }


def read_at2(path):
    """A PEER AT2 record in g: (dt, accelerations)."""
    lines = path.read_text().splitlines()
    if "UNITS OF G" not in lines[2].upper():
        fail(f"{path}:3: expected a PEER AT2 header in units of g")
    header = lines[3].replace(",", " ").replace("=", " ").split()
    npts = int(header[header.index("NPTS") + 1])
    dt = float(header[header.index("DT") + 1])
    values = [float(v) for line in lines[4:] for v in line.split()]
    if len(values) != npts:
        fail(f"{path}:4: NPTS = {npts} but {len(values)} values follow")
    return dt, values


def read_scene(path):
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    expect_keys(scene, {"name", "model", "building", "link", "ground", "solver", "output"}, str(path))
    if scene.get("model", {}).get("units") != "SI":
        fail(f"{path}: model.units: expected \"SI\"")
    links = []
    for i, link in enumerate(scene.get("link", []), 1):
        expect_keys(link, {"floors", "type", "slip_force"}, f"{path}: link {i}")
        if link.get("type") != "friction":
            fail(f"{path}: link {i}.type: expected \"friction\"")
        links.append((int(link["floors"][0]), int(link["floors"][1]), float(link["slip_force"])))
    ground = scene["ground"]
    expect_keys(ground, {"source", "file"}, f"{path}: ground")
    solver = scene["solver"]
    expect_keys(solver, {"h", "t_end"}, f"{path}: solver")
    return {
        "A": building_of(scene, "A", path),
        "B": building_of(scene, "B", path),
        "links": links,
        "record": read_at2(path.parent / ground["file"]),
        "h": float(solver["h"]),
        "t_end": float(solver["t_end"]),
    }


def storeys_tcl(name, b):
    """Nodes, masses and zeroLength storeys of building `name` (its ground node fixed)."""
    first = FIRST_NODE[name]
    out = [f"# building {name}: {b['n']} floors of {b['mass']:.9g} kg, storeys k = {b['k']:.9g} N/m"]
    for i in range(b["n"] + 1):
        out.append(f"node {first + i} 0.0")
    out.append(f"fix {first} 1")
    for i in range(1, b["n"] + 1):
        out.append(f"mass {first + i} {b['mass']!r}")
    material = STOREY_TAG[name]
    if b["bilinear"]:  # kinematic hardening, as adjoin's: b k d + (1 - b) k z
        out.append(f"uniaxialMaterial Steel01 {material} {b['fy']!r} {b['k']!r} {b['b']!r}")
    else:
        out.append(f"uniaxialMaterial Elastic {material} {b['k']!r}")
    for i in range(1, b["n"] + 1):
        out.append(f"element zeroLength {STOREY_TAG[name] + i - 1} {first + i - 1} {first + i} -mat {material} -dir 1")
    return out


def recorder_tcl(m, d, node_list, storey_list, link_list):
    """Floors' displacements, storeys' and links' forces at every h from t = 0 (record: t = 0)."""
    every = f"-time -precision 12 -dT {m['h']!r}"
    out = [f"recorder Node -file {d / 'disp.out'} {every} -node {node_list} -dof 1 disp",
           f"recorder Element -file {d / 'storeys.out'} {every} -ele {storey_list} basicForce"]
    if link_list:
        out.append(f"recorder Element -file {d / 'links.out'} {every} -ele {link_list} basicForce")
    return out + ["record"]  # the t = 0 row; the next one at t = h (the recorders' -dT)


def links_tcl(links, slider_k):
    """Each friction link: a zeroLength from floor i of A to floor j of B (deformation x_B - x_A)."""
    out = []
    for i, (fa, fb, slip) in enumerate(links):
        tag = LINK_TAG + i
        out.append(f"uniaxialMaterial ElasticPP {tag} {slider_k!r} {slip / slider_k!r}")
        out.append(f"element zeroLength {tag} {FIRST_NODE['A'] + fa} {FIRST_NODE['B'] + fb} -mat {tag} -dir 1")
    return out


def analysis_tcl(steps, dt):
    """Newmark average acceleration (adjoin's trapezoidal rule), Newton, a banded solver.

    A step where Newton fails (it can cycle between a slider's stick and slip states) is
    retried as OpenSees users do: other algorithms on the same step, then 4 and 16 sub-steps;
    the count of retried steps goes to stderr."""
    return [
        "constraints Plain",
        "numberer Plain",  # A's floors, then B's: the links' band (n) holds each building's dense modal block
        "system BandGeneral",
        "test NormDispIncr 1.0e-10 50",
        "algorithm Newton",
        "integrator Newmark 0.5 0.25",
        "analysis Transient",
        f"set steps {steps}",
        f"set dt {dt!r}",
        "set retried 0",
        "proc retry {dt} {",
        "  foreach algo {{NewtonLineSearch 0.8} {KrylovNewton} {ModifiedNewton -initial}} {",
        "    algorithm {*}$algo",
        "    set ok [analyze 1 $dt]",
        "    algorithm Newton",
        "    if {$ok == 0} { return 0 }",
        "  }",
        "  foreach n {4 16} {",
        "    if {[analyze $n [expr {$dt / $n}]] == 0} { return 0 }",
        "  }",
        "  return -1",
        "}",
        "set done 0",
        "while {$done < $steps} {",
        "  if {[analyze [expr {$steps - $done}] $dt] == 0} { break }",
        "  incr retried",
        "  if {[retry $dt] != 0} { puts stderr \"error: analyze failed at t = [getTime]\"; exit 3 }",
        "  set done [expr {round([getTime] / $dt)}]",
        "}",
        "puts stderr \"steps retried: $retried\"",
        "wipe",  # closes the recorders' files
    ]


def model_tcl(m, out_dir, refine, slider_k, steps, recorders):
    a, b = m["A"], m["B"]
    if a["zeta"] != b["zeta"]:
        fail("building.A/B.damping.ratio: this generator needs one ratio for both (OpenSees's modalDamping factor)")
    record_dt, _ = m["record"]
    dt = m["h"] / refine
    if steps is None:
        steps = round(m["t_end"] / m["h"]) * refine
    modes = a["n"] + b["n"]
    node_list = " ".join(str(FIRST_NODE[x] + i) for x, bx in (("A", a), ("B", b)) for i in range(1, bx["n"] + 1))
    storey_list = " ".join(str(STOREY_TAG[x] + i - 1) for x, bx in (("A", a), ("B", b)) for i in range(1, bx["n"] + 1))
    link_list = " ".join(str(LINK_TAG + i) for i in range(len(m["links"])))
    d = out_dir.resolve()
    lines = ["# Written by bench/opensees/pair_to_tcl.py from an adjoin scene: do not edit.",
             "wipe", "model basic -ndm 1 -ndf 1"]
    lines += storeys_tcl("A", a) + storeys_tcl("B", b)
    lines += [
        "# Modal damping of every mode of each building alone: the eigenvectors of the two",
        "# uncoupled buildings (all of them: -fullGenLapack), taken before the links join them.",
        f"eigen -fullGenLapack {modes}",
        f"modalDamping {a['zeta']!r}",
        f"# Friction links: elastic-perfectly-plastic springs of stiffness {slider_k:.6g} N/m",
        "# (OpenSees's regularised Coulomb slider; adjoin's stick is exact).",
    ]
    lines += links_tcl(m["links"], slider_k)
    lines += [
        f"timeSeries Path 1 -dt {record_dt!r} -filePath {d / 'ground.txt'} -factor {GRAVITY!r}",
        "pattern UniformExcitation 1 1 -accel 1",
    ]
    if recorders:
        lines += recorder_tcl(m, d, node_list, storey_list, link_list)
    lines += analysis_tcl(steps, dt)
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", type=pathlib.Path)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--refine", type=int, default=1)
    parser.add_argument("--slider-stiffness", type=float, default=1e11)
    parser.add_argument("--steps", type=int, default=None)
    parser.add_argument("--no-recorders", action="store_true")
    args = parser.parse_args()
    if args.refine < 1:
        fail("--refine: expected an integer >= 1")
    if not args.slider_stiffness > 0 or not math.isfinite(args.slider_stiffness):
        fail("--slider-stiffness: expected a positive stiffness in N/m")
    model = read_scene(args.scene)
    args.out.mkdir(parents=True, exist_ok=True)
    _, accel = model["record"]
    (args.out / "ground.txt").write_text("".join(f"{v!r}\n" for v in accel))
    tcl = model_tcl(model, args.out, args.refine, args.slider_stiffness, args.steps, not args.no_recorders)
    (args.out / "pair.tcl").write_text(tcl)


if __name__ == "__main__":
    main()
