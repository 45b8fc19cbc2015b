// An example port of the haptic-timeline knob firmware to SimpleFOC (Arduino), as a sketch.
//
// NOT TESTED ON HARDWARE: it shows where each piece of the HAL goes (docs/firmware.md, "Porting").
// Written against SimpleFOC 2.3 (BLDCMotor, MagneticSensorSPI, torque control) and Adafruit
// TinyUSB's vendor class (tud_vendor_*), on an STM32 board (STM32duino's HardwareTimer).
// Copy ht_fw.c, ht_fw.h and ht_hal.h beside this file; for position mode also an exported
// table (`haptic-timeline export fan_knob.htl -o fan_knob.h`). Build with -DHT_REAL_FLOAT.
#include <Adafruit_TinyUSB.h>
#include <SimpleFOC.h>

extern "C" {
#include "ht_fw.h"
#include "ht_hal.h"
}
#include "fan_knob.h"  // position mode's tables: FAN_KNOB_COUNT, _START, _RATE, fan_knob_torque...

// --- the motor: fill in your board's pins and your motor's constants ---------------------------
static const float KT = 0.05f;     // N*m per A of the motor (datasheet): torque -> current
static const float MAX_TORQUE = 0.18f;  // N*m the amplifier and motor may give continuously
BLDCMotor motor(7);                        // pole pairs
BLDCDriver3PWM driver(PA8, PA9, PA10, PB12);
MagneticSensorSPI sensor(AS5047_SPI, PA4);  // 14-bit: 2*pi/16384 rad per count
InlineCurrentSense current(0.01f, 50.0f, PA0, PA1);

static ht_fw knob;                  // the whole firmware state, static (no heap)
static volatile float target = 0;  // A: the last torque command, for the FOC loop
static uint8_t packet[1300];        // one block or one report (at most 512-sample blocks: bigger)
HardwareTimer servo(TIM2);

// --- the HAL: two functions (ht_hal.h) --------------------------------------------------------
ht_real ht_hal_encoder_read(void *port) {
  (void)port;
  return sensor.getAngle();  // rad, with full turns; updated by loopFOC's sensor.update()
}

void ht_hal_torque_command(void *port, ht_real torque) {
  (void)port;
  target = torque / KT;  // finite and within MAX_TORQUE: the firmware guarantees it
}

static void tick() { ht_fw_tick(&knob); }  // 10 kHz, from the timer's interrupt

// --- USB: TinyUSB's vendor class calls these ---------------------------------------------------
extern "C" bool tud_vendor_control_xfer_cb(uint8_t rhport, uint8_t stage,
                                           tusb_control_request_t const *request) {
  static uint8_t data[HT_INFO_SIZE];
  if (request->bmRequestType_bit.type != TUSB_REQ_TYPE_VENDOR) return false;
  if (request->bmRequestType_bit.direction == TUSB_DIR_IN) {
    if (stage != CONTROL_STAGE_SETUP) return true;
    servo.pause();  // ht_fw_* calls never run while ht_fw_tick does
    int n = ht_fw_control_in(&knob, request->bRequest, request->wLength, data);
    servo.resume();
    return n >= 0 && tud_control_xfer(rhport, request, data, (uint16_t)n);  // false: STALL
  }
  // OUT: START and STOP carry no data (act at SETUP); SET_LIMITS acts when its 8 bytes arrive
  bool act = request->wLength ? stage == CONTROL_STAGE_DATA : stage == CONTROL_STAGE_SETUP;
  if (!act) {
    if (stage != CONTROL_STAGE_SETUP) return true;
    return request->wLength <= sizeof data &&
           tud_control_xfer(rhport, request, data, request->wLength);
  }
  servo.pause();
  int done = ht_fw_control_out(&knob, request->bRequest, request->wValue, data,
                               request->wLength);
  servo.resume();
  if (done) return false;  // STALL: refused, nothing changed
  return request->wLength ? true : tud_control_status(rhport, request);
}

static void usb_poll() {
  // Bulk OUT: one transfer is one block; a real port collects packets until a short one.
  uint32_t n = tud_vendor_available() ? tud_vendor_read(packet, sizeof packet) : 0;
  if (n) {
    servo.pause();
    ht_fw_bulk_out(&knob, packet, n);
    servo.resume();
  }
  // Bulk IN: a report as soon as one report's worth of samples has played.
  if (ht_fw_report_ready(&knob) && tud_vendor_write_available() >= HT_REPORT_HEADER_SIZE + 1204u) {
    servo.pause();
    size_t len = ht_fw_report(&knob, packet);
    servo.resume();
    tud_vendor_write(packet, len);
    tud_vendor_flush();
  }
}

// --- set-up and the FOC loop --------------------------------------------------------------------
static const ht_table fan = {
    FAN_KNOB_COUNT, FAN_KNOB_START, FAN_KNOB_RATE,
    {fan_knob_torque, fan_knob_damping, fan_knob_mass}, {0, 0, 0}, {0, 0, 0}};

void setup() {
  TinyUSBDevice.setID(0x1209, 0x0001);  // pid.codes' TEST PID: register your own to ship
  sensor.init();
  motor.linkSensor(&sensor);
  driver.voltage_power_supply = 12;
  driver.init();
  motor.linkDriver(&driver);
  current.linkDriver(&driver);
  current.init();
  motor.linkCurrentSense(&current);
  motor.torque_controller = TorqueControlType::foc_current;
  motor.controller = MotionControlType::torque;
  motor.current_limit = MAX_TORQUE / KT;
  motor.init();
  motor.initFOC();

  ht_config cfg = {};
  cfg.kind = HT_KIND_KINESTHETIC;
  cfg.channels = HT_ALL_CHANNELS;
  cfg.delay = 1;  // the torque computed in one tick is applied by the FOC loop after it
  cfg.protocol_minor = 1;
  cfg.estimator = HT_ESTIMATOR_KALMAN;
  cfg.wait_first_block = 1;
  cfg.firmware_major = 1;
  cfg.rate_hz = 10000;
  cfg.buffer_capacity = HT_QUEUE_MAX;  // build with -DHT_QUEUE_MAX=1024 -DHT_TELEMETRY_MAX=512
  cfg.max_block = 512;
  cfg.report_samples = 100;
  cfg.watchdog_ms = 50;
  cfg.ramp_ms = 10;
  cfg.max_torque = MAX_TORQUE;
  cfg.max_stiffness = 100;
  cfg.max_damping = 1;
  cfg.max_mass = 1e-2f;
  cfg.encoder_resolution = 2 * PI / 16384;
  cfg.inertia = 1e-5f;   // measure yours: the host's stability checks use these three
  cfg.viscous = 1e-4f;
  cfg.coulomb = 1e-3f;
  cfg.velocity_cutoff = 2000;
  cfg.velocity_gain = 1 - expf(-2 * PI * cfg.velocity_cutoff / cfg.rate_hz);
  cfg.gains[0] = 0.5263614f;  // the Kalman gain the host declares for 10 kHz (docs/firmware.md)
  cfg.gains[1] = 1944.2095f;
  cfg.gains[2] = 3590641.8f;
  ht_fw_init(&knob, &cfg, nullptr);

  servo.setOverflow(10000, HERTZ_FORMAT);
  servo.attachInterrupt(tick);
  servo.resume();
  delay(500);
  if (!TinyUSBDevice.mounted()) ht_fw_play_table(&knob, &fan, 0.0f);  // no host: position mode
}

void loop() {
  motor.loopFOC();       // reads the sensor, runs the current loop
  motor.move(target);    // the torque the firmware commanded, as a current
  usb_poll();
}
