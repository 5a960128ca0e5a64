"""Run the c hypotheses and print one table row each (research/c_hypotheses.md).

PYTHONPATH=/work/wt-repro OPENBLAS_NUM_THREADS=1 python3 research/run_c_hypotheses.py [lines] [names...]
lines: comma-separated C_max values (default 1); env RB_N (grid, default 40), RB_POINTS (15)."""
import json
import os
import sys
import time

from rotbeam.integrate import Numerics

from rotbeam.analysis_c_hypotheses import HYPOTHESES, c_for_hypothesis

lines = tuple(float(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "1").split(","))
names = sys.argv[2:] or list(HYPOTHESES)
for name in names:
    t = time.perf_counter()
    try:
        r = c_for_hypothesis(name, c_max_lines=lines,
                             numerics=Numerics(N=int(os.environ.get("RB_N", 40))),
                             points=int(os.environ.get("RB_POINTS", 15)))
    except Exception as exc:  # report and go on
        print(f"| {name} | error: {type(exc).__name__}: {exc} |", flush=True)
        continue
    dt = time.perf_counter() - t
    c = " | ".join(f"{v:.4f}" for v in r["c"].values())
    d0 = [round(float(ln["delta"][0]), 4) for ln in r["lines"]]
    f0 = [round(float(ln["f0"]), 3) for ln in r["lines"]]
    print(f"| {name} | {c} | N {os.environ.get('RB_N', 40)}, lines {lines}, Delta(0.15 f0) {d0}, f0 {f0}, {dt:.1f} s |"
          + (f" notes: {'; '.join(r['notes'][:2])}" if r["notes"] else ""), flush=True)
    print("JSON " + json.dumps({"name": name, "lines": lines, "c": r["c"],
                                "per_line": r["per_line"], "seconds": dt}), flush=True)
