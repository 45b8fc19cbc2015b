/* The host port: the HAL over a simulated motor and hand, for the emulated pyusb device and the
 * tests. The motor and the hand are the simulated knob's (device/sim: its plant map over one
 * period, Coulomb friction, a pushing or turning hand), handed over from Python; this file only
 * steps them, so the firmware's loop and the simulator's are the same arithmetic. */
#include <math.h>
#include <string.h>

#include "../../ht_hal.h"

typedef struct {
    double theta, omega, r;          /* true angle, speed, the hand's grip target */
    double speed, push, push_ramp;   /* the hand: turning speed, push torque and its ramp */
    double period, quantum, coulomb; /* the rotor's constants */
    double map[10];                  /* the theta row then the omega row over [theta omega u r v] */
    uint32_t samples;                /* periods since the hand was set (START) */
    double *trace;                   /* (angle, velocity, torque) per period, when set */
    uint32_t trace_cap, trace_len;
} ht_sim;

size_t ht_sim_size(void) { return sizeof(ht_sim); }

void ht_sim_init(ht_sim *sim, const double map[10], double period, double quantum,
                 double coulomb) {
    memset(sim, 0, sizeof *sim);
    memcpy(sim->map, map, sizeof sim->map);
    sim->period = period;
    sim->quantum = quantum;
    sim->coulomb = coulomb;
}

/* A new hand from now on (the plant's map with its grip and inertia, its push and speed);
 * its grip target starts at the knob's angle. */
void ht_sim_set_hand(ht_sim *sim, const double map[10], double push, double push_ramp,
                     double speed) {
    memcpy(sim->map, map, sizeof sim->map);
    sim->push = push;
    sim->push_ramp = push_ramp;
    sim->speed = speed;
    sim->r = sim->theta;
    sim->samples = 0;
}

void ht_sim_set_trace(ht_sim *sim, double *trace, uint32_t capacity) {
    sim->trace = trace;
    sim->trace_cap = capacity;
    sim->trace_len = 0;
}

uint32_t ht_sim_trace_len(const ht_sim *sim) { return sim->trace_len; }

double ht_sim_theta(const ht_sim *sim) { return sim->theta; }

ht_real ht_hal_encoder_read(void *port) {
    const ht_sim *sim = (const ht_sim *)port;
    double q = sim->quantum;
    return q ? floor(sim->theta * (1.0 / q) + 0.5) * q : sim->theta;
}

/* Hold the torque over one period: the hand's push, Coulomb friction as the torque (within
 * its level) that would stop the rotor in the period, then the plant's linear map. */
void ht_hal_torque_command(void *port, ht_real torque) {
    ht_sim *sim = (ht_sim *)port;
    const double *t = sim->map, *w = sim->map + 5;
    double u = torque, free;
    if (sim->push) {
        double elapsed = (double)sim->samples * sim->period;
        u += elapsed >= sim->push_ramp ? sim->push : sim->push * elapsed / sim->push_ramp;
    }
    free = w[0] * sim->theta + w[1] * sim->omega + w[2] * u + w[3] * sim->r + w[4] * sim->speed;
    if (sim->coulomb) {
        double fr = -free / w[2];
        fr = fr > sim->coulomb ? sim->coulomb : (fr < -sim->coulomb ? -sim->coulomb : fr);
        u += fr;
        free += w[2] * fr;
    }
    sim->theta = t[0] * sim->theta + t[1] * sim->omega + t[2] * u + t[3] * sim->r +
                 t[4] * sim->speed;
    sim->omega = free;
    sim->r += sim->speed * sim->period;
    sim->samples++;
}

void ht_trace(void *port, ht_real angle, ht_real velocity, ht_real torque) {
    ht_sim *sim = (ht_sim *)port;
    if (sim->trace && sim->trace_len < sim->trace_cap) {
        double *row = sim->trace + 3u * sim->trace_len++;
        row[0] = angle;
        row[1] = velocity;
        row[2] = torque;
    }
}

/* n servo periods. */
void ht_sim_run(ht_fw *fw, uint32_t n) {
    while (n--) ht_fw_tick(fw);
}

/* What the emulation reads of the firmware's state, in one call. */
void ht_sim_status(const ht_fw *fw, uint32_t out[11], double reals[2]) {
    out[0] = fw->state;
    out[1] = fw->flags;
    out[2] = fw->underruns;
    out[3] = fw->overruns;
    out[4] = fw->played;
    out[5] = fw->q_count;
    out[6] = fw->t_count;
    out[7] = fw->mask;
    out[8] = fw->last_block_seq;
    out[9] = fw->watchdog_ms;
    out[10] = fw->saturated;
    reals[0] = fw->torque;
    reals[1] = fw->torque_limit;
}
