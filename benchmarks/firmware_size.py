"""The knob's C firmware on a Cortex-M4F: flash and RAM bytes, and host time per servo period.

    python benchmarks/firmware_size.py

Cross-compiles device/usb/firmware/ht_fw.c with Debian's arm-none-eabi-gcc (apt-get install
gcc-arm-none-eabi; not needed in CI) for a Cortex-M4F (-mcpu=cortex-m4 -mfpu=fpv4-sp-d16
-mfloat-abi=hard -Os, float arithmetic), links it with a stub port (two HAL functions on
memory-mapped registers, a static ht_fw, no C library) and reads the sizes with arm-none-eabi-size:
flash = text + data, RAM = data + bss (the stack aside). Two builds: the queue and telemetry of
the emulated knob (4,096 and 8,192 samples) and a microcontroller's (1,024 and 512). Then times
ht_fw_tick on this machine through the host build (double arithmetic, the sim port stepping the
motor and hand: an upper bound on the firmware alone) while a four-channel stream plays, and
prints it as a fraction of the 100 us period at 10 kHz. docs/firmware.md has the figures.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
FIRMWARE = ROOT / "device" / "usb" / "firmware"
CPU = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16"]
BUILDS = {"emulated knob's buffers": (4096, 8192), "microcontroller buffers": (1024, 512)}

STUB = r"""
#include "ht_fw.h"
#include "ht_hal.h"

static ht_fw knob;
static uint8_t transfer[1300];

ht_real ht_hal_encoder_read(void *port) { (void)port; return *(volatile float *)0x40000000; }
void ht_hal_torque_command(void *port, ht_real t) { (void)port; *(volatile float *)0x40000004 = t; }

void *memcpy(void *to, const void *from, size_t n) {
    uint8_t *p = to; const uint8_t *q = from;
    while (n--) *p++ = *q++;
    return to;
}
void *memset(void *to, int c, size_t n) {
    uint8_t *p = to;
    while (n--) *p++ = (uint8_t)c;
    return to;
}

void _start(void) {
    ht_config cfg = {0};
    cfg.channels = HT_ALL_CHANNELS; cfg.delay = 1; cfg.protocol_minor = 1;
    cfg.estimator = HT_ESTIMATOR_KALMAN; cfg.wait_first_block = 1; cfg.rate_hz = 10000;
    cfg.buffer_capacity = HT_QUEUE_MAX; cfg.max_block = 512; cfg.report_samples = 100;
    cfg.watchdog_ms = 50; cfg.ramp_ms = 10; cfg.max_torque = 0.18f; cfg.velocity_gain = 0.7153f;
    ht_fw_init(&knob, &cfg, 0);
    for (;;) {
        volatile uint32_t *usb = (volatile uint32_t *)0x50000000;
        uint8_t req = (uint8_t)usb[0];
        if (usb[6]) ht_fw_tick(&knob); /* the timer's interrupt, as a poll: kept by the linker */
        if (usb[7]) usb[4] = (uint32_t)ht_fw_descriptor(&knob, (uint8_t)usb[7], 0, transfer, 255);
        if (usb[1]) ht_fw_bulk_out(&knob, transfer, usb[2]);
        if (ht_fw_report_ready(&knob)) usb[3] = (uint32_t)ht_fw_report(&knob, transfer);
        if (req & 0x80) usb[4] = (uint32_t)ht_fw_control_in(&knob, req & 0x7f, 86, transfer);
        else if (req)
            usb[4] = (uint32_t)ht_fw_control_out(&knob, req, (uint16_t)usb[5], transfer, 8);
    }
}
"""


def cortex_m4_sizes(queue: int, telemetry: int, folder: Path) -> tuple[int, int]:
    """(flash, RAM) bytes of the firmware with a stub port, linked for a Cortex-M4F."""
    stub = folder / "stub.c"
    stub.write_text(STUB)
    elf = folder / f"knob-{queue}-{telemetry}.elf"
    command = [
        "arm-none-eabi-gcc", *CPU, "-std=c99", "-Os", "-ffreestanding", "-nostdlib",
        "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections", "-Wl,-e,_start",
        "-DHT_REAL_FLOAT", f"-DHT_QUEUE_MAX={queue}", f"-DHT_TELEMETRY_MAX={telemetry}",
        f"-I{FIRMWARE}", "-o", str(elf), str(FIRMWARE / "ht_fw.c"), str(stub), "-lgcc",
    ]  # fmt: skip
    subprocess.run(command, check=True)
    out = subprocess.run(["arm-none-eabi-size", str(elf)], check=True, capture_output=True)
    text, data, bss = (int(x) for x in out.stdout.decode().splitlines()[1].split()[:3])
    return text + data, data + bss


def host_time_per_tick(seconds: float = 20.0) -> float:
    """CPU seconds per ht_fw_tick on this machine, four channels, the Kalman observer running."""
    sys.path.insert(0, str(ROOT))
    from device.usb import protocol as p
    from device.usb.firmware import EmulatedKnob

    knob = EmulatedKnob()
    knob.control_out(p.REQ_START, p.ALL_CHANNELS, b"")
    n = 500
    t = np.arange(n) / 10_000
    samples = np.column_stack([0.03 * np.sin(2 * np.pi * 15 * t), np.full(n, 0.4),
                               np.full(n, 2e-4), np.full(n, 2e-6)])  # fmt: skip
    spent, ticks, seq = 0.0, 0, 0
    while ticks < seconds * 10_000:
        knob.receive(p.encode_block(p.Block(seq, p.ALL_CHANNELS, samples)))
        seq += 1
        start = time.thread_time()  # CPU time: other processes' load is not counted
        knob.advance_samples(n)
        spent += time.thread_time() - start
        ticks += n
        knob.report()
    return spent / ticks


def main() -> int:
    if shutil.which("arm-none-eabi-gcc"):
        with tempfile.TemporaryDirectory() as folder:
            for name, (queue, telemetry) in BUILDS.items():
                flash, ram = cortex_m4_sizes(queue, telemetry, Path(folder))
                print(f"Cortex-M4F, {name} (queue {queue}, telemetry {telemetry} samples): "
                      f"flash {flash:,} bytes, RAM {ram:,} bytes")  # fmt: skip
    else:
        print("arm-none-eabi-gcc not found (apt-get install gcc-arm-none-eabi): sizes skipped")
    per_tick = host_time_per_tick()
    load = os.getloadavg()[0]
    print(
        f"host: {per_tick * 1e6:.3f} us CPU per servo period (double, sim port included), "
        f"{per_tick / 1e-4:.4f} of the 100 us period at 10 kHz; load average {load:.2f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
