"""Where the suite finds tse-kin: $TSE_KIN_CLI (the ctest passes it), else the host build."""
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
