"""Type stubs: the checked-in ellipsect/_ellipsect.pyi is what stubgen makes of the built module
(docs/python.md says how to regenerate it), and python/examples/typed_usage.py passes
`mypy --strict` against the installed package."""

import subprocess
import sys
from pathlib import Path

PYTHON = Path(__file__).resolve().parent.parent


def test_stub_equals_stubgen_of_the_module(tmp_path):
    # Debian's mypy is compiled: stubgen runs through its main(), not `python -m mypy.stubgen`.
    stubgen = "from mypy.stubgen import main; main()"
    subprocess.run([sys.executable, "-c", stubgen, "-q", "-m", "ellipsect._ellipsect", "-o", str(tmp_path)],
                   check=True, cwd=tmp_path)
    made = (tmp_path / "ellipsect" / "_ellipsect.pyi").read_text()
    assert made == (PYTHON / "ellipsect" / "_ellipsect.pyi").read_text(), (
        "python/ellipsect/_ellipsect.pyi differs from the module: regenerate it (docs/python.md, Types)")


def test_example_passes_mypy_strict(tmp_path):
    run = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--cache-dir", str(tmp_path / "cache"),
                          str(PYTHON / "examples" / "typed_usage.py")], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
