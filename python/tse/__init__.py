"""The Triple Scissor Extender from Python.

tse.kin: the kinematics library (the controller's own C code, double and float builds) over numpy
arrays, through ctypes and libtse_kin.so.  See tse/kin.py.
tse.plan: waypoints to a trajectory the controller accepts, near the fastest (the planner of
`tse-kin plan`, through libtse_kin.so).  See tse/plan.py.
tse.can: a controller on a CAN bus through python-can (enable, home, move, trajectories,
telemetry, parameters), its frames packed from the protocol table protogen prints
(tse/_protocol.py).  See tse/can.py.

Neither is imported by `import tse`: tse.can needs no numpy, tse.kin no python-can.
"""

__all__ = ["kin", "plan", "can"]
