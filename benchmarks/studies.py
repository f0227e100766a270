"""Times one small but real study on each backend: serially, on joblib with 2
processes and on a Dask LocalCluster with 2 workers, each beside the reference
workload (benchmarks/reference.py) timed just before and just after it, and checks that
the three files are byte-identical.

    python benchmarks/studies.py [--seeds 8] [--rollouts 300] [--out record.json]

The study is the remedies study cut small: 7 conditions x `--seeds` seeds (per
condition, spread over its 4 root seeds), `--rollouts` rollouts each, every unit a seed
of a condition, as in the full study. Prints a Markdown table (wall time, the CPU
seconds of the units, the speed-up over serial by wall time and by the wall time's
ratio to the reference) and writes the record as JSON. On a machine others share, the
reference itself can swing several-fold within minutes: read both speed-ups, and the
load average printed with them.
"""

import argparse
import json
import os
import pathlib
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

from reference import reference_seconds  # noqa: E402

from icm import studies  # noqa: E402
from icm.studies import engine  # noqa: E402


def _time(name, out, options, **run):
    before = reference_seconds()
    start = time.perf_counter()
    studies.run_study(name, out, progress=False, **options, **run)
    wall = time.perf_counter() - start
    after = reference_seconds()
    log = json.loads(engine.run_log_of(out).read_text().splitlines()[-1])
    return {"wall_seconds": round(wall, 1), "unit_cpu_seconds": log["unit_cpu_seconds_total"],
            "reference_seconds": [round(before, 4), round(after, 4)],
            "wall_over_reference": round(wall / ((before + after) / 2), 0)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--rollouts", type=int, default=300)
    parser.add_argument("--out", type=pathlib.Path, default=None)
    args = parser.parse_args(argv)
    from dask import distributed

    options = {"seeds": args.seeds, "rollouts": args.rollouts, "reach_movements": 50}
    record = {"study": "remedies", "options": options, "cpu_count": os.cpu_count(),
              "load_average_before": os.getloadavg(), "times": {}}
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        record["times"]["serial"] = _time("remedies", folder / "serial.json", options,
                                          backend="serial")
        record["times"]["joblib, 2 processes"] = _time(
            "remedies", folder / "joblib.json", options, backend="joblib", n_jobs=2)
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            record["times"]["Dask LocalCluster, 2 workers"] = _time(
                "remedies", folder / "dask.json", options, backend="dask", client=client)
        texts = {p.name: p.read_bytes() for p in folder.glob("*.json")}
        record["byte_identical"] = len(set(texts.values())) == 1
    record["load_average_after"] = os.getloadavg()
    serial = record["times"]["serial"]
    print(f"remedies study, {args.seeds} seeds per condition, {args.rollouts} rollouts "
          f"({os.cpu_count()} cores, load average {record['load_average_before'][0]:.1f})")
    print("| backend | wall, s | units' CPU, s | speed-up (wall) | wall / reference "
          "| speed-up (ratio) |")
    print("|---|---|---|---|---|---|")
    for name, t in record["times"].items():
        speed = serial["wall_over_reference"] / t["wall_over_reference"]
        t["speed_up_over_serial"] = round(speed, 2)
        t["wall_speed_up_over_serial"] = round(serial["wall_seconds"] / t["wall_seconds"], 2)
        print(f"| {name} | {t['wall_seconds']} | {t['unit_cpu_seconds']} "
              f"| {t['wall_speed_up_over_serial']:.2f} | {t['wall_over_reference']:.0f} "
              f"| {speed:.2f} |")
    print(f"byte-identical files: {record['byte_identical']}")
    if args.out:
        args.out.write_text(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
