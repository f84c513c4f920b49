"""What the Python module's tests share (tests/python_*_test.py): the
quiver program and the scenes they compare with, from the environment ctest
gives them (tests/CMakeLists.txt), and the program's outputs read back."""
import json
import os
import shutil
import subprocess

import pytest

CLI = os.environ.get("QUIVER_CLI", "")
DATA = os.environ.get("QUIVER_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "data"))
SHARED = os.environ.get("QUIVER_SHARED_DIR", "")
TINY = os.path.join(DATA, "scenes", "tiny.nff")


def cli():
    """The quiver program, or a skip saying why not."""
    if not CLI or not os.access(CLI, os.X_OK):
        pytest.skip("QUIVER_CLI does not name the quiver program (ctest sets it)")
    return CLI


def shared_file(*parts):
    """A file of the shared folder (QUIVER_SHARED_DIR), or a skip saying why not."""
    path = os.path.join(SHARED, *parts)
    if not SHARED or not os.path.isfile(path):
        pytest.skip("%s is absent (set QUIVER_SHARED_DIR to the folder holding %s)" % (path, os.path.join(*parts)))
    return path


def run_cli(*args):
    """(exit code, stdout, stderr) of the quiver program."""
    done = subprocess.run([cli()] + [str(a) for a in args], capture_output=True, text=True, timeout=600)
    return done.returncode, done.stdout, done.stderr


def trace_json(*args):
    """The JSON line of `quiver trace ARGS`."""
    code, out, err = run_cli("trace", *args)
    assert code == 0, err
    return json.loads(out)


def cli_error(*args):
    """The message of a failing quiver command, without its "quiver: " prefix."""
    code, _, err = run_cli(*args)
    assert code != 0
    line = err.strip().splitlines()[0]
    assert line.startswith("quiver: "), err
    return line[len("quiver: "):]


def tool(name):
    """An OpenImageIO tool (openimageio-tools), or a skip saying why not."""
    path = shutil.which(name)
    if path is None:
        pytest.skip("%s is not installed (openimageio-tools)" % name)
    return path
