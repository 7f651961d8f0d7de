"""The Triple Scissor Extender from Python.

tse.kin: the kinematics library (the controller's own C code, double and float builds) over numpy
arrays, through ctypes and libtse_kin.so.  See tse/kin.py.
"""

__all__ = ["kin"]
