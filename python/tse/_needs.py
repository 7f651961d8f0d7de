"""A third-party module the package needs, or an ImportError that says which interpreter has it.

The project installs its Python dependencies as Debian packages (scripts/setup.sh: python3-numpy,
python3-can), which only Debian's interpreter, /usr/bin/python3, sees; a python3 found first on
PATH (pyenv, a virtual environment, a conda build) does not, and would only say "No module named
'numpy'"."""
import importlib
import sys

DEBIAN_PYTHON = "/usr/bin/python3"


def need(module, debian_package, for_what):
    try:
        return importlib.import_module(module)
    except ImportError as e:
        here = f"{sys.executable} (Python {sys.version.split()[0]})"
        raise ImportError(
            f"{for_what} needs the module '{module}', which this interpreter, {here}, cannot import ({e}). "
            f"The project installs it as Debian's {debian_package} (scripts/setup.sh) for {DEBIAN_PYTHON}: "
            f"run {DEBIAN_PYTHON} instead, or install '{module}' into this interpreter.") from e
