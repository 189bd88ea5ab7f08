"""Simulation of the equivalent pendulums driven by a container motion.

- `sloshkit.sim.equations`: the equations of motion (one right-hand side per model family).
- `sloshkit.sim.discretisation`: exact first-order-hold discretisation of the linear pendulum.
- `sloshkit.sim.simulate`: `simulate` (one motion, time histories) and the cart-pendulum.
- `sloshkit.sim.batch`: metrics of many linear cases at once (numba kernel).
- `sloshkit.sim.metrics`: time grid, residual amplitude, wall elevation.
- `sloshkit.sim.response`: `SloshResponse` and `CartPendulumResponse`.
"""
