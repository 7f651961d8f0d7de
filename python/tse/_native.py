"""libtse_kin.so, found and loaded once, with ctypes alone (no numpy): the C side of tse.kin and of
tse.can's trajectory check, REJECT words and waits for rest (python/csrc), and the controller rates
those take.

It is found at $TSE_KIN_LIB, next to this package (an installed copy), or in a build directory
(build/host/python/libtse_kin.so beside the source tree's python/).
"""

import ctypes
import os
from pathlib import Path

from . import _protocol as _P

_lib = None


def find_library():
    """The path of libtse_kin.so; ImportError saying how to build it when there is none."""
    env = os.environ.get("TSE_KIN_LIB")
    if env:
        return Path(env)
    here = Path(__file__).resolve().parent
    candidates = [here / "libtse_kin.so"]
    root = here.parent.parent  # the source tree, when imported from python/
    for preset in ("host", "release"):
        candidates.append(root / "build" / preset / "python" / "libtse_kin.so")
    for c in candidates:
        if c.exists():
            return c
    raise ImportError("tse: libtse_kin.so not found; build the tse_kin_py target "
                      "(cmake --build --preset host) or set TSE_KIN_LIB to its path")


def load():
    """The library, loaded on first use."""
    global _lib
    if _lib is None:
        _lib = ctypes.CDLL(str(find_library()))
    return _lib


def built_in_rates():
    """(step_hz, segment_hz): the controller's built-in rates (firmware/include/fw/limits.h), which a
    controller whose firmware is older than INFO ran at, and what planning offline assumes."""
    r = (ctypes.c_uint * 2)()
    load().tse_py_rates_built_in(r)
    return r[0], r[1]


def checked_rates(rates):
    """rates as (step_hz, segment_hz) ints (None: built_in_rates()); ValueError for rates no
    controller runs at (a control segment of whole microseconds and whole step interrupts, within
    INFO's fields)."""
    if rates is None:
        return built_in_rates()
    try:
        step_hz, segment_hz = (int(x) for x in rates)
    except (TypeError, ValueError):
        raise ValueError(f"rates: (step_hz, segment_hz) in whole hertz, not {rates!r}") from None
    f = load().tse_py_rates_run
    f.restype = ctypes.c_int
    f.argtypes = [ctypes.c_uint, ctypes.c_uint]
    if not (0 < step_hz < 2 ** 32 and 0 < segment_hz < 2 ** 32) or not f(step_hz, segment_hz):
        top = {field[0]: field[4] for field in _P.MESSAGES["INFO"][3]}
        raise ValueError(f"rates: no controller runs at {step_hz} Hz step interrupts and {segment_hz} Hz control "
                         "segments (a segment of whole microseconds and whole step interrupts, step_hz up to "
                         f"{top['step_hz']}, segment_hz up to {top['segment_hz']}: INFO's fields)")
    return step_hz, segment_hz
