# SPDX-License-Identifier: MIT
"""The Python module on a busy machine: example 07's design loop (eight Morpher solves) on a
quiet machine and beside busy processes, one per core, with the user's environment as a new
user has it (no OMP_WAIT_POLICY, GOMP_SPINCOUNT or OMP_NUM_THREADS), and, for comparison,
with libgomp's own default of spinning waits (GOMP_SPINCOUNT=300000). Prints a Markdown row
per setting: the seconds of the eight solves (best of ROUNDS runs) quiet and busy, and their ratio
(bench/README.md, "The Python module under load").

    python3 bench/python_load.py BUILD_DIR [ROUNDS]
"""
import multiprocessing
import os
import pathlib
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
build = pathlib.Path(sys.argv[1]).resolve()
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
loop = root / "examples" / "07_python_design_loop" / "design_loop.py"


def busy():
    while True:
        pass


def solve_seconds(env, out_dir):
    """The seconds of the design loop's solves (its table's column), summed."""
    text = subprocess.run([sys.executable, str(loop), str(out_dir)], env=env, check=True, capture_output=True,
                          text=True).stdout
    rows = [line.split("|") for line in text.splitlines() if line.startswith("| 0.")]
    return sum(float(row[5]) for row in rows)


def best(env, out_dir):
    return min(solve_seconds(env, out_dir) for _ in range(rounds))


def main():
    base = {k: v for k, v in os.environ.items()
            if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "OMP_NUM_THREADS") and not k.startswith("MESHMORPH_")}
    base["PYTHONPATH"] = str(build / "python")
    settings = [("nothing set (the module's default)", base),
                ("GOMP_SPINCOUNT=300000 (libgomp's default spinning)", {**base, "GOMP_SPINCOUNT": "300000"})]
    out_dir = build / "bench-python-load"
    out_dir.mkdir(exist_ok=True)
    quiet = {name: best(env, out_dir) for name, env in settings}
    hogs = [multiprocessing.Process(target=busy, daemon=True) for _ in range(os.cpu_count() or 1)]
    for h in hogs:
        h.start()
    try:
        loaded = {name: best(env, out_dir) for name, env in settings}
    finally:
        for h in hogs:
            h.terminate()
    print(f"machine: {os.cpu_count()} cores; busy: {len(hogs)} processes spinning beside")
    print("| environment | quiet: s (8 solves) | busy: s | busy / quiet |")
    print("|---|---:|---:|---:|")
    for name, _ in settings:
        print(f"| {name} | {quiet[name]:.3f} | {loaded[name]:.3f} | {loaded[name] / quiet[name]:.1f} |")


if __name__ == "__main__":
    main()
