/* The hardware abstraction the firmware calls: a port implements these two functions.
 *
 * USB endpoint I/O goes the other way: the port's USB stack calls ht_fw_control_in/out,
 * ht_fw_bulk_out and ht_fw_report (ht_fw.h), and its timer calls ht_fw_tick at the rate.
 * `port` is the pointer handed to ht_fw_init. */
#ifndef HT_HAL_H
#define HT_HAL_H

#include "ht_fw.h"

/* The encoder's absolute angle now, rad (as the sensor quantises it). */
ht_real ht_hal_encoder_read(void *port);

/* Apply this motor torque (N*m; a vibrotactile driver: -1..+1 of full scale) until the next
 * call. Always finite and within the limit. */
void ht_hal_torque_command(void *port, ht_real torque);

#ifdef HT_TRACE
/* Host builds only: each period's reading (rad from the anchor), velocity estimate and applied
 * torque in full precision, for comparing the loop with the simulated knob. */
void ht_trace(void *port, ht_real angle, ht_real velocity, ht_real torque);
#endif

#endif /* HT_HAL_H */
