"""Simulated knob: the whole-loop stability flag against simulated growth (random k, b, m).

    python benchmarks/loop_sweep.py [--quick]

300 mixes per estimator and delay, each played with every hand's load (10,800 runs of 2 s;
`--quick`: 30 mixes, 1 s runs). The measuring code is device/sim/bench/loop_sweep.py; the
figures are in docs/devices.md ("Stability flags").
"""

import sys
from pathlib import Path

from device.sim.bench.loop_sweep import run

if __name__ == "__main__":
    for table in run("--quick" in sys.argv[1:], Path(".")):
        print(table.text(), end="\n\n")
