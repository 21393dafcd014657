# The CLI's progress bar (app/progress.h): drawn on stderr when stderr is a terminal (here a
# pseudo-terminal), rising to 100% and ending its line; nothing at all on stderr when it is a
# pipe; stdout the same either way.
import json
import os
import pty
import re
import subprocess

import pytest

from conftest import CLI, run_cli

BAR = re.compile(r"\r([\w ]+) \[([#-]{30})\] +(\d+)%  (\d+)/(\d+)")


def run_in_terminal(*args):
    """The CLI with stderr on a pseudo-terminal and stdout a pipe: (exit code, stdout, what the
    terminal received)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([CLI, *map(str, args)], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                         stderr=slave)
    os.close(slave)
    received = b""
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        received += data
    os.close(master)
    out = p.stdout.read().decode()
    p.stdout.close()
    return p.wait(timeout=600), out, received.decode()


def bars(terminal):
    """(label, percent, done, total) of every bar drawn, in order."""
    return [(m[1], int(m[3]), int(m[4]), int(m[5])) for m in BAR.finditer(terminal)]


def without_timing(result):
    return {k: v for k, v in result.items()
            if k not in ("seconds", "step_us_median", "controller_solve_us", "controller_solve_max_us")}


# Each runs for several times the half second before the first bar (about 2 s of CPU here).
LONG_COMMANDS = {
    "run": (["run", "hexagon", "--time", "4000"], "run hexagon", 240000),
    "track": (["track", "--target", "0.1,0.2", "--time", "1200", "--pid"], "track", 72000),
    "reach": (["reach", "--grid", "7"], "reach", 49),
}


@pytest.mark.parametrize("command", sorted(LONG_COMMANDS))
def test_a_terminal_sees_a_bar_that_ends_at_100_percent(command):
    args, label, total = LONG_COMMANDS[command]
    code, out, terminal = run_in_terminal(*args)
    assert code == 0, terminal
    drawn = bars(terminal)
    assert len(drawn) >= 2, terminal  # at least one bar under way and the final one
    assert terminal.startswith("\r" + label + " [")
    percents = [p for _, p, _, _ in drawn]
    assert percents == sorted(percents) and percents[-1] == 100 and percents[0] < 100
    _, _, done, last_total = drawn[-1]
    assert done == last_total
    if total is not None:
        assert last_total == total
    assert terminal.endswith("s\x1b[K\r\n")  # "... 100%  N/N  2.3 s", then the line ends
    assert terminal.count("\n") == 1
    # The same answer on stdout as without a terminal, and a pipe gets no bar at all.
    piped = run_cli(*args)
    assert piped.returncode == 0 and piped.stderr == ""
    assert without_timing(json.loads(out)) == without_timing(json.loads(piped.stdout))


def test_a_quick_command_draws_nothing_even_on_a_terminal():
    code, out, terminal = run_in_terminal("run", "pulley", "--time", "1")
    assert code == 0 and json.loads(out)["steps"] == 60
    assert terminal == ""


def test_bad_input_on_a_terminal_shows_only_the_error_line(tmp_path):
    # An unwritable --csv path fails before the run: no bar, the one error line.
    code, _, terminal = run_in_terminal("run", "hexagon", "--time", "2000", "--csv",
                                        tmp_path / "no" / "such" / "dir.csv")
    assert code == 2
    assert terminal.count("\n") == 1 and terminal.startswith("command line: --csv: ")
