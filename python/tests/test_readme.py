"""README.md's Python code blocks run as printed.  The session that drives a controller
(`Controller(`) needs a bus: tests/vcan/python_can_test.sh runs it against tse-sim in the VM (it
must be the first block of "## Python", the one that script takes); every other block runs here,
each in a fresh namespace, with the host build's library."""
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"


def python_blocks():
    text = README.read_text()
    blocks = []
    for m in re.finditer(r"^```python\n(.*?)^```", text, re.S | re.M):
        line = text.count("\n", 0, m.start()) + 2  # the block's first line of code
        blocks.append((line, m.group(1)))
    return text, blocks


def test_readme_has_python_blocks_and_the_session_is_the_one_the_vm_runs():
    text, blocks = python_blocks()
    assert blocks, "README.md has no python block"
    on_bus = [(line, code) for line, code in blocks if "Controller(" in code]
    section = text.index("## Python")
    first = min((line, code) for line, code in blocks if text.count("\n", 0, section) + 1 < line)
    assert on_bus == [first], ("the only block that needs a bus must be the first of '## Python' "
                               "(tests/vcan/python_can_test.sh runs that one)")


@pytest.mark.parametrize("line,code", [b for b in python_blocks()[1] if "Controller(" not in b[1]],
                         ids=lambda v: f"README.md:{v}" if isinstance(v, int) else "")
def test_readme_block_runs(line, code):
    namespace = {"__name__": "__readme__"}
    try:
        exec(compile(code, f"README.md:{line}", "exec"), namespace)
    except Exception as e:  # name the block in the failure
        pytest.fail(f"README.md's python block at line {line} fails: {type(e).__name__}: {e}")
