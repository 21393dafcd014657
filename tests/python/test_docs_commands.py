# Every command in README.md and docs/*.md runs as written, from a fresh clone after
# scripts/test: each page's fenced blocks run in order in one temporary folder that looks like the
# project's top folder (build/, assets/, examples/, tests/ linked; out/ and docs/img/ empty, so
# pictures the docs make land here, not over the committed ones).
#   ```sh      run with bash -eo pipefail; must exit 0. A block of only `cablelab gui` commands
#              opens the window: it must still be running, silent, after a few seconds (Xvfb).
#   ```python  run with Debian's python3 and the built module; must exit 0.
#   ```text    right after a sh or python block: each of its lines must be in that block's output.
#   ```json    a scene: it must load and run; one named like examples/scenes/NAME.json must be
#              that file.
import json
import os
import re
import signal
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ["CABLELAB_SOURCE_DIR"])
BUILD = Path(os.environ["CABLELAB_BUILD_DIR"])
PAGES = [SOURCE / "README.md"] + sorted((SOURCE / "docs").glob("*.md"))

# Commands the suite runs by other means: scripts/test is this suite; scripts/run installs and
# builds as scripts/test does, then opens the window; the pip install is tests/python/test_package.py.
NOT_RUN_HERE = (re.compile(r"^scripts/(run|test)\b"), re.compile(r"\bpip install\b"))

FENCE = re.compile(r"^```(\w*)\n(.*?)^```$", re.S | re.M)


def blocks(page):
    """(language, text, line number, follows) of every fenced block; follows: nothing but blank
    lines stand between it and the block before (a text block there is that block's output)."""
    found = []
    text = page.read_text()
    end = None
    for m in FENCE.finditer(text):
        follows = end is not None and text[end:m.start()].strip() == ""
        found.append((m.group(1), m.group(2), text.count("\n", 0, m.start()) + 1, follows))
        end = m.end()
    return found


def command_lines(script):
    joined = script.replace("\\\n", " ")
    return [line.strip() for line in joined.splitlines()
            if line.strip() and not line.strip().startswith("#")]


def is_window(script):
    lines = command_lines(script)
    return bool(lines) and all(
        re.match(r"build/bin/cablelab gui\b", line)
        and not re.search(r"--(frames|screenshot|script|test-input)\b", line) for line in lines)


def cases():
    for page in PAGES:
        found = blocks(page)
        for i, (lang, body, line, _) in enumerate(found):
            if lang not in ("sh", "python", "json"):
                continue
            expected = None
            if i + 1 < len(found) and found[i + 1][0] == "text" and found[i + 1][3] and lang != "json":
                expected = found[i + 1][1]
            yield pytest.param(page.name, lang, body, expected, id=f"{page.name}:{line}")


FOLDERS = {}


@pytest.fixture
def folders(tmp_path_factory):
    return FOLDERS, tmp_path_factory


def project_for(page_name, folders):
    cache, factory = folders
    if page_name not in cache:
        top = factory.mktemp(page_name.replace(".", "_"))
        for name in ("assets", "examples", "tests", "python"):
            (top / name).symlink_to(SOURCE / name)
        (top / "build").symlink_to(BUILD)
        (top / "out").mkdir()
        (top / "docs" / "img").mkdir(parents=True)
        cache[page_name] = top
    return cache[page_name]


def environment():
    env = dict(os.environ, PYTHONPATH="build/python", MPLBACKEND="Agg")
    return env


def run_window(script, cwd):
    """Starts the block under Xvfb; the window must stay open and quiet for 5 s."""
    process = subprocess.Popen(["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", "bash", "-c", script],
                               cwd=cwd, env=environment(), stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        out, err = process.communicate(timeout=5)
        pytest.fail(f"the window closed (exit {process.returncode}): {out}{err}")
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, err = process.communicate()
    assert err.strip() == "", err


@pytest.mark.parametrize("page,lang,body,expected", list(cases()))
def test_block_runs_as_written(page, lang, body, expected, folders):
    project = project_for(page, folders)
    if lang == "json":
        scene = json.loads(body)
        if "bodies" not in scene:
            return  # a fragment of a scene, shown for its fields
        named = SOURCE / "examples" / "scenes" / f"{scene.get('name', '')}.json"
        if named.exists():
            assert json.loads(named.read_text()) == scene, f"{named} differs from the page"
        path = project / "scene.json"
        path.write_text(body)
        run = subprocess.run([str(BUILD / "bin" / "cablelab"), "run", str(path), "--time", "0.2"],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        return
    if lang == "sh":
        lines = command_lines(body)
        if lines and all(any(p.search(line) for p in NOT_RUN_HERE) for line in lines):
            return
        assert not any(any(p.search(line) for p in NOT_RUN_HERE) for line in lines), \
            "put commands run elsewhere in a block of their own"
        if is_window(body):
            run_window(body, project)
            return
        command = ["bash", "-eo", "pipefail", "-c", body]
    else:
        command = ["/usr/bin/python3", "-c", body]
    run = subprocess.run(command, cwd=project, env=environment(), capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, f"exit {run.returncode}\n{run.stdout}\n{run.stderr}"
    if expected is not None:
        output = (run.stdout + run.stderr).splitlines()
        for line in expected.strip().splitlines():
            assert line.rstrip() in (o.rstrip() for o in output), \
                f"expected line {line!r} not in the output:\n{run.stdout}{run.stderr}"


def test_every_picture_in_the_docs_is_made_by_a_command_they_give():
    made = set()
    for page in PAGES:
        for lang, body, _, _ in blocks(page):
            if lang == "sh":
                made.update(re.findall(r"(docs/img/[\w.-]+\.png)", body))
    shown = set()
    for page in PAGES:
        for target in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", page.read_text()):
            path = (page.parent / target).resolve().relative_to(SOURCE.resolve())
            shown.add(str(path))
            assert (SOURCE / path).exists(), f"{page.name} shows {target}, which is not committed"
    assert shown <= made, f"pictures no command makes: {sorted(shown - made)}"


def test_docs_say_nothing_about_when_the_work_was_done():
    dated = re.compile(r"\b20\d\d-\d\d-\d\d\b|\b(this|last|next) session\b", re.I)
    for page in PAGES:
        hits = [line for line in page.read_text().splitlines() if dated.search(line)]
        assert not hits, f"{page.name}: {hits[:3]}"
