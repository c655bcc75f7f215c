"""Thread speed-up of one DEM run stepped from Python (issue 12): `pdamp.simulate` of the
side-by-side bed (bench/dem_bed.toml) at N grains, box footprint widened as sqrt(N/250), the
bed packed by the advancing front, settled for 0.03 s, then driven (vibrated) or held still
(rest). Prints the run's `particle_steps_per_s` (driven phase, wall clock).

The thread count is rayon's (`RAYON_NUM_THREADS`, read when the package loads), so compare
runs of separate processes, alternating:

    for k in 1 2 3; do for t in 1 2; do
        RAYON_NUM_THREADS=$t python bench/dem_python_threads.py 4000 rest; done; done
"""

import math
import os
import sys

import pdamp

BENCH = os.path.dirname(os.path.abspath(__file__))


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 4000
    state = sys.argv[2] if len(sys.argv) > 2 else "rest"
    side = 0.03675 * math.sqrt(n / 250)
    steps = min(max(int(2e7 / n), 400), 20000)
    dt = 2.8e-6
    overrides = {
        "damper.count": n,
        "damper.box": [side, side, 0.1225],
        "damper.packing": "advancing-front",
        "damper.settle_time": 0.03,
        "run.duration": 1.1 * steps * dt,
    }
    if state == "rest":
        overrides["excitation.amplitude"] = 0.0
    sim = pdamp.simulate(
        os.path.join(BENCH, "dem_bed.toml"), set=overrides, analyze=False, series=False
    )
    rate = sim.summary["particle_steps_per_s"]
    threads = os.environ.get("RAYON_NUM_THREADS", "default")
    print(f"N = {n} {state}, RAYON_NUM_THREADS = {threads}: {rate / 1e6:.2f} M particle-steps/s")


if __name__ == "__main__":
    main()
