"""Simulated knob: integrator error against the analytic solution, and speed.

    python benchmarks/sim_integrators.py [--quick] [--out DIR]

Same as `haptic-timeline bench integrators sim-speed` (the measuring code is in device/sim/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "integrators", "sim-speed"]))
