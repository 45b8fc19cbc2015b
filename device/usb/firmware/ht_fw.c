/* The knob side of the haptic-timeline USB protocol 2.1: requests, blocks, queue, safety,
 * servo loop and telemetry (docs/usb-protocol.md, docs/firmware.md). C99, no heap, no OS. */
#include "ht_fw.h"

#include "ht_hal.h"

#define BLOCK_FLAG_END 1u

/* --- little-endian bytes ------------------------------------------------------------------ */

static void put_u16(uint8_t *p, uint32_t v) {
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *p, uint32_t v) {
    put_u16(p, v);
    put_u16(p + 2, v >> 16);
}

typedef union {
    float f;
    uint32_t u;
} bits32;

static void put_f32(uint8_t *p, float f) {
    bits32 b;
    b.f = f;
    put_u32(p, b.u);
}

static uint32_t get_u16(const uint8_t *p) { return (uint32_t)p[0] | ((uint32_t)p[1] << 8); }

static uint32_t get_u32(const uint8_t *p) { return get_u16(p) | (get_u16(p + 2) << 16); }

/* float32 from 4 bytes; *finite cleared when it is NaN or infinite (by its bits: no libm). */
static float get_f32(const uint8_t *p, int *finite) {
    bits32 b;
    b.u = get_u32(p);
    if ((b.u & 0x7f800000u) == 0x7f800000u) *finite = 0;
    return b.f;
}

/* --- CRC-32 (zlib's: polynomial 0x04C11DB7 reflected, 0xFFFFFFFF in and out) -------------- */

static const uint32_t CRC_NIBBLE[16] = {
    0x00000000u, 0x1db71064u, 0x3b6e20c8u, 0x26d930acu, 0x76dc4190u, 0x6b6b51f4u,
    0x4db26158u, 0x5005713cu, 0xedb88320u, 0xf00f9344u, 0xd6d6a3e8u, 0xcb61b38cu,
    0x9b64c2b0u, 0x86d3d2d4u, 0xa00ae278u, 0xbdbdf21cu};

uint32_t ht_crc32(const uint8_t *data, size_t length) {
    uint32_t crc = 0xffffffffu;
    size_t i;
    for (i = 0; i < length; i++) {
        crc ^= data[i];
        crc = (crc >> 4) ^ CRC_NIBBLE[crc & 15u];
        crc = (crc >> 4) ^ CRC_NIBBLE[crc & 15u];
    }
    return crc ^ 0xffffffffu;
}

static size_t seal(uint8_t *out, size_t length) {
    put_u32(out + length, ht_crc32(out, length));
    return length + HT_CRC_SIZE;
}

/* 1209:0001 is pid.codes' test ID: a product registers its own (docs/usb-protocol.md). */
static const ht_identity DEFAULT_IDENTITY = {
    0x1209, 0x0001, 64, {"haptic-timeline", "Haptic knob", "0001"}};

/* --- set-up --------------------------------------------------------------------------------- */

/* No C library: these two are all the firmware needs of <string.h>. */
static void zero(void *to, size_t n) {
    uint8_t *p = (uint8_t *)to;
    while (n--) *p++ = 0;
}

static void copy(void *to, const void *from, size_t n) {
    uint8_t *p = (uint8_t *)to;
    const uint8_t *q = (const uint8_t *)from;
    while (n--) *p++ = *q++;
}

size_t ht_fw_size(void) { return sizeof(ht_fw); }

static void clear_queue(ht_fw *fw) {
    fw->q_head = 0;
    fw->q_count = 0;
}

/* A play begins: the current angle is the anchor (theta = 0); estimators reset. */
static void restart_loop(ht_fw *fw) {
    fw->anchor = ht_hal_encoder_read(fw->port);
    fw->prev_meas = fw->vel = fw->prev_vel = fw->acc = 0;
    fw->pending = fw->est_theta = fw->est_vel = 0;
    fw->idle = 0;
    zero(fw->last, sizeof fw->last);
    fw->last_use_mass = 0;
    fw->tmax = fw->torque_limit;
}

int ht_fw_init(ht_fw *fw, const ht_config *cfg, void *port) {
    if (!cfg->rate_hz || !cfg->report_samples || cfg->buffer_capacity > HT_QUEUE_MAX ||
        cfg->buffer_capacity < cfg->max_block || !(cfg->channels & HT_CH_D) || cfg->delay > 1 ||
        !(cfg->max_torque > 0))
        return -1;
    zero(fw, sizeof *fw);
    fw->cfg = *cfg;
    fw->port = port;
    fw->identity = DEFAULT_IDENTITY;
    fw->watchdog_ms = cfg->watchdog_ms;
    fw->torque_limit = cfg->max_torque;
    fw->state = HT_STATE_IDLE;
    restart_loop(fw);
    return 0;
}

/* --- standard descriptors ------------------------------------------------------------------ */

void ht_fw_set_identity(ht_fw *fw, const ht_identity *identity) { fw->identity = *identity; }

/* UTF-8 (the Basic Multilingual Plane) to a USB string descriptor's UTF-16LE; bytes written. */
static uint32_t utf16(const char *text, uint8_t *out, uint32_t room) {
    const uint8_t *s = (const uint8_t *)text;
    uint32_t n = 0;
    while (*s && n + 2 <= room) {
        uint32_t c = *s++;
        if (c >= 0xe0 && s[0] && s[1]) {
            c = ((c & 0x0fu) << 12) | ((uint32_t)(s[0] & 0x3fu) << 6) | (s[1] & 0x3fu);
            s += 2;
        } else if (c >= 0xc0 && s[0]) {
            c = ((c & 0x1fu) << 6) | (s[0] & 0x3fu);
            s += 1;
        }
        put_u16(out + n, c);
        n += 2;
    }
    return n;
}

int ht_fw_descriptor(const ht_fw *fw, uint8_t type, uint8_t index, uint8_t *out,
                     uint16_t capacity) {
    uint8_t d[255];
    uint32_t n, i;
    const ht_identity *id = &fw->identity;
    if (type == 1) { /* device: USB 2.0, class per interface, EP0 64 bytes, strings 1-3 */
        const uint8_t head[8] = {18, 1, 0x00, 0x02, 0, 0, 0, 64};
        copy(d, head, 8);
        put_u16(d + 8, id->vid);
        put_u16(d + 10, id->pid);
        put_u16(d + 12, 0x0100);
        d[14] = 1;
        d[15] = 2;
        d[16] = 3;
        d[17] = 1;
        n = 18;
    } else if (type == 2 && index == 0) { /* configuration, interface 0xFF/0x48/2, 0x01, 0x81 */
        const uint8_t body[32] = {9, 2, 32, 0, 1, 1, 0, 0xc0, 50, /* self-powered, 100 mA */
                                  9, 4, 0, 0, 2, 0xff, 0x48, HT_PROTOCOL_VERSION, 0,
                                  7, 5, 0x01, 2, 0, 0, 0, 7, 5, 0x81, 2, 0, 0, 0};
        copy(d, body, 32);
        put_u16(d + 22, id->packet_size);
        put_u16(d + 29, id->packet_size);
        n = 32;
    } else if (type == 3 && index == 0) { /* the LANGID list: English (United States) */
        d[0] = 4;
        d[1] = 3;
        put_u16(d + 2, 0x0409);
        n = 4;
    } else if (type == 3 && index <= 3 && id->strings[index - 1]) {
        n = 2 + utf16(id->strings[index - 1], d + 2, sizeof d - 2);
        d[0] = (uint8_t)n;
        d[1] = 3;
    } else {
        return -1;
    }
    if (n > capacity) n = capacity;
    for (i = 0; i < n; i++) out[i] = d[i];
    return (int)n;
}

/* --- control requests ----------------------------------------------------------------------- */

static size_t encode_info(const ht_fw *fw, uint8_t *out) {
    const ht_config *c = &fw->cfg;
    out[0] = 'H';
    out[1] = 'I';
    out[2] = HT_PROTOCOL_VERSION;
    out[3] = c->kind;
    out[4] = c->firmware_major;
    out[5] = c->firmware_minor;
    put_u16(out + 6, c->firmware_patch);
    put_u32(out + 8, c->rate_hz);
    put_f32(out + 12, (float)c->max_torque);
    put_f32(out + 16, (float)c->max_stiffness);
    put_f32(out + 20, (float)c->max_damping);
    put_f32(out + 24, (float)c->max_mass);
    put_f32(out + 28, (float)c->encoder_resolution);
    put_u32(out + 32, c->buffer_capacity);
    put_u16(out + 36, c->max_block);
    put_u16(out + 38, c->report_samples);
    out[40] = c->channels;
    out[41] = c->delay;
    put_u16(out + 42, c->watchdog_ms);
    put_u16(out + 44, c->ramp_ms);
    put_f32(out + 46, (float)c->inertia);
    put_f32(out + 50, (float)c->viscous);
    put_f32(out + 54, (float)c->coulomb);
    if (!c->protocol_minor) return HT_INFO_V20_SIZE;
    out[58] = c->protocol_minor;
    out[59] = c->estimator;
    put_u16(out + 60, 0);
    put_f32(out + 62, (float)c->velocity_cutoff);
    put_f32(out + 66, (float)c->acceleration_cutoff);
    put_f32(out + 70, (float)c->gains[0]);
    put_f32(out + 74, (float)c->gains[1]);
    put_f32(out + 78, (float)c->gains[2]);
    return seal(out, 82);
}

int ht_fw_control_in(ht_fw *fw, uint8_t request, uint16_t length, uint8_t *out) {
    uint8_t info[HT_INFO_SIZE];
    size_t n;
    if (request != HT_REQ_GET_INFO || length < HT_INFO_V20_SIZE) return -1;
    n = encode_info(fw, info);
    if (n > length) n = length; /* a 2.0 host asks for 58 bytes: the 2.0 part */
    copy(out, info, n);
    return (int)n;
}

static void begin_ramp(ht_fw *fw) {
    uint32_t samples = ((uint32_t)fw->cfg.ramp_ms * fw->cfg.rate_hz + 999u) / 1000u;
    fw->state = HT_STATE_RAMPING;
    /* + 1 for the sample where the ramp reaches zero, + delay for that zero to be applied */
    fw->ramp_left = (samples ? samples : 1u) + 1u + fw->cfg.delay;
}

static void start(ht_fw *fw, uint8_t mask) {
    clear_queue(fw);
    restart_loop(fw);
    fw->state = HT_STATE_RUNNING;
    fw->mask = mask;
    fw->flags = 0;
    fw->underruns = fw->overruns = fw->played = 0;
    fw->last_block_seq = fw->expected_seq = fw->since_block = 0;
    fw->end = 0;
    fw->table_mode = 0;
    fw->table = NULL;
    zero(fw->hold, sizeof fw->hold);
    fw->t_head = fw->t_count = 0;
}

int ht_fw_control_out(ht_fw *fw, uint8_t request, uint16_t value, const uint8_t *data,
                      uint16_t length) {
    if (request == HT_REQ_SET_LIMITS) {
        int finite = 1;
        float limit;
        uint32_t watchdog;
        if (length != HT_LIMITS_SIZE) return -1;
        limit = get_f32(data, &finite);
        watchdog = get_u16(data + 4);
        if (!finite || !(limit >= 0.0f)) return -1;
        if (watchdog < HT_WATCHDOG_MIN_MS || watchdog > HT_WATCHDOG_MAX_MS) return -1;
        fw->torque_limit = (ht_real)limit < fw->cfg.max_torque ? (ht_real)limit
                                                               : fw->cfg.max_torque;
        fw->watchdog_ms = (uint16_t)watchdog;
        return 0;
    }
    if (request == HT_REQ_START && !length) {
        if (!value || (value & ~(uint32_t)fw->cfg.channels)) return -1;
        start(fw, (uint8_t)value);
        return 0;
    }
    if (request == HT_REQ_STOP && !length) {
        clear_queue(fw);
        fw->end = 1;
        if (fw->state == HT_STATE_RUNNING) begin_ramp(fw);
        return 0;
    }
    return -1;
}

/* --- bulk OUT: coefficient blocks ----------------------------------------------------------- */

static int channel_count(uint32_t mask) {
    int n = 0;
    for (; mask; mask >>= 1) n += (int)(mask & 1u);
    return n;
}

void ht_fw_bulk_out(ht_fw *fw, const uint8_t *data, size_t length) {
    uint32_t mask, seq, n, flags, i;
    size_t body;
    int width, c;
    if (fw->state != HT_STATE_RUNNING || fw->end || fw->table_mode) return;
    /* decode: CRC, magic, version, mask, reserved flags, length */
    if (length < HT_BLOCK_HEADER_SIZE + HT_CRC_SIZE) goto bad;
    body = length - HT_CRC_SIZE;
    if (ht_crc32(data, body) != get_u32(data + body)) goto bad;
    if (data[0] != 'H' || data[1] != 'B' || data[2] != HT_PROTOCOL_VERSION) goto bad;
    mask = data[3];
    seq = get_u32(data + 4);
    n = get_u16(data + 8);
    flags = get_u16(data + 10);
    if (!mask || (mask & ~(uint32_t)HT_ALL_CHANNELS) || (flags & ~BLOCK_FLAG_END)) goto bad;
    width = channel_count(mask);
    if (body != HT_BLOCK_HEADER_SIZE + (size_t)4 * (size_t)width * n) goto bad;
    if (mask & ~(uint32_t)fw->mask) goto bad; /* a channel outside the START mask */
    if (seq != fw->expected_seq) fw->flags |= HT_FLAG_SEQUENCE;
    fw->expected_seq = seq + 1u;
    if (fw->q_count + n > fw->cfg.buffer_capacity) {
        fw->overruns++;
        fw->flags |= HT_FLAG_OVERRUN;
        return;
    }
    for (i = 0; i < n; i++) {
        float *row = fw->queue[(fw->q_head + fw->q_count + i) % HT_QUEUE_MAX];
        const uint8_t *p = data + HT_BLOCK_HEADER_SIZE + (size_t)4 * (size_t)width * i;
        int finite = 1;
        for (c = 0; c < 4; c++) {
            row[c] = 0.0f;
            if (mask & (1u << c)) {
                row[c] = get_f32(p, &finite);
                p += 4;
            }
        }
        if (!finite) { /* the whole sample becomes zero torque */
            zero(row, 4 * sizeof row[0]);
            fw->flags |= HT_FLAG_NON_FINITE;
        }
    }
    fw->q_count += n;
    fw->last_block_seq = seq;
    fw->since_block = 0;
    fw->end = (uint8_t)(flags & BLOCK_FLAG_END);
    return;
bad:
    fw->flags |= HT_FLAG_BAD_BLOCK;
}

/* --- the servo loop --------------------------------------------------------------------------- */

static ht_real clamp(ht_real v, ht_real limit) {
    return v > limit ? limit : (v < -limit ? -limit : v);
}

static void record(ht_fw *fw, ht_real angle, ht_real velocity, ht_real torque) {
    float *row;
    if (fw->t_count == HT_TELEMETRY_MAX) { /* nobody reads: the oldest sample is lost */
        fw->t_head = (fw->t_head + 1u) % HT_TELEMETRY_MAX;
        fw->t_count--;
    }
    row = fw->telemetry[(fw->t_head + fw->t_count) % HT_TELEMETRY_MAX];
    fw->t_count++;
    if (fw->cfg.kind == HT_KIND_VIBROTACTILE) angle = velocity = 0;
    row[0] = (float)angle;
    row[1] = (float)velocity;
    row[2] = (float)torque;
    fw->played++;
    fw->torque = torque;
}

/* One period: read the encoder, estimate, tau = (d - k*theta - b*theta_dot - m*theta_ddot) *
 * gain, clamp (NaN -> 0), apply it (a period later with D = 1), report it. */
static void servo(ht_fw *fw, const ht_real co[4], int use_mass, ht_real gain) {
    const ht_config *c = &fw->cfg;
    ht_real rate = (ht_real)c->rate_hz;
    ht_real meas = ht_hal_encoder_read(fw->port) - fw->anchor;
    ht_real m = 0, tau;
    fw->vel += c->velocity_gain * ((meas - fw->prev_meas) * rate - fw->vel);
    if (use_mass) {
        if (c->estimator == HT_ESTIMATOR_KALMAN || c->estimator == HT_ESTIMATOR_TRACKING) {
            /* predict with the acceleration held, correct by L times the reading's miss */
            ht_real t = (ht_real)1.0 / rate;
            ht_real p0 = fw->est_theta + t * fw->est_vel + t * t / (ht_real)2.0 * fw->acc;
            ht_real p1 = fw->est_vel + t * fw->acc;
            ht_real p2 = fw->acc;
            ht_real miss = meas - p0;
            fw->est_theta = p0 + c->gains[0] * miss;
            fw->est_vel = p1 + c->gains[1] * miss;
            fw->acc = p2 + c->gains[2] * miss;
        } else {
            fw->acc += c->acceleration_gain * ((fw->vel - fw->prev_vel) * rate - fw->acc);
            fw->prev_vel = fw->vel;
        }
        m = co[3];
    }
    fw->prev_meas = meas;
    tau = (co[0] - co[1] * meas - co[2] * fw->vel - m * fw->acc) * gain;
    if (tau > fw->tmax)
        tau = fw->tmax;
    else if (tau < -fw->tmax)
        tau = -fw->tmax;
    else if (tau != tau) /* NaN never reaches the motor */
        tau = 0;
    if (c->delay) {
        ht_real now = fw->pending;
        fw->pending = tau;
        tau = now;
    }
    ht_hal_torque_command(fw->port, tau);
#ifdef HT_TRACE
    ht_trace(fw->port, meas, fw->vel, tau);
#endif
    if (tau >= fw->tmax || tau <= -fw->tmax) fw->saturated = 1;
    record(fw, meas, fw->vel, tau);
}

static ht_real table_value(const ht_table *t, int which, uint32_t j) {
    if (t->values[which]) return (ht_real)t->values[which][j];
    if (t->counts[which]) return (ht_real)t->counts[which][j] * t->scales[which];
    return 0;
}

/* The coefficients at the angle the encoder reads: T, B, M interpolated linearly, ends held. */
static void table_lookup(ht_fw *fw, ht_real co[4]) {
    const ht_table *t = fw->table;
    ht_real meas = ht_hal_encoder_read(fw->port) - fw->anchor;
    ht_real x = (fw->origin + meas - t->start) * t->rate, f;
    ht_real tlast = (ht_real)(t->count - 1u);
    uint32_t j, nxt;
    int which, slot[3] = {0, 2, 3};
    co[0] = co[1] = co[2] = co[3] = 0;
    if (!t->count) return;
    j = x >= tlast ? t->count - 1u : (x > 0 ? (uint32_t)x : 0u); /* NaN reads entry 0 */
    f = (x > 0 && x < tlast) ? x - (ht_real)j : 0;
    nxt = j < t->count - 1u ? j + 1u : j;
    for (which = 0; which < 3; which++) {
        ht_real a = table_value(t, which, j);
        co[slot[which]] = a + f * (table_value(t, which, nxt) - a);
    }
}

/* The torque law while ramping or idle: the last one scaled by a gain falling from 1 to 0. */
static void ramp_sample(ht_fw *fw) {
    ht_real period = (ht_real)1.0 / (ht_real)fw->cfg.rate_hz;
    ht_real ramp = (ht_real)fw->cfg.ramp_ms / (ht_real)1000.0;
    ht_real gain = 0, co[4];
    int use_mass = fw->last_use_mass;
    if (ramp > 0) {
        gain = (ht_real)1.0 - ((ht_real)fw->idle * period) / ramp;
        gain = gain < 0 ? 0 : (gain > 1 ? 1 : gain);
    }
    fw->idle++;
    if (fw->table_mode) {
        table_lookup(fw, co);
        use_mass = fw->table->values[2] || fw->table->counts[2];
    } else {
        copy(co, fw->last, sizeof co);
    }
    servo(fw, co, use_mass, gain);
}

static uint32_t watchdog_samples(const ht_fw *fw) {
    uint32_t num = (uint32_t)fw->watchdog_ms * fw->cfg.rate_hz, q = num / 1000u;
    uint32_t r = num % 1000u;
    if (r > 500u || (r == 500u && (q & 1u))) q++; /* round half to even */
    return q ? q : 1u;
}

void ht_fw_tick(ht_fw *fw) {
    if (fw->state == HT_STATE_RUNNING && fw->table_mode) {
        ht_real co[4];
        table_lookup(fw, co);
        fw->idle = 0;
        fw->last_use_mass = fw->table->values[2] || fw->table->counts[2];
        servo(fw, co, fw->last_use_mass, 1);
        return;
    }
    if (fw->state == HT_STATE_RUNNING) {
        uint32_t limit = watchdog_samples(fw);
        if (!fw->end && fw->since_block >= limit) {
            fw->flags |= HT_FLAG_WATCHDOG;
            begin_ramp(fw);
        } else if (fw->end && !fw->q_count) {
            begin_ramp(fw);
        } else if (fw->cfg.wait_first_block && !fw->played && !fw->q_count) {
            fw->since_block++; /* the host's first transfer is on its way */
            ht_hal_torque_command(fw->port, 0);
            return;
        } else {
            ht_real co[4];
            int c;
            if (fw->q_count) {
                const float *row = fw->queue[fw->q_head];
                const ht_real limits[4] = {fw->cfg.max_torque, fw->cfg.max_stiffness,
                                           fw->cfg.max_damping, fw->cfg.max_mass};
                for (c = 0; c < 4; c++) fw->hold[c] = clamp((ht_real)row[c], limits[c]);
                fw->q_head = (fw->q_head + 1u) % HT_QUEUE_MAX;
                fw->q_count--;
            } else { /* the host is late: keep rendering the last sample */
                fw->underruns++;
                fw->flags |= HT_FLAG_UNDERRUN;
            }
            copy(co, fw->hold, sizeof co);
            copy(fw->last, co, sizeof co);
            fw->last_use_mass = (fw->mask & HT_CH_M) != 0;
            fw->since_block++;
            fw->idle = 0;
            servo(fw, co, fw->last_use_mass, 1);
            return;
        }
    }
    if (fw->state == HT_STATE_RAMPING && !--fw->ramp_left) fw->state = HT_STATE_IDLE;
    ramp_sample(fw);
}

/* --- bulk IN: telemetry reports ------------------------------------------------------------- */

int ht_fw_report_ready(const ht_fw *fw) { return fw->t_count >= fw->cfg.report_samples; }

size_t ht_fw_report(ht_fw *fw, uint8_t *out) {
    uint32_t n = fw->t_count < fw->cfg.report_samples ? fw->t_count : fw->cfg.report_samples;
    uint32_t i;
    out[0] = 'H';
    out[1] = 'T';
    out[2] = HT_PROTOCOL_VERSION;
    out[3] = fw->state;
    put_u32(out + 4, fw->report_seq);
    put_u32(out + 8, fw->played - fw->t_count);
    put_u16(out + 12, n);
    put_u16(out + 14, fw->flags | (fw->saturated ? HT_FLAG_SATURATED : 0u));
    put_u32(out + 16, fw->q_count);
    put_u32(out + 20, fw->underruns);
    put_u32(out + 24, fw->overruns);
    put_u32(out + 28, fw->last_block_seq);
    for (i = 0; i < n; i++) {
        const float *row = fw->telemetry[(fw->t_head + i) % HT_TELEMETRY_MAX];
        uint8_t *p = out + HT_REPORT_HEADER_SIZE + 12u * i;
        put_f32(p, row[0]);
        put_f32(p + 4, row[1]);
        put_f32(p + 8, row[2]);
    }
    fw->t_head = (fw->t_head + n) % HT_TELEMETRY_MAX;
    fw->t_count -= n;
    fw->report_seq++;
    fw->saturated = 0;
    return seal(out, HT_REPORT_HEADER_SIZE + 12u * n);
}

/* --- position mode -------------------------------------------------------------------------- */

void ht_fw_play_table(ht_fw *fw, const ht_table *table, ht_real origin) {
    start(fw, HT_CH_D);
    fw->table = table;
    fw->origin = origin;
    fw->table_mode = 1;
    fw->end = 1; /* no host streams: the watchdog does not watch */
}
