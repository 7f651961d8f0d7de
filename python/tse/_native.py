"""libtse_kin.so, found and loaded once, with ctypes alone (no numpy): the C side of tse.kin and of
tse.can's trajectory check, REJECT words and waits for rest (python/csrc).

It is found at $TSE_KIN_LIB, next to this package (an installed copy), or in a build directory
(build/host/python/libtse_kin.so beside the source tree's python/).
"""

import ctypes
import os
from pathlib import Path

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
