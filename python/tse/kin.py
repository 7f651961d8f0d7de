"""tse.kin: the TSE kinematics over numpy arrays.

The controller's kinematics library (kinematics/, the contract in docs/kinematics.md) through
ctypes, from libtse_kin.so (python/csrc): both precisions, and batch entry points that run the
per-pose loop in C.  Each row's answer is what `tse-kin` prints for that row, bit for bit.

Nothing is copied here from the C side: the status names, the parameter names, their spellings in
a parameter file and their rules are read from the library, and parameter sets are validated by
the library (the build of the precision asked for).

    import numpy as np
    from tse import kin
    r = kin.ik(np.array([[0.1, -0.05, 1.1, 0.1, -0.05, 0.2]]))
    r.status[0] == kin.Status.OK, r.q[0]          # slides s_a1, s_b1, ..., s_b3 [m]

ik and fk run a large batch on several threads (threads=None: one per CPU) with the GIL released;
the answers do not depend on the thread count.

The library is found at $TSE_KIN_LIB, next to this package (an installed copy), or in a build
directory (build/host/python/libtse_kin.so beside the source tree's python/): see tse/_native.py.
"""

import ctypes
import enum
import math
import os
from collections import namedtuple

from ._needs import need

np = need("numpy", "python3-numpy", "tse.kin")

from . import _native

__all__ = ["Status", "Params", "spellings", "IKResult", "FKResult", "JacobianResult", "ik", "fk", "jacobian", "haf",
           "sigma_z", "workspace", "workspace_points", "library_path"]

library_path = _native.find_library()
_lib = _native.load()

_dp = ctypes.POINTER(ctypes.c_double)
_ip = ctypes.POINTER(ctypes.c_int)
_lp = ctypes.POINTER(ctypes.c_long)
_c_int, _c_long, _c_char_p = ctypes.c_int, ctypes.c_long, ctypes.c_char_p


def _sig(name, restype, *argtypes):
    f = getattr(_lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


_status_count = _sig("tse_py_status_count", _c_int)
_status_name = _sig("tse_py_status_name", _c_char_p, _c_int)
_param_count = _sig("tse_py_param_count", _c_int)
_param_name = _sig("tse_py_param_name", _c_char_p, _c_int)
_param_key = _sig("tse_py_param_key", _c_char_p, _c_int, _ip, _ip, ctypes.POINTER(_c_char_p))
_params_default = _sig("tse_py_params_default", None, _dp)
_params_load = _sig("tse_py_params_load", _c_int, _c_char_p, _c_int, _dp, ctypes.c_char_p, ctypes.c_size_t)

_PRECISIONS = {"double": "_d", "float": "_f"}
_fn = {}
for _prec, _suf in _PRECISIONS.items():
    _fn[_prec] = {
        "check": _sig("tse_py_check" + _suf, _c_int, _dp),
        "ik": _sig("tse_py_ik" + _suf, _c_int, _dp, _c_long, _dp, _dp, _c_long, _c_int, _c_int, _ip, _ip, _dp),
        "fk": _sig("tse_py_fk" + _suf, _c_int, _dp, _c_long, _dp, _dp, _c_long, _c_int, _c_int, _ip, _ip, _dp),
        "jacobian": _sig("tse_py_jacobian" + _suf, _c_int, _dp, _c_long, _dp, _ip, _ip, _dp, _dp),
        "haf": _sig("tse_py_haf" + _suf, _c_int, _dp, _c_long, _dp, _ip, _dp),
        "sigma_z": _sig("tse_py_sigma_z" + _suf, _c_int, _dp, _c_long, _dp, _ip, _dp),
        "workspace": _sig("tse_py_workspace" + _suf, _c_int, _dp, _c_int, _c_int, _c_int, _dp, _ip, _lp, _lp),
        "workspace_points": _sig("tse_py_workspace_points" + _suf, _c_int, _dp, _c_int, _c_int, _c_int, _dp,
                                 _dp, _ip, _ip),
    }


class _StatusBase(enum.IntEnum):
    def __str__(self):
        return self.name.lower()


# The contract's statuses, in its order and with its names (tse_status_name): Status.OK,
# Status.UNREACHABLE, ...; str(Status.BELOW) == "below", Status["below".upper()].
Status = _StatusBase("Status", [(_status_name(i).decode().upper(), i) for i in range(_status_count())],
                     module=__name__)
Status.__doc__ = "Outcome of a kinematic computation, as kinematics.md names them (str() gives its name)."

_NPARAMS = _param_count()
_PARAM_NAMES = [_param_name(i + 1).decode() for i in range(_NPARAMS)]  # "L", "k1", ..., "nu_min"


def _keys():
    out, i = {}, 0
    while True:
        pid, deg, rule = _c_int(), _c_int(), _c_char_p()
        key = _param_key(i, ctypes.byref(pid), ctypes.byref(deg), ctypes.byref(rule))
        if key is None:
            return out
        out[key.decode()] = (pid.value, bool(deg.value), rule.value.decode())
        i += 1


_KEYS = _keys()  # spelling -> (parameter id, in degrees, rule in that spelling's unit)
_RULE = {pid: rule for (pid, deg, rule) in _KEYS.values() if not deg}


def spellings():
    """The keys a parameter file and Params take for the kinematic parameters, each with the
    parameter's SI name and whether its value is in degrees: {"eta_deg": ("eta", True), ...}
    (the library's table; files take them in any case)."""
    return {key: (_PARAM_NAMES[pid - 1], deg) for key, (pid, deg, _) in _KEYS.items()}


class Params:
    """One TSE design: the kinematic parameters of kinematics.md, in SI units and radians.

    Params(**values): the prototype's values (tse_params_default) with the keyword arguments given
    over them, under the names a parameter file uses (L, k1, eta, k3, k4, alpha_min, alpha_max,
    s_min, s_max, mu_min, nu_min; eta_deg, alpha_min_deg, alpha_max_deg in degrees).
    Params.from_file(path, design=False): a parameter file as tse-kin --params (or --design) reads it.
    The library validates the set (double build; a float call checks it again after rounding);
    a rejected set raises ValueError naming the parameter and its constraint.
    """

    __slots__ = ("_v",)

    def __init__(self, **values):
        v = (ctypes.c_double * _NPARAMS)()
        _params_default(v)
        given = {}
        for key, value in values.items():
            if key not in _KEYS:
                raise TypeError(f"Params: unknown parameter '{key}' (parameters: {', '.join(_KEYS)})")
            pid, deg, _ = _KEYS[key]
            if pid in given:
                raise TypeError(f"Params: '{key}' and '{given[pid]}' are the same parameter; give one of them")
            given[pid] = key
            x = float(value)
            v[pid - 1] = math.radians(x) if deg else x
        self._v = v
        self._check("double", given)

    @classmethod
    def from_file(cls, path, design=False):
        """A parameter file, read by the one reader tse-kin, tse-sim and tsectl share: ValueError with
        tse-kin's message (file and line) for a file it refuses, OSError for one it cannot read.
        design=False: the controller's parameter file, judged as tse-sim judges it (tse-kin --params:
        the same files are taken); design=True: a design to analyse, judged by kinematics.md's
        rules only (tse-kin --design)."""
        v = (ctypes.c_double * _NPARAMS)()
        err = ctypes.create_string_buffer(1024)
        r = _params_load(os.fsencode(path), 1 if design else 0, v, err, len(err))
        if r == -2:
            raise OSError(err.value.decode(errors="replace"))
        if r != 0:
            raise ValueError(err.value.decode(errors="replace"))
        self = cls.__new__(cls)
        self._v = v
        return self

    def _check(self, precision, given=None):
        bad = _fn[precision]["check"](self._v)
        if bad:
            _raise_invalid(self, bad, precision, given)

    def __getattr__(self, name):
        if name in _PARAM_NAMES:
            return self._v[_PARAM_NAMES.index(name)]
        raise AttributeError(name)

    def as_dict(self):
        """The values by parameter name (SI, radians)."""
        return {n: self._v[i] for i, n in enumerate(_PARAM_NAMES)}

    def replace(self, **values):
        """A copy with some values changed (same names as the constructor)."""
        d = self.as_dict()
        for key in values:
            if key in _KEYS:
                d.pop(_PARAM_NAMES[_KEYS[key][0] - 1], None)
        d.update(values)
        return Params(**d)

    def __eq__(self, other):
        return isinstance(other, Params) and list(self._v) == list(other._v)

    def __repr__(self):
        return "Params(" + ", ".join(f"{n}={self._v[i]!r}" for i, n in enumerate(_PARAM_NAMES)) + ")"


def _raise_invalid(params, bad, precision, given=None):
    name = _PARAM_NAMES[bad - 1]
    value = params._v[bad - 1]
    how = "" if (given is None or bad in given) else " (default value, invalid with the values given)"
    where = " in float precision" if precision == "float" else ""
    raise ValueError(f"{name} = {value!r} is invalid{where}{how} (needs {_RULE[bad]})")


_DEFAULT = None


def _params(params):
    global _DEFAULT
    if params is None:
        if _DEFAULT is None:
            _DEFAULT = Params()
        return _DEFAULT
    if not isinstance(params, Params):
        raise TypeError("params: a tse.kin.Params (or None for the prototype)")
    return params


def _fns(precision):
    try:
        return _fn[precision]
    except KeyError:
        raise ValueError(f"precision: 'double' or 'float', not {precision!r}") from None


def _rows(a, what, width=6):
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim == 1 and a.shape[0] == width:
        a = a.reshape(1, width)
    if a.ndim != 2 or a.shape[1] != width:
        raise ValueError(f"{what}: an (N, {width}) array (or one row of {width}), got shape {a.shape}")
    return a


def _seed(seed, n, warm):
    """(pointer, stride, keep-alive) for a seed of None, one row, or one row per pose."""
    if seed is None:
        return None, 0, None
    s = np.ascontiguousarray(seed, dtype=np.float64)
    if s.shape == (6,):
        return s.ctypes.data_as(_dp), 0, s
    if s.shape == (n, 6):
        if warm:
            raise ValueError("seed: one seed per row and warm=True exclude each other")
        return s.ctypes.data_as(_dp), 6, s
    raise ValueError(f"seed: None, one row of 6 or an ({n}, 6) array, got shape {s.shape}")


_MAX_THREADS = 64  # tse_py_batch.c's limit (TSE_PY_MAX_THREADS): no more are started


def _threads(threads):
    """The thread count for the library: None is os.cpu_count(), else a whole number >= 1."""
    if threads is None:
        return min(os.cpu_count() or 1, _MAX_THREADS)
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise ValueError(f"threads: None (one per CPU) or a whole number >= 1, not {threads!r}")
    return int(min(threads, _MAX_THREADS))


def _call(fns, name, params, precision, *args):
    bad = fns[name](params._v, *args)
    if bad:
        _raise_invalid(params, bad, precision)


def _p(a, t=_dp):
    return a.ctypes.data_as(t)


IKResult = namedtuple("IKResult", "status scissor q")
IKResult.__doc__ = """status: (N,) int32 of Status values; scissor: (N,) first failing scissor 1..3, 0 when ok;
q: (N, 6) slides s_a1, s_b1, s_a2, s_b2, s_a3, s_b3 [m] as the library returned them (NaN where none)."""
FKResult = namedtuple("FKResult", "status scissor pose")
FKResult.__doc__ = """status, scissor as IKResult's; pose: (N, 6) x, y, z, roll, pitch, yaw, NaN unless ok."""
JacobianResult = namedtuple("JacobianResult", "status scissor J sv")
JacobianResult.__doc__ = """J: (N, 6, 6) dq/dp (rows s_a1..s_b3, columns x..yaw); sv: (N, 6) singular values of
dp/dq, descending; NaN unless ok."""


def ik(poses, seed=None, params=None, precision="double", warm=False, threads=None):
    """Inverse kinematics of poses (N, 6): x, y, z [m], roll, pitch, yaw [rad], R = Rz Ry Rx.

    seed: None (every row from the home configuration, as `tse-kin ik`), one slide vector (6,)
    for every row, or one per row (N, 6).  warm=True: a row after one that came back ok is seeded
    with that row's slides, as a controller stepping along a path (the first row, and rows after a
    failure, with `seed`).
    threads: how many threads the library may use, None for os.cpu_count(), 1 for the calling
    thread only.  Rows are cut into contiguous chunks, one per thread; a batch of fewer than 4096
    rows, and a warm batch (each row waits for the one before it), run on the calling thread.  The
    answers are the same whatever the count.  The GIL is released during the computation (ctypes
    releases it around every call into the library), so other Python threads run meanwhile.
    Returns IKResult(status, scissor, q)."""
    fns, params, nthreads = _fns(precision), _params(params), _threads(threads)
    p = _rows(poses, "poses")
    n = p.shape[0]
    sp, stride, keep = _seed(seed, n, warm)
    status = np.empty(n, dtype=np.intc)
    scissor = np.empty(n, dtype=np.intc)
    q = np.empty((n, 6), dtype=np.float64)
    _call(fns, "ik", params, precision, n, _p(p), sp, stride, int(bool(warm)), nthreads, _p(status, _ip),
          _p(scissor, _ip), _p(q))
    del keep
    return IKResult(status, scissor, q)


def fk(q, seed=None, params=None, precision="double", warm=False, threads=None):
    """Forward kinematics of slides q (N, 6).  seed: None (the home pose), one pose (6,) or one per
    row (N, 6); warm=True seeds a row after an ok one with that row's pose.  threads as in ik():
    None for os.cpu_count(), 1 for the calling thread only; warm batches and batches of fewer than
    4096 rows run on the calling thread; the answers do not depend on it.  The library checks
    its answer with the inverse kinematics: pose is NaN unless status is ok.  Returns FKResult."""
    fns, params, nthreads = _fns(precision), _params(params), _threads(threads)
    a = _rows(q, "q")
    n = a.shape[0]
    sp, stride, keep = _seed(seed, n, warm)
    status = np.empty(n, dtype=np.intc)
    scissor = np.empty(n, dtype=np.intc)
    pose = np.empty((n, 6), dtype=np.float64)
    _call(fns, "fk", params, precision, n, _p(a), sp, stride, int(bool(warm)), nthreads, _p(status, _ip),
          _p(scissor, _ip), _p(pose))
    del keep
    return FKResult(status, scissor, pose)


def jacobian(poses, params=None, precision="double"):
    """dq/dp at each pose (N, 6), its slides solved from home (as `tse-kin jacobian`), and the
    singular values of dp/dq.  Returns JacobianResult(status, scissor, J, sv)."""
    fns, params = _fns(precision), _params(params)
    p = _rows(poses, "poses")
    n = p.shape[0]
    status = np.empty(n, dtype=np.intc)
    scissor = np.empty(n, dtype=np.intc)
    J = np.empty((n, 6, 6), dtype=np.float64)
    sv = np.empty((n, 6), dtype=np.float64)
    _call(fns, "jacobian", params, precision, n, _p(p), _p(status, _ip), _p(scissor, _ip), _p(J), _p(sv))
    return JacobianResult(status, scissor, J, sv)


def _per_height(name, z, params, precision):
    fns, params = _fns(precision), _params(params)
    zz = np.ascontiguousarray(np.atleast_1d(z), dtype=np.float64).ravel()
    status = np.empty(zz.shape[0], dtype=np.intc)
    out = np.empty(zz.shape[0], dtype=np.float64)
    _call(fns, name, params, precision, zz.shape[0], _p(zz), _p(status, _ip), _p(out))
    return status, out


def haf(z, params=None, precision="double"):
    """The paper's Height Amplification Factor at heights z [m] (scalar or array):
    (status, haf) arrays, haf NaN unless ok."""
    return _per_height("haf", z, params, precision)


def sigma_z(z, params=None, precision="double"):
    """The vertical spatial gear ratio at (0, 0, z, 0, 0, 0): (status, sigma_z) arrays."""
    return _per_height("sigma_z", z, params, precision)


def _orientation(orientation):
    o = np.ascontiguousarray(orientation, dtype=np.float64)
    if o.shape != (3,):
        raise ValueError(f"orientation: roll, pitch, yaw (3 numbers), got shape {o.shape}")
    return o


def workspace(n_r=11, n_phi=24, n_z=21, orientation=(0.0, 0.0, 0.0), params=None, precision="double"):
    """The paper's workspace count on its cylindrical grid at a fixed orientation: (reachable,
    total); the fraction is reachable / total.  ValueError for a grid the library refuses."""
    fns, params = _fns(precision), _params(params)
    o = _orientation(orientation)
    st, reach, total = _c_int(), _c_long(), _c_long()
    _call(fns, "workspace", params, precision, int(n_r), int(n_phi), int(n_z), _p(o), ctypes.byref(st),
          ctypes.byref(reach), ctypes.byref(total))
    if st.value != Status.OK:
        raise ValueError(f"workspace: {Status(st.value)} (needs n_r >= 2, n_phi >= 1, n_z >= 2 and a finite "
                         "orientation)")
    return reach.value, total.value


def workspace_points(n_r=11, n_phi=24, n_z=21, orientation=(0.0, 0.0, 0.0), params=None, precision="double"):
    """Every point of that grid, (i, j, k) with k fastest: (poses (M, 6), status, scissor) from the
    inverse kinematics without a seed, what workspace() counts."""
    fns, params = _fns(precision), _params(params)
    o = _orientation(orientation)
    if int(n_r) < 2 or int(n_phi) < 1 or int(n_z) < 2:
        raise ValueError("workspace_points: needs n_r >= 2, n_phi >= 1, n_z >= 2")
    m = int(n_r) * int(n_phi) * int(n_z)
    pose = np.empty((m, 6), dtype=np.float64)
    status = np.empty(m, dtype=np.intc)
    scissor = np.empty(m, dtype=np.intc)
    _call(fns, "workspace_points", params, precision, int(n_r), int(n_phi), int(n_z), _p(o), _p(pose),
          _p(status, _ip), _p(scissor, _ip))
    return pose, status, scissor
