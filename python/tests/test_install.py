"""The package installs as README says: the shared library copied next to kin.py, then
`pip install --no-build-isolation ./python` with Debian's pip and setuptools, nothing downloaded
(here into a target directory, so the machine's Python is left as it was).  The installed tse.kin
answers as the tree's does, and tse.can imports."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tse import kin

PYDIR = Path(__file__).resolve().parents[1]


def test_pip_install_no_build_isolation(tmp_path):
    tree = tmp_path / "python"
    shutil.copytree(PYDIR, tree, ignore=shutil.ignore_patterns("tests*", "examples", "build", "*.egg-info",
                                                               "__pycache__", "libtse_kin.so"))
    shutil.copy(kin.library_path, tree / "tse")
    site = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-build-isolation", "--no-deps", "--no-index",
                        "--target", str(site), str(tree)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    pose = [0.1, -0.05, 1.1, 0.1, -0.05, 0.2]
    code = ("import sys; from tse import kin, can; import numpy as np; "
            f"r = kin.ik(np.array([{pose}])); print(kin.__file__); print(repr(r.q[0].tolist()))")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TSE_KIN_LIB")}
    env["PYTHONPATH"] = str(site)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    where, q = r.stdout.splitlines()
    assert Path(where).is_relative_to(site)
    assert eval(q) == kin.ik(np.array([pose])).q[0].tolist()


def test_the_package_version_is_the_projects():
    """pyproject.toml's version is the project's (CMakeLists.txt's project(... VERSION), which the
    firmware reports in INFO): CMake gives it to this suite as TSE_PROJECT_VERSION."""
    want = os.environ.get("TSE_PROJECT_VERSION")
    if not want:
        pytest.skip("TSE_PROJECT_VERSION not set (run by ctest)")
    text = (PYDIR / "pyproject.toml").read_text()
    got = next(line.split('"')[1] for line in text.splitlines() if line.startswith("version = "))
    assert got == want
