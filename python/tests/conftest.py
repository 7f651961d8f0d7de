"""Where the suite finds the host tools: $TSE_KIN_CLI, $TSE_SIM, $TSECTL (the ctest passes them),
else the host build."""
import os
from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def tse_kin_cli():
    env = os.environ.get("TSE_KIN_CLI")
    path = Path(env) if env else Path(__file__).resolve().parents[2] / "build" / "host" / "host_tools" / "tse-kin"
    if not path.exists():
        pytest.fail(f"tse-kin not found at {path}: build it, or set TSE_KIN_CLI")
    return str(path)


def _tool(env_name, *rel):
    env = os.environ.get(env_name)
    path = Path(env) if env else Path(__file__).resolve().parents[2].joinpath("build", "host", *rel)
    if not path.exists():
        pytest.fail(f"{rel[-1]} not found at {path}: build the host preset, or set {env_name}")
    return str(path)


@pytest.fixture(scope="session")
def tse_sim():
    return _tool("TSE_SIM", "host_tools", "tse-sim")


@pytest.fixture(scope="session")
def tsectl():
    return _tool("TSECTL", "host_tools", "tsectl", "tsectl")
