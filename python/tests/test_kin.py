"""tse.kin against tse-kin, the contract, and its own promises.

Expectations come from outside tse.kin: tse-kin's %.17g output for the same rows (same precision,
same seeds: the same bits), the contract's worked values and status names (docs/kinematics.md),
and the parameter rules it states.  The batch speed is printed, not asserted."""
import math
import subprocess
import time

import numpy as np
import pytest

from tse import kin

CONTRACT_STATUSES = ["ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular", "degenerate",
                     "noconverge"]
PRECISIONS = ["double", "float"]


def random_poses(n, seed):
    """Poses over and beyond the prototype's workspace, so that every status shows up: most
    reachable, some below the base, beyond the stops or the stroke, tilted into singularities."""
    rng = np.random.default_rng(seed)
    p = np.empty((n, 6))
    p[:, 0:2] = rng.uniform(-0.5, 0.5, (n, 2))
    p[:, 2] = rng.uniform(-0.1, 1.8, n)
    p[:, 3:5] = rng.uniform(-0.8, 0.8, (n, 2))
    p[:, 5] = rng.uniform(-math.pi, math.pi, n)
    near = rng.random(n) < 0.5  # half of them close to the middle of the workspace
    p[near, 0:2] *= 0.2
    p[near, 2] = rng.uniform(0.6, 1.4, near.sum())
    p[near, 3:6] *= 0.2
    return p


def run_cli(cli, command, rows, precision, params_file=None):
    text = "".join(",".join("%.17g" % x for x in row) + "\n" for row in rows)
    args = [cli, command, "--precision", precision]
    if params_file:
        args += ["--params", str(params_file)]
    out = subprocess.run(args, input=text, capture_output=True, text=True, check=True).stdout
    lines = out.splitlines()
    assert len(lines) == len(rows)
    status = [l.split(",")[0] for l in lines]
    scissor = np.array([int(l.split(",")[1]) for l in lines])
    values = np.array([[float(x) for x in l.split(",")[2:]] for l in lines])
    return status, scissor, values


def same_bits(a, b):
    """Equal to the last bit, NaN equal to NaN."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    both_nan = np.isnan(a) & np.isnan(b)
    return np.array_equal(np.where(both_nan, 0.0, a).view(np.int64), np.where(both_nan, 0.0, b).view(np.int64))


def test_statuses_are_the_contracts():
    assert [str(s) for s in kin.Status] == CONTRACT_STATUSES
    assert [s.value for s in kin.Status] == list(range(len(CONTRACT_STATUSES)))
    assert kin.Status.UNREACHABLE == 2 and str(kin.Status.BELOW) == "below"


@pytest.mark.parametrize("precision", PRECISIONS)
def test_ik_matches_tse_kin(tse_kin_cli, precision):
    poses = random_poses(4000, 12)
    poses[:3] = [[math.nan, 0, 1, 0, 0, 0], [0, 0, math.inf, 0, 0, 0], [0, 0, 1e75, 0, 0, 0]]
    r = kin.ik(poses, precision=precision)
    status, scissor, q = run_cli(tse_kin_cli, "ik", poses, precision)
    assert [str(kin.Status(s)) for s in r.status] == status
    assert np.array_equal(r.scissor, scissor)
    assert same_bits(r.q, q)
    seen = {str(kin.Status(s)) for s in r.status}
    assert {"ok", "invalid", "unreachable", "below", "alpha"} <= seen, seen
    print(f"\n[{precision}] statuses over {len(poses)} poses:",
          {s: int(np.sum(r.status == kin.Status[s.upper()])) for s in CONTRACT_STATUSES})


@pytest.mark.parametrize("precision", PRECISIONS)
def test_fk_matches_tse_kin(tse_kin_cli, precision):
    poses = random_poses(3000, 34)
    r = kin.ik(poses, precision=precision)
    ok = r.status == kin.Status.OK
    q = r.q[ok]
    # Seeds: the pose itself moved a little (as the last pose of a path), and no seed.
    rng = np.random.default_rng(5)
    seeds = poses[ok] + rng.normal(0, 0.02, (q.shape[0], 6))
    f = kin.fk(q, seed=seeds, precision=precision)
    status, scissor, pose = run_cli(tse_kin_cli, "fk", np.hstack([q, seeds]), precision)
    assert [str(kin.Status(s)) for s in f.status] == status
    assert np.array_equal(f.scissor, scissor)
    assert same_bits(f.pose, pose)
    f0 = kin.fk(q[:500], precision=precision)
    status, scissor, pose = run_cli(tse_kin_cli, "fk", q[:500], precision)
    assert [str(kin.Status(s)) for s in f0.status] == status
    assert same_bits(f0.pose, pose)


def test_contract_worked_values():
    r = kin.ik([[0, 0, 1.0, 0, 0, 0], [0.1, -0.05, 1.1, 0.1, -0.05, 0.2]])
    assert list(r.status) == [kin.Status.OK, kin.Status.OK]
    assert np.all(np.abs(r.q[0] - 0.43015083911167) <= 1e-9)
    expect = [0.39127069075903, 0.41631844093909, 0.38241559603276, 0.42099161248302, 0.56558364785006,
              0.23697220292616]
    assert np.all(np.abs(r.q[1] - expect) <= 1e-9)
    f = kin.fk(r.q[1:])
    assert f.status[0] == kin.Status.OK
    assert np.all(np.abs(f.pose[0] - [0.1, -0.05, 1.1, 0.1, -0.05, 0.2]) <= 1e-9)


@pytest.mark.parametrize("precision", PRECISIONS)
def test_warm_start_is_the_last_ok_rows_seed(precision):
    """warm=True: each row is solved as a single call seeded with the last ok row's slides."""
    t = np.linspace(0, 1, 300)[:, None]
    path = np.hstack([0.2 * np.sin(3 * t), 0.1 * t, 0.7 + 0.6 * t, 0.3 * t, -0.2 * t, np.cos(2 * t)])
    path[100] = [0, 0, -1, 0, 0, 0]  # a failure in the middle: the next row keeps the last good seed
    w = kin.ik(path, warm=True, precision=precision)
    last = None
    for i in range(len(path)):
        one = kin.ik(path[i], seed=last, precision=precision)
        assert one.status[0] == w.status[i] and same_bits(one.q[0], w.q[i]), i
        if one.status[0] == kin.Status.OK:
            last = one.q[0]
    assert w.status[100] == kin.Status.BELOW


def test_jacobian_haf_workspace_shapes_and_values():
    poses = random_poses(200, 9)
    ikr = kin.ik(poses)
    j = kin.jacobian(poses)
    assert j.J.shape == (200, 6, 6) and j.sv.shape == (200, 6)
    ok = ikr.status == kin.Status.OK
    assert np.all(j.status[~ok] == ikr.status[~ok])
    # Finite differences of the inverse kinematics agree with the analytic dq/dp.
    i = int(np.flatnonzero(j.status == kin.Status.OK)[0])
    h = 1e-6
    fd = np.empty((6, 6))
    for c in range(6):
        dp = np.zeros(6)
        dp[c] = h
        fd[:, c] = (kin.ik(poses[i] + dp).q[0] - kin.ik(poses[i] - dp).q[0]) / (2 * h)
    assert np.allclose(fd, j.J[i], atol=1e-6)
    st, h = kin.haf([0.8, 1.0, -1.0])
    assert list(st[:2]) == [0, 0] and np.all(h[:2] > 0)
    reach, total = kin.workspace(5, 8, 6)
    pts, st, _ = kin.workspace_points(5, 8, 6)
    assert total == 5 * 8 * 6 == len(pts)
    assert reach == int(np.sum(st == kin.Status.OK))


def test_params_keywords_and_file(tmp_path):
    p = kin.Params(L=1.5, eta_deg=25, mu_min=0.1)
    assert p.L == 1.5 and p.eta == math.radians(25) and p.mu_min == 0.1
    f = tmp_path / "design.params"
    f.write_text("# a design\nL = 1.5\neta_deg = 25\nmu_min = 0.1\nslide_vmax = 0.1\n")
    assert kin.Params.from_file(f) == p
    poses = random_poses(500, 3)
    assert same_bits(kin.ik(poses, params=p).q, kin.ik(poses, params=kin.Params.from_file(f)).q)


def test_params_against_tse_kin_params_file(tse_kin_cli, tmp_path):
    f = tmp_path / "d.params"
    f.write_text("L = 1.4\nk1 = 0.3\nalpha_max_deg = 65\nk4 = 0.1\n")
    poses = random_poses(1000, 77)
    for precision in PRECISIONS:
        r = kin.ik(poses, params=kin.Params.from_file(f), precision=precision)
        status, _, q = run_cli(tse_kin_cli, "ik", poses, precision, params_file=f)
        assert [str(kin.Status(s)) for s in r.status] == status
        assert same_bits(r.q, q)


# The contract's rules ("Valid parameter sets" and the margins): one violation each.
BAD = [
    ({"L": 0}, "L", "L > 0"),
    ({"L": -1}, "L", "L > 0"),
    ({"k1": 0}, "k1", "0 < k1 <= 1"),
    ({"k1": 1.01}, "k1", "0 < k1 <= 1"),
    ({"eta": math.pi / 2}, "eta", "-pi/2 < eta < pi/2"),
    ({"eta_deg": -90}, "eta", "-pi/2 < eta < pi/2"),
    ({"k3": -0.01}, "k3", "k3 >= 0"),
    ({"k4": 0}, "k4", "k4 > 0"),
    ({"alpha_min": 0}, "alpha_min", "0 < alpha_min < pi/2"),
    ({"alpha_max": 0.1}, "alpha_max", "alpha_min < alpha_max < pi/2"),
    ({"alpha_max_deg": 90}, "alpha_max", "alpha_min < alpha_max < pi/2"),
    ({"s_min": -0.1}, "s_min", "s_min >= 0"),
    ({"s_max": 0}, "s_max", "s_min < s_max"),
    ({"mu_min": 1}, "mu_min", "0 <= mu_min < 1"),
    ({"nu_min": -0.5}, "nu_min", "0 <= nu_min < 1"),
    ({"L": math.nan}, "L", "L > 0"),
    ({"k1": math.inf}, "k1", "0 < k1 <= 1"),
]


@pytest.mark.parametrize("values,name,rule", BAD)
def test_params_errors_name_the_parameter_and_rule(values, name, rule):
    with pytest.raises(ValueError) as e:
        kin.Params(**values)
    msg = str(e.value)
    assert msg.startswith(name + " = ") and f"(needs {rule})" in msg, msg


def test_params_errors_other():
    with pytest.raises(TypeError, match="unknown parameter 'length'"):
        kin.Params(length=1.0)
    with pytest.raises(TypeError, match="same parameter"):
        kin.Params(eta=0.5, eta_deg=30)
    # A set valid in double that the float build rejects (L beyond the float range).
    p = kin.Params(L=1e39)
    with pytest.raises(ValueError, match=r"^L = 1e\+39 is invalid in float precision \(needs L > 0\)"):
        kin.ik(np.zeros((1, 6)), params=p, precision="float")
    with pytest.raises(ValueError, match="precision"):
        kin.ik(np.zeros((1, 6)), precision="half")
    with pytest.raises(ValueError, match="poses"):
        kin.ik(np.zeros((3, 5)))


def test_params_file_errors(tmp_path):
    f = tmp_path / "bad.params"
    f.write_text("L = 1.5\nk1 = 1.5\n")
    with pytest.raises(ValueError, match=r"bad.params:2: k1 = 1.5 is invalid \(needs 0 < k1 <= 1\)"):
        kin.Params.from_file(f)
    f.write_text("L = 1.5\nlength = 2\n")
    with pytest.raises(ValueError, match=r"bad.params:2: unknown key 'length'"):
        kin.Params.from_file(f)
    with pytest.raises(OSError, match="cannot open"):
        kin.Params.from_file(tmp_path / "missing.params")


def test_batch_speed():
    """The issue's goal: ik on 1,000,000 poses in at most 1 s.  Printed, not asserted."""
    n = 1_000_000
    poses = random_poses(n, 2024)
    for precision in PRECISIONS:
        for warm in (False, True):
            t0 = time.perf_counter()
            r = kin.ik(poses, precision=precision, warm=warm)
            dt = time.perf_counter() - t0
            ok = int(np.sum(r.status == kin.Status.OK))
            print(f"\nik {precision} {'warm' if warm else 'cold'}: {n} poses in {dt:.3f} s "
                  f"({dt / n * 1e9:.0f} ns per pose, {ok} ok)")
