"""Without numpy or python-can (an interpreter other than Debian's, which setup.sh installs them
for), importing tse.kin or tse.can says which interpreter to use, not just 'No module named'."""
import subprocess
import sys
from pathlib import Path

import pytest

PKG = str(Path(__file__).resolve().parents[1])


@pytest.mark.parametrize("module,missing,package", [("tse.kin", "numpy", "python3-numpy"),
                                                     ("tse.can", "can", "python3-can")])
def test_missing_module_names_the_interpreter_to_use(module, missing, package):
    # sys.modules[name] = None makes 'import name' fail as an absent module does.
    code = f"import sys; sys.modules[{missing!r}] = None; sys.path.insert(0, {PKG!r}); import {module}"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: ") and f"{module} needs the module '{missing}'" in last, last
    assert sys.executable in last and "/usr/bin/python3" in last and package in last, last
