/* A harness for fuzzing the firmware under AddressSanitizer and UBSan (build.py).
 *
 * Reads commands from stdin and feeds them to one ht_fw on a free rotor (the host port):
 *   0 len:u16 bytes            a bulk OUT transfer (a block)
 *   1 req:u8 value:u16 len:u16 bytes  a vendor OUT request
 *   2 n:u16                    n servo periods
 *   3                          a telemetry report, written to stdout as len:u32 bytes
 *   4 req:u8 length:u16        a vendor IN request, its answer written like a report
 *   5 type:u8 index:u8 cap:u16  a GET_DESCRIPTOR, its answer written like a report
 * After every period it checks the torque applied is finite and within the maximum (else it
 * aborts); the caller decodes the reports. Exits 0 at the end of the input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../../ht_hal.h"

size_t ht_sim_size(void);
void ht_sim_init(void *sim, const double map[10], double period, double quantum, double coulomb);

static ht_fw fw; /* static, as on a microcontroller */
static double sim[64];
static uint8_t buffer[1u << 17];

static int read_bytes(uint8_t *to, size_t n) { return fread(to, 1, n, stdin) == n; }

static int read_u16(uint32_t *v) {
    uint8_t b[2];
    if (!read_bytes(b, 2)) return 0;
    *v = (uint32_t)b[0] | ((uint32_t)b[1] << 8);
    return 1;
}

static void emit(const uint8_t *data, size_t n) {
    uint8_t head[4] = {(uint8_t)n, (uint8_t)(n >> 8), (uint8_t)(n >> 16), (uint8_t)(n >> 24)};
    fwrite(head, 1, 4, stdout);
    fwrite(data, 1, n, stdout);
}

int main(void) {
    const double t = 1e-4, j = 3e-5;
    const double map[10] = {1.0, t, t * t / (2 * j), 0, 0, 0, 1.0, t / j, 0, 0};
    ht_config cfg = {0};
    int op;
    if (ht_sim_size() > sizeof sim) return 2;
    cfg.kind = HT_KIND_KINESTHETIC;
    cfg.channels = HT_ALL_CHANNELS;
    cfg.delay = 1;
    cfg.protocol_minor = 1;
    cfg.estimator = HT_ESTIMATOR_KALMAN;
    cfg.rate_hz = 10000;
    cfg.buffer_capacity = 600;
    cfg.max_block = 512;
    cfg.report_samples = 100;
    cfg.watchdog_ms = 50;
    cfg.ramp_ms = 10;
    cfg.max_torque = 0.18;
    cfg.max_stiffness = 100;
    cfg.max_damping = 1;
    cfg.max_mass = 1e-2;
    cfg.encoder_resolution = 1.7453292519943296e-05;
    cfg.velocity_gain = 0.7153;
    cfg.gains[0] = 0.5263614058494568;
    cfg.gains[1] = 1944.20947265625;
    cfg.gains[2] = 3590641.75;
    ht_sim_init(sim, map, t, cfg.encoder_resolution, 1e-3);
    if (ht_fw_init(&fw, &cfg, sim)) return 3;
    while ((op = getchar()) != EOF) {
        uint32_t a = 0, b = 0, n = 0, i;
        if (op == 0 && read_u16(&n) && read_bytes(buffer, n)) {
            ht_fw_bulk_out(&fw, buffer, n);
        } else if (op == 1 && read_bytes(buffer, 1) && read_u16(&a) && read_u16(&n) &&
                   read_bytes(buffer + 1, n)) {
            ht_fw_control_out(&fw, buffer[0], (uint16_t)a, buffer + 1, (uint16_t)n);
        } else if (op == 2 && read_u16(&n)) {
            for (i = 0; i < n; i++) {
                ht_fw_tick(&fw);
                if (!isfinite(fw.torque) || fabs(fw.torque) > cfg.max_torque) abort();
            }
        } else if (op == 3) {
            emit(buffer, ht_fw_report(&fw, buffer));
        } else if (op == 4 && read_bytes(buffer, 1) && read_u16(&b)) {
            int got = ht_fw_control_in(&fw, buffer[0], (uint16_t)b, buffer + 1);
            emit(buffer + 1, got < 0 ? 0u : (size_t)got);
        } else if (op == 5 && read_bytes(buffer, 2) && read_u16(&b)) {
            int got = ht_fw_descriptor(&fw, buffer[0], buffer[1], buffer + 2, (uint16_t)b);
            if (got > (int)b) abort();
            emit(buffer + 2, got < 0 ? 0u : (size_t)got);
        } else {
            break; /* truncated input ends the run */
        }
    }
    return 0;
}
