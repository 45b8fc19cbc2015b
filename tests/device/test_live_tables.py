"""A position program with a live table source: the sim renders the newest table at each chunk."""

import numpy as np

from device.sim import SimKnob
from timeline.plugins.device_protocol import Hand, PositionProgram, PositionTable


def constant(torque: float) -> PositionTable:
    return PositionTable(-1.0, 100.0, np.full(201, torque))


def test_the_sim_reads_the_live_table_once_per_chunk():
    tables = [constant(0.02)]
    reads = []

    def live() -> PositionTable:
        reads.append(len(reads))
        if len(reads) == 3:
            tables[0] = constant(-0.05)  # an edit arrives while the program plays
        return tables[0]

    program = PositionProgram(constant(0.0), 0.2, 0.0, live=live)
    tel = SimKnob().play(program, Hand("hold"))
    assert len(reads) == 4  # 0.2 s in 50 ms chunks
    assert tel.torque[0] == 0.02 and tel.torque[999] == 0.02  # first two chunks
    assert tel.torque[1000] == -0.05 and tel.torque[-1] == -0.05  # after the edit
    assert PositionProgram(constant(0.01), 0.1).table_now().torque[0] == 0.01
