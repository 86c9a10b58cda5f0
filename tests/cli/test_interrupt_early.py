"""Ctrl-C at any moment of a command's start, the first 50 ms included (issue 27.7): "interrupted" and
exit 130, or the command's own result; never a KeyboardInterrupt traceback.

The delays count from the moment CPython has started (measured: ``python -c pass``): a Ctrl-C while
CPython itself initialises and imports ``site`` (an editable install's ``.pth`` finder runs there) is
CPython's "Fatal Python error: init_import_site", before any line of l2p-bullet runs, which no package
can catch; so is one while the console script looks the package up (importlib's and the editable install's
finders: a traceback none of whose frames is in the package). From the package's first line on, the window
is ours: the entry point's first statements install the handler (``l2p_bullet/launch.py``).

The program is run as pip's console script runs it, from the entry point ``pyproject.toml`` declares (a
console script installed before that entry point changed would test the old one). Importing the package,
or its command line module, installs nothing: only the program does.
"""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import textwrap
import time
import tomllib
from pathlib import Path

import pytest
from interrupt import ctrl_c_as_at_a_terminal

import l2p_bullet

PACKAGE = str(Path(l2p_bullet.__file__).resolve().parent)
PYPROJECT = Path(PACKAGE).parent / "pyproject.toml"


@pytest.fixture(scope="module")
def program(tmp_path_factory) -> Path:
    """``l2p-bullet`` as pip writes it (its console-script template) from the declared entry point."""
    if not PYPROJECT.is_file():
        pytest.skip("no pyproject.toml next to the package (an installed copy)")
    module, func = tomllib.loads(PYPROJECT.read_text())["project"]["scripts"]["l2p-bullet"].split(":")
    path = tmp_path_factory.mktemp("bin") / "l2p-bullet"
    path.write_text(textwrap.dedent(f"""\
        import re
        import sys
        from {module} import {func}
        if __name__ == "__main__":
            sys.argv[0] = re.sub(r"(-script\\.pyw|\\.exe)?$", "", sys.argv[0])
            sys.exit({func}())
        """))
    return path


@pytest.mark.parametrize("module", ["l2p_bullet", "l2p_bullet.cli"])
def test_importing_the_package_installs_no_signal_handler(module):
    """Even in a process named like the program: only running the entry point sets Ctrl-C's handler."""
    code = (f"import sys; sys.argv[0] = '/usr/bin/l2p-bullet'; import signal, {module}; "
            "print(signal.getsignal(signal.SIGINT) is signal.default_int_handler, "
            "signal.getsignal(signal.SIGTERM) is signal.SIG_DFL)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                       preexec_fn=ctrl_c_as_at_a_terminal)  # as at a terminal, also when the suite runs behind "&"
    assert r.returncode == 0 and r.stdout.split() == ["True", "True"], (r.stdout, r.stderr)


def landed_before_the_package(err: str) -> bool:
    """True when the Ctrl-C landed before any line of l2p-bullet ran: CPython's own start-up, or a
    KeyboardInterrupt none of whose traceback's frames is in the package (the console script's lookup)."""
    if "init_import_site" in err:
        return True
    frames = re.findall(r'File "([^"]+)"', err)
    # no frame at all: a bare "KeyboardInterrupt" (exit 1), raised while CPython read the console script
    return "KeyboardInterrupt" in err and not any(
        str(Path(f).resolve()).startswith(PACKAGE) for f in frames if not f.startswith("<"))


def _python_start_s() -> float:
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "pass"], check=True)
        best = min(best, time.perf_counter() - t0)
    return best


@pytest.fixture(scope="module")
def python_start_s() -> float:
    return _python_start_s()


@pytest.mark.slow
@pytest.mark.parametrize("delay_ms", [0, 5, 15, 30, 50, 80, 150, 300])
def test_ctrl_c_while_the_command_starts_prints_no_traceback(tmp_path, program, python_start_s, delay_ms):
    late = 0.0
    for attempt in range(6):
        p = subprocess.Popen(
            [sys.executable, str(program), "plan", "move A past B", "--out", str(tmp_path / f"p{attempt}")],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=ctrl_c_as_at_a_terminal,
        )
        time.sleep(python_start_s + late + delay_ms / 1000)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60)
        if not landed_before_the_package(err):
            break
        # on a loaded machine CPython's own start took longer than measured: the Ctrl-C landed before any
        # line of l2p-bullet ran (see the module docstring). Send it a little later, the window is the same.
        late += 0.02
    assert not landed_before_the_package(err), f"CPython never got past its start-up in time: {err[-500:]}"
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    # 130: interrupted; 0: it finished first; -SIGINT: the signal landed while the interpreter was shutting
    # down after the command (CPython restores the default disposition then), which prints nothing
    assert p.returncode in (130, 0, -signal.SIGINT), (p.returncode, err)
    assert p.returncode != -signal.SIGINT or not err.strip(), err
