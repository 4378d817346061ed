"""Ctrl-C during a render: KeyboardInterrupt in Python, promptly, no crash."""

import signal
import subprocess
import sys
import textwrap
import time

from conftest import CORNELL

# A render that would take hours; it announces itself on the first progress report.
CHILD = textwrap.dedent(
    """
    import sys, time
    import steradian
    scene = steradian.load_file(sys.argv[1], res=128)
    started = False
    def progress(done, total):
        global started
        if not started:
            started = True
            print("started", done, total, flush=True)
    t = time.perf_counter()
    try:
        scene.render(spp=1_000_000, progress=progress)
    except KeyboardInterrupt:
        print(f"interrupted after {time.perf_counter() - t:.2f} s", flush=True)
        # the interpreter is intact: it can render again
        print("again", scene.render(spp=1, progress=None).shape, flush=True)
        sys.exit(7)
    print("finished", flush=True)
    """
)


def test_sigint_raises_keyboard_interrupt_and_python_goes_on():
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, str(CORNELL)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        first = child.stdout.readline()
        assert first.startswith("started"), first + child.stderr.read()
        time.sleep(0.2)
        sent = time.perf_counter()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60)
        waited = time.perf_counter() - sent
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert child.returncode == 7, (child.returncode, out, err)
    assert "interrupted after" in out and "again (128, 128, 3)" in out, out
    assert "panicked" not in err and "Traceback" not in err, err
    # the driver checks the cancel flag every pixel row; allow a loaded machine its time
    assert waited < 10, waited
