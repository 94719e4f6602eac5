#!/usr/bin/env python3
"""Errors of adjoin and OpenSees runs of pair.toml against a fine reference (README.md here).

    python3 bench/opensees/compare.py REF RUN...

REF is an `adjoin run` directory of the scene at h/N with `--set output.every=N` (rows on the
scene's grid h). Each RUN is an `adjoin run` directory (summary.json, timeseries.csv) or an
OpenSees output directory of pair_to_tcl.py (pair.tcl, disp.out, storeys.out, links.out), on
the grid h. Prints, per run: the largest error of either roof's displacement history, of a
peak storey drift and of a final (t_end) storey drift [m], and the plastic work and the
friction links' dissipated energy [J] with their relative errors. The reference's peaks are
its own (refined between its samples); a run's are the largest |drift| at its samples, and for
adjoin also its summary's refined peaks. Standard library only.
"""
import csv
import json
import pathlib
import re
import sys


def fail(message):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def scene_numbers(tcl):
    """Storeys, stiffness, yield force and hardening of A and B from a written pair.tcl."""
    text = tcl.read_text()
    laws = {int(m[0]): (float(m[1]), float(m[2]), float(m[3]))
            for m in re.findall(r"uniaxialMaterial Steel01 (\d+) (\S+) (\S+) (\S+)", text)}
    return {"A": laws.get(1), "B": laws.get(1001)}


class Run:
    """Floors' displacements x[name][floor-1][step], storey forces (OpenSees) and summaries."""

    def __init__(self, path, h):
        self.path = path
        if (path / "summary.json").exists():
            self.kind = "adjoin"
            self._read_adjoin(h)
        elif (path / "disp.out").exists():
            self.kind = "OpenSees"
            self._read_opensees(h)
        else:
            fail(f"{path}: neither an adjoin run (summary.json) nor an OpenSees output (disp.out)")

    def _read_adjoin(self, h):
        self.summary = json.loads((self.path / "summary.json").read_text())
        with open(self.path / "timeseries.csv") as f:
            rows = csv.reader(f)
            header = next(rows)
            columns = list(zip(*([float(v) for v in row] for row in rows)))
        col = {name: i for i, name in enumerate(header)}
        check_grid(self.path / "timeseries.csv", columns[0], h)
        self.x = {b: [columns[col[f"{b}.x{i}"]] for i in range(1, n_floors(header, b) + 1)] for b in "AB"}
        links = sum(1 for name in header if name.endswith(".stroke"))
        self.link_force = [columns[col[f"link{i}.force"]] for i in range(1, links + 1)]
        self.link_stroke = [columns[col[f"link{i}.stroke"]] for i in range(1, links + 1)]

    def _read_opensees(self, h):
        disp = read_table(self.path / "disp.out")
        check_grid(self.path / "disp.out", disp[0], h)
        n = (len(disp) - 1) // 2
        self.x = {"A": disp[1:n + 1], "B": disp[n + 1:]}
        storeys = read_table(self.path / "storeys.out")
        self.shear = {"A": storeys[1:n + 1], "B": storeys[n + 1:]}
        self.link_force, self.link_stroke = [], []
        if (self.path / "links.out").exists():
            links = read_table(self.path / "links.out")
            floors = re.findall(r"element zeroLength 50\d\d (\d+) (\d+)", (self.path / "pair.tcl").read_text())
            for i, (na, nb) in enumerate(floors):
                xa, xb = self.x["A"][int(na) - 2], self.x["B"][int(nb) - 1002]
                self.link_force.append([-f for f in links[i + 1]])  # adjoin's q: -F (pair_to_tcl.py)
                self.link_stroke.append([a - b for a, b in zip(xa, xb)])
        self.laws = scene_numbers(self.path / "pair.tcl")

    def steps(self):
        return len(self.x["A"][0]) - 1

    def drift(self, b, i):
        upper = self.x[b][i]
        lower = self.x[b][i - 1] if i > 0 else [0.0] * len(upper)
        return [u - l for u, l in zip(upper, lower)]

    def storeys(self, b):
        return len(self.x[b])

    def plastic_work(self, b):
        if self.kind == "adjoin":
            return sum(s["plastic_work"] for s in self.summary.get("yield", {}).get(b, []))
        if self.laws[b] is None:  # elastic storeys
            return 0.0
        fy, k, hard = self.laws[b]
        work = 0.0
        for i in range(self.storeys(b)):
            d, f = self.drift(b, i), self.shear[b][i]
            # F = b k d + (1 - b) k z; the slider's slip u_p = d - z, its force (1 - b) F_y
            slip = [dd - (ff - hard * k * dd) / ((1 - hard) * k) for dd, ff in zip(d, f)]
            work += (1 - hard) * fy * sum(abs(s1 - s0) for s0, s1 in zip(slip, slip[1:]))
        return work

    def link_energy(self):
        if self.kind == "adjoin":
            return sum(link["energy"] for link in self.summary["links"])
        return sum(sum(0.5 * (f0 + f1) * (s1 - s0) for f0, f1, s0, s1 in zip(f, f[1:], s, s[1:]))
                   for f, s in zip(self.link_force, self.link_stroke))


def n_floors(header, b):
    return sum(1 for name in header if re.fullmatch(rf"{b}\.x\d+", name))


def read_table(path):
    with open(path) as f:
        return list(zip(*([float(v) for v in line.split()] for line in f if line.strip())))


def check_grid(path, times, h):
    for k, t in enumerate(times):
        if abs(t - k * h) > 1e-6 * h:
            fail(f"{path}: row {k + 1} at t = {t}, expected {k * h} (a row every h = {h} s from t = 0)")


def max_abs_diff(u, v):
    return max(abs(a - b) for a, b in zip(u, v))


def relative(value, reference):
    return (value - reference) / reference if reference else value - reference


def peak(u):
    return max(abs(a) for a in u)


def errors(run, ref):
    roof = max(max_abs_diff(run.x[b][-1], ref.x[b][-1]) for b in "AB")
    roof_peak = max(peak(ref.x[b][-1]) for b in "AB")
    peak_err, peak_rel, final_err, refined_err = 0.0, 0.0, 0.0, 0.0
    for b in "AB":
        for i in range(run.storeys(b)):
            true_peak = ref.summary["peaks"][f"{b}.drift{i + 1}"]["max_abs"]
            d, d_ref = run.drift(b, i), ref.drift(b, i)
            e = abs(peak(d) - true_peak)
            peak_err, peak_rel = max(peak_err, e), max(peak_rel, e / true_peak)
            final_err = max(final_err, abs(d[-1] - d_ref[-1]))
            if run.kind == "adjoin":
                refined = run.summary["peaks"][f"{b}.drift{i + 1}"]["max_abs"]
                refined_err = max(refined_err, abs(refined - true_peak))
    out = {"roof_history": roof, "roof_history_rel": roof / roof_peak, "peak_drift": peak_err,
           "peak_drift_rel": peak_rel, "final_drift": final_err}
    if run.kind == "adjoin":
        out["peak_drift_refined"] = refined_err
    wp, wp_ref = sum(run.plastic_work(b) for b in "AB"), sum(ref.plastic_work(b) for b in "AB")
    we, we_ref = run.link_energy(), ref.link_energy()
    out.update({"plastic_work": wp, "plastic_work_rel": relative(wp, wp_ref),
                "link_energy": we, "link_energy_rel": relative(we, we_ref)})
    return out


def main():
    if len(sys.argv) < 3:
        fail("usage: compare.py REF RUN... (README.md)")
    ref_path = pathlib.Path(sys.argv[1])
    fine_h = json.loads((ref_path / "summary.json").read_text())["solver"]["h"]
    with open(ref_path / "timeseries.csv") as f:  # its rows: every N-th point, the grid h
        next(f)
        h = [float(next(f).split(",")[0]) for _ in range(2)][1]
    every = round(h / fine_h)
    ref = Run(ref_path, h)
    print(f"reference {ref_path}: h/{every}; roof peaks A {peak(ref.x['A'][-1]):.6g} m, B {peak(ref.x['B'][-1]):.6g} m; "
          f"plastic work {sum(ref.plastic_work(b) for b in 'AB'):.6g} J, links {ref.link_energy():.6g} J")

    for arg in sys.argv[2:]:
        run = Run(pathlib.Path(arg), h)
        if run.steps() != ref.steps():
            fail(f"{arg}: {run.steps()} steps of h, the reference {ref.steps()} (did the run stop early?)")
        e = errors(run, ref)

        line = (f"{run.kind:8s} {arg}: roof history {e['roof_history']:.3g} m ({e['roof_history_rel']:.2e} of the peak), "
                f"peak drift {e['peak_drift']:.3g} m ({e['peak_drift_rel']:.2e})")
        if "peak_drift_refined" in e:
            line += f" [refined {e['peak_drift_refined']:.3g} m]"
        line += (f", final drift {e['final_drift']:.3g} m, plastic work {e['plastic_work']:.6g} J ({e['plastic_work_rel']:+.2e}),"
                 f" links {e['link_energy']:.6g} J ({e['link_energy_rel']:+.2e})")
        print(line)


if __name__ == "__main__":
    main()
