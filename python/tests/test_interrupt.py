"""Ctrl-C stops a sweep within a second (KeyboardInterrupt) and leaves nothing half-written; the GIL is released while
the core computes; a sweep draws a progress bar in a terminal and nothing in a script's log."""

import os
import pty
import select
import signal
import subprocess
import sys
import textwrap
import threading
import time
import _thread

import pytest

import impact

from conftest import MODELS

SLOW = MODELS / "chung-ooi-test4.toml"  # frictional: every row runs the slide path (about 25 µs a row here)
DEMO = MODELS / "demo.toml"


def test_ctrl_c_stops_a_sweep_within_a_second(python, tmp_path):
    script = textwrap.dedent(f"""
        import sys, time, impact
        print("ready", flush=True)
        start = time.monotonic()
        try:
            impact.sweep({str(SLOW)!r}, {{"bodies.0.incidence_deg": "5:85:400000"}}, progress=False)
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
    """)
    child = subprocess.Popen([python, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             cwd=tmp_path)
    assert child.stdout.readline().strip() == "ready"
    time.sleep(1.5)  # the sweep is well under way (400,000 frictional rows take about ten seconds)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    try:
        out, err = child.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        child.kill()
        pytest.fail("the sweep did not stop within 10 s of Ctrl-C")
    words = out.split()
    assert words[0] == "interrupted", out + err
    assert float(words[1]) - sent < 1.0, f"stopped {float(words[1]) - sent:.2f} s after Ctrl-C"
    assert child.returncode == 0
    assert list(tmp_path.iterdir()) == []


def test_interrupting_to_csv_leaves_no_file(tmp_path):
    # (A million rows of e alone: about a second to compute, a quarter of one to write.)
    sweep = impact.sweep(DEMO, {"contact.damping": "0.01:100:1000000:log"},
                         columns=["restitution_velocity_ratio", "approach_speed", "stiffness"], progress=False)
    target = tmp_path / "sweep.csv"
    timer = threading.Timer(0.02, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sweep.to_csv(target)
        time.sleep(5)  # (only if to_csv finished first: then the interrupt lands here, and the check below fails)
    timer.join()
    assert list(tmp_path.iterdir()) == [], "no file and no temporary file"


def test_interrupt_main_stops_a_sweep_in_process():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        impact.sweep(SLOW, {"bodies.0.incidence_deg": "5:85:400000"}, progress=False)
    assert time.monotonic() - start < 1.5
    timer.join()


def _python_work_during(call):
    """How many iterations a Python loop in this thread makes while `call` runs in another thread."""
    worker = threading.Thread(target=call)
    count = 0
    worker.start()
    while worker.is_alive():
        count += 1
    worker.join()
    return count


def test_the_gil_is_released_while_a_sweep_computes():
    start = time.monotonic()
    # (Long enough to measure: 8000 rows took 0.19 s once the frictional rows got faster, and failed the bound.)
    count = _python_work_during(
        lambda: impact.sweep(SLOW, {"bodies.0.incidence_deg": "5:85:40000"}, progress=False, threads=1))
    elapsed = time.monotonic() - start
    assert elapsed > 0.2
    # A loop that held no GIL would reach millions a second; a GIL held by the sweep would leave it a few switches.
    assert count / elapsed > 100_000, f"{count} iterations in {elapsed:.2f} s"


def test_the_gil_is_released_while_a_world_runs():
    start = time.monotonic()
    count = _python_work_during(lambda: impact.run(MODELS / "bouncing-ball.toml"))
    elapsed = time.monotonic() - start
    assert count / elapsed > 100_000, f"{count} iterations in {elapsed:.2f} s"


PROGRESS = textwrap.dedent(f"""
    import sys, impact
    progress = {{"none": None, "true": True, "false": False}}[sys.argv[1]]
    impact.sweep({str(SLOW)!r}, {{"bodies.0.incidence_deg": "5:85:1500"}}, progress=progress, threads=1)
    print("done", flush=True)
""")


def test_no_progress_bar_in_a_scripts_log(python):
    done = subprocess.run([python, "-c", PROGRESS, "none"], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "done"
    assert done.stderr == ""


def test_progress_true_draws_even_into_a_log(python):
    done = subprocess.run([python, "-c", PROGRESS, "true"], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "done"
    assert "1500" in done.stderr


def test_a_bar_in_a_terminal(python):
    primary, secondary = pty.openpty()
    child = subprocess.Popen([python, "-c", PROGRESS, "none"], stdout=subprocess.PIPE, stderr=secondary,
                             text=True)
    os.close(secondary)
    seen = b""
    while True:
        ready, _, _ = select.select([primary], [], [], 60)
        if not ready:
            break
        try:
            chunk = os.read(primary, 4096)
        except OSError:
            break
        if not chunk:
            break
        seen += chunk
    child.wait(timeout=60)
    os.close(primary)
    assert child.stdout.read().strip() == "done"
    assert b"1500" in seen, seen[-300:]
