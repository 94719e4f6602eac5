#!/usr/bin/env python3
"""The two-frame study from Python: three damper designs over the shipped records.

Two adjacent steel frames (a 5-storey A and a 3-storey B, records/scenes/buildings/
two-frames.toml) joined at floor 3, with a 5 cm gap that can close (a linear contact law with
restitution 0.65, so impacts are counted). Three designs of the link between them:

    friction 5 %     a friction damper slipping at 5 % of B's weight (the shipped scene)
    friction 15 %    the same, slipping at 15 %
    viscous          a dashpot of c = 2e6 N s/m

each run over every PEER record in records/real/peer with adjoin.run_many (native threads),
then a table of peaks and impacts, and the drift profiles (mean over the records, range
shaded) in OUT/two_frames_drifts.png.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/two_frames.py OUT [--jobs 2] [--t-end 45]
"""
import argparse
import copy
import pathlib
import sys

import adjoin

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "records" / "scenes" / "buildings" / "two-frames.toml"
RECORDS = sorted((ROOT / "records" / "real" / "peer").glob("*.AT2"))

DESIGNS = {
    "friction 5 %": {"floors": [3, 3], "type": "friction", "slip_ratio": 0.05, "of": "B"},
    "friction 15 %": {"floors": [3, 3], "type": "friction", "slip_ratio": 0.15, "of": "B"},
    "viscous": {"floors": [3, 3], "type": "dashpot", "c": 2.0e6},
}


def scenes_for(base, design, t_end):
    """One scene (a dict: the TOML file's structure) per record for a link design."""
    out = []
    for record in RECORDS:
        d = copy.deepcopy(base)
        d["name"] = f"{design.replace(' %', 'pct').replace(' ', '-')}-{record.stem}"
        d["link"] = [DESIGNS[design]]
        d["contact"][0].update(model="linear", stiffness=1.0e8, restitution=0.65)
        d["ground"]["file"] = str(record)
        d["solver"]["t_end"] = t_end
        d["output"]["timeseries"] = False  # the peaks are in the summary; no history needed
        out.append(d)
    return out


def table(results_by_design):
    lines = [f"{'design':<14} {'record':<32} {'A roof [m]':>10} {'A drift [m]':>11} {'B drift [m]':>11} "
             f"{'link [kN]':>9} {'impacts':>7} {'F_max [kN]':>10}"]
    for design, results in results_by_design.items():
        for record, r in zip(RECORDS, results):
            p = r.summary["peaks"]
            drift_a = max(p[f"A.drift{i}"]["max_abs"] for i in range(1, 6))
            drift_b = max(p[f"B.drift{i}"]["max_abs"] for i in range(1, 4))
            contact = r.summary["contacts"][0]
            lines.append(f"{design:<14} {record.stem[:32]:<32} {p['A.x5']['max_abs']:>10.4f} {drift_a:>11.4f} "
                         f"{drift_b:>11.4f} {p['link1.force']['max_abs'] / 1e3:>9.1f} {contact['impacts']:>7d} "
                         f"{contact['force_max'] / 1e3:>10.1f}")
    return "\n".join(lines)


def plot(results_by_design, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import adjoin.plot

    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(9, 4.5))
    for design, results in results_by_design.items():
        adjoin.plot.drift_profile(results, "A", ax=ax_a, label=design)
        adjoin.plot.drift_profile(results, "B", ax=ax_b, label=design)
    ax_a.set_title("building A (5 storeys)")
    ax_b.set_title("building B (3 storeys)")
    ax_a.legend()
    fig.suptitle(f"peak storey drifts, mean over {len(RECORDS)} records (range shaded)")
    fig.tight_layout()
    path = out / "two_frames_drifts.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=pathlib.Path, help="folder for the figure (created)")
    parser.add_argument("--jobs", type=int, default=0, help="threads (0: one per core)")
    parser.add_argument("--t-end", type=float, default=45.0, help="horizon of every run [s]")
    args = parser.parse_args(argv)

    base = adjoin.load_scene(SCENE).to_dict()  # the shipped scene, as a dict to edit in code
    results_by_design = {}
    for design in DESIGNS:
        results_by_design[design] = adjoin.run_many(scenes_for(base, design, args.t_end), jobs=args.jobs)
    print(table(results_by_design))
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"wrote {plot(results_by_design, args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
