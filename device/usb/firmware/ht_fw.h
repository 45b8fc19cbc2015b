/* The knob side of the haptic-timeline USB protocol, version 2.1 (docs/usb-protocol.md).
 *
 * Portable C99: no heap, no operating system, no C library (only the freestanding headers
 * <stdint.h> and <stddef.h>). One `ht_fw` holds the whole device (queue, counters, flags,
 * estimator, telemetry); the port allocates it (statically on a microcontroller) and calls:
 *
 *   ht_fw_init          once, with the device's constants (ht_config);
 *   ht_fw_tick          once per servo period, from its timer (HT rate, e.g. 10 kHz);
 *   ht_fw_control_in    on a vendor IN request on endpoint 0 (GET_INFO);
 *   ht_fw_control_out   on a vendor OUT request (SET_LIMITS, START, STOP);
 *   ht_fw_bulk_out      with each transfer received on endpoint 0x01 (one block);
 *   ht_fw_report        to fill the next telemetry report for endpoint 0x81;
 *   ht_fw_play_table    to play position tables standalone (no host: position mode).
 *
 * The firmware calls the port's hardware abstraction (ht_hal.h): read the encoder, command the
 * torque. ht_fw_tick must not run while one of the USB calls above runs (same interrupt
 * priority, or the timer interrupt masked around them).
 *
 * ht_real is double unless HT_REAL_FLOAT is defined (a Cortex-M4F computes in float natively;
 * the host build uses double so that its servo loop equals the simulated knob's). */
#ifndef HT_FW_H
#define HT_FW_H

#include <stddef.h>
#include <stdint.h>

#ifdef HT_REAL_FLOAT
typedef float ht_real;
#else
typedef double ht_real;
#endif

/* Largest queue (samples) and unreported telemetry (samples) one ht_fw holds: its RAM. */
#ifndef HT_QUEUE_MAX
#define HT_QUEUE_MAX 4096
#endif
#ifndef HT_TELEMETRY_MAX
#define HT_TELEMETRY_MAX 8192
#endif

#define HT_PROTOCOL_VERSION 2
#define HT_PROTOCOL_MINOR 1
#define HT_INFO_V20_SIZE 58
#define HT_INFO_SIZE 86
#define HT_LIMITS_SIZE 8
#define HT_BLOCK_HEADER_SIZE 12
#define HT_REPORT_HEADER_SIZE 32
#define HT_CRC_SIZE 4

#define HT_REQ_GET_INFO 0x01
#define HT_REQ_SET_LIMITS 0x02
#define HT_REQ_START 0x03
#define HT_REQ_STOP 0x04

#define HT_KIND_KINESTHETIC 0
#define HT_KIND_VIBROTACTILE 1
#define HT_CH_D 1
#define HT_CH_K 2
#define HT_CH_B 4
#define HT_CH_M 8
#define HT_ALL_CHANNELS 15

#define HT_FLAG_UNDERRUN (1u << 0)
#define HT_FLAG_OVERRUN (1u << 1)
#define HT_FLAG_WATCHDOG (1u << 2)
#define HT_FLAG_SEQUENCE (1u << 3)
#define HT_FLAG_BAD_BLOCK (1u << 4)
#define HT_FLAG_NON_FINITE (1u << 5)
#define HT_FLAG_SATURATED (1u << 6)

#define HT_STATE_IDLE 0
#define HT_STATE_RUNNING 1
#define HT_STATE_RAMPING 2

#define HT_ESTIMATOR_UNDECLARED 0
#define HT_ESTIMATOR_FILTER 1
#define HT_ESTIMATOR_KALMAN 2
#define HT_ESTIMATOR_TRACKING 3

#define HT_WATCHDOG_MIN_MS 5
#define HT_WATCHDOG_MAX_MS 1000

/* The device's constants: what GET_INFO declares and what the servo loop runs. */
typedef struct {
    uint8_t kind;           /* HT_KIND_* */
    uint8_t channels;       /* mask of the coefficients rendered (bit 0, d, set) */
    uint8_t delay;          /* computation delay D: 0 or 1 servo period */
    uint8_t protocol_minor; /* 1: a 2.1 device (86-byte GET_INFO); 0: a 2.0 device (58 bytes) */
    uint8_t estimator;      /* HT_ESTIMATOR_* (2.1) */
    uint8_t wait_first_block; /* 1: from START to the first block, zero torque and nothing
                               * counted but the watchdog (hardware); 0: underrun at once */
    uint8_t firmware_major, firmware_minor;
    uint16_t firmware_patch;
    uint32_t rate_hz;         /* servo periods per second */
    uint32_t buffer_capacity; /* queue, samples (at most HT_QUEUE_MAX) */
    uint16_t max_block;       /* largest block, samples */
    uint16_t report_samples;  /* samples per telemetry report */
    uint16_t watchdog_ms;     /* initial watchdog */
    uint16_t ramp_ms;         /* ramp to zero */
    ht_real max_torque, max_stiffness, max_damping, max_mass; /* per-channel clamps */
    ht_real encoder_resolution, inertia, viscous, coulomb;    /* declared only */
    ht_real velocity_cutoff, acceleration_cutoff;             /* Hz, declared */
    /* first-order low-pass gain per period at a cut-off fc: 1 - exp(-2*pi*fc/rate), 1: none */
    ht_real velocity_gain;
    ht_real acceleration_gain; /* the filter estimator's acceleration low-pass gain */
    ht_real gains[3];          /* observer gain L (kalman, tracking); zeros for a filter */
} ht_config;

/* Who the device says it is (USB descriptors): IDs, bulk packet size (64 full speed, 512 high
 * speed) and the manufacturer, product and serial strings (UTF-8, NUL-terminated). */
typedef struct {
    uint16_t vid, pid, packet_size;
    const char *strings[3];
} ht_identity;

/* A table over the position axis, as `haptic-timeline export -o TABLES.h` writes it: `count`
 * entries from `start` (rad), `rate` entries per radian, each of torque (N*m), damping
 * (N*m*s/rad) and mass (kg*m^2) given as float32 or as int16 times a scale; NULL when absent. */
typedef struct {
    uint32_t count;
    ht_real start, rate;
    const float *values[3];   /* torque, damping, mass as float32, or */
    const int16_t *counts[3]; /* ... as int16 counts ... */
    ht_real scales[3];        /* ... times these scales */
} ht_table;

typedef struct {
    ht_config cfg;
    void *port; /* handed to the HAL */
    ht_identity identity;
    /* protocol state */
    uint8_t state, mask, end, table_mode, saturated, last_use_mass;
    uint16_t flags, watchdog_ms;
    uint32_t underruns, overruns, played, last_block_seq, expected_seq, report_seq;
    uint32_t since_block, ramp_left, idle;
    ht_real torque_limit, tmax, torque;
    /* queue: full rows d, k, b, m as received (float32; non-finite rows zeroed) */
    uint32_t q_head, q_count;
    float queue[HT_QUEUE_MAX][4];
    ht_real hold[4], last[4];
    /* servo loop (the estimator and the delayed torque) */
    ht_real anchor, prev_meas, vel, prev_vel, acc, pending, est_theta, est_vel;
    /* position mode */
    const ht_table *table;
    ht_real origin;
    /* unreported telemetry: angle, velocity, torque */
    uint32_t t_head, t_count;
    float telemetry[HT_TELEMETRY_MAX][3];
} ht_fw;

/* 0, or -1 when the constants cannot work (capacity beyond HT_QUEUE_MAX, zero rate...). */
int ht_fw_init(ht_fw *fw, const ht_config *cfg, void *port);
void ht_fw_tick(ht_fw *fw);

/* Vendor requests: the answer's length (IN), 0 (OUT), or -1: STALL endpoint 0. */
int ht_fw_control_in(ht_fw *fw, uint8_t request, uint16_t length, uint8_t *out);
int ht_fw_control_out(ht_fw *fw, uint8_t request, uint16_t value, const uint8_t *data,
                      uint16_t length);
void ht_fw_bulk_out(ht_fw *fw, const uint8_t *data, size_t length);

/* The standard descriptors (GET_DESCRIPTOR): device (type 1), configuration (2, index 0: the
 * whole vendor interface with its two bulk endpoints), string (3; index 0: the LANGID list).
 * Returns the length written to out (at most `capacity`: room for 255 bytes takes any), or -1
 * when there is no such descriptor. Identity as set by ht_fw_set_identity (default: 1209:0001,
 * full speed, "haptic-timeline", "Haptic knob", "0001"). */
void ht_fw_set_identity(ht_fw *fw, const ht_identity *identity);
int ht_fw_descriptor(const ht_fw *fw, uint8_t type, uint8_t index, uint8_t *out,
                     uint16_t capacity);

/* Bytes of the next report written to out (room for HT_REPORT_HEADER_SIZE + 12 *
 * report_samples + 4 bytes); ht_fw_report_ready says a full report's samples are waiting. */
size_t ht_fw_report(ht_fw *fw, uint8_t *out);
int ht_fw_report_ready(const ht_fw *fw);

/* Position mode: play `table` looked up at origin + the angle from now (rad), until STOP. */
void ht_fw_play_table(ht_fw *fw, const ht_table *table, ht_real origin);

uint32_t ht_crc32(const uint8_t *data, size_t length);

/* The size of one ht_fw (for a host that allocates it, e.g. through ctypes). */
size_t ht_fw_size(void);

#endif /* HT_FW_H */
