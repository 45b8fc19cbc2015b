"""The simulated knob's benchmarks (integrators, speed, estimators), registered for
`haptic-timeline bench` through the `haptic_timeline.benchmarks` entry point group."""
