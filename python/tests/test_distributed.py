"""Distributed renders on Ray (`steradian.distributed`), on a local Ray of 2 CPUs: the image
is `Scene.render`'s bit for bit for any task count, after a worker is killed mid-task, and
after a driver stopped part-way resumes from its checkpoint; bad input gives clear errors."""

import os
import signal
import threading
import time

import numpy as np
import pytest
import ray

import steradian
from conftest import CORNELL
from steradian import distributed


@pytest.fixture(scope="module", autouse=True)
def local_ray():
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False, configure_logging=False)
    yield
    ray.shutdown()


def bits(a):
    return np.ascontiguousarray(a).view(np.uint32)


@pytest.mark.parametrize("tasks", [1, 2, 7])
def test_the_image_is_the_single_process_image(tasks):
    want = steradian.load_file(CORNELL, res=24).render(64, 3)
    sums, _, report = distributed.render_sums(CORNELL, 64, 3, tasks=tasks, progress=False, defaults={"res": 24})
    assert report.tasks == tasks and not report.retried
    got = distributed.render(CORNELL, 64, 3, tasks=tasks, progress=False, defaults={"res": 24})
    assert got.shape == want.shape and got.dtype == np.float32
    np.testing.assert_array_equal(bits(got), bits(want))
    np.testing.assert_array_equal(bits(sums.image()), bits(want))


def _cpu_ticks(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime + stime


def _task_pids():
    """Processes rendering a task right now: titled `ray::_render_task` by Ray (a worker that
    ran one before may keep the title while idle) and busy on the CPU."""
    titled = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    if f.read().startswith(b"ray::_render_task"):
                        titled.append((int(pid), _cpu_ticks(pid)))
            except OSError:
                pass
    time.sleep(0.2)
    busy = []
    for pid, ticks in titled:
        try:
            if _cpu_ticks(pid) - ticks >= 10:  # at least half a core over 0.2 s
                busy.append(pid)
        except OSError:
            pass
    return busy


def test_a_killed_worker_loses_no_sample():
    args = dict(tasks=4, progress=False, defaults={"res": 48})
    result = {}

    def run():
        try:
            result["out"] = distributed.render_sums(CORNELL, 768, 1, **args)
        except BaseException as e:  # reported by the main thread
            result["error"] = e

    t = threading.Thread(target=run)
    t.start()
    killed = None
    deadline = time.time() + 120
    while killed is None and t.is_alive() and time.time() < deadline:
        pids = _task_pids()
        if pids:
            os.kill(pids[0], signal.SIGKILL)  # mid-task
            killed = pids[0]
        time.sleep(0.05)
    t.join(300)
    assert "error" not in result, result.get("error")
    assert killed is not None, "no task was seen running"
    sums, scene, report = result["out"]
    assert report.retried, f"the killed task was not run again ({killed}: {report})"
    want = steradian.load_file(CORNELL, res=48).render(768, 1)
    np.testing.assert_array_equal(bits(scene.develop(sums)), bits(want))


def test_a_stopped_driver_resumes_from_its_checkpoint(tmp_path):
    ck = tmp_path / "render.ck"
    args = dict(defaults={"res": 32}, tasks=6)

    def stop_after_first(done, total):
        if done > 0:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        distributed.render_sums(CORNELL, 384, 2, checkpoint=ck, progress=stop_after_first, **args)
    kept = [p for p in os.listdir(tmp_path) if p.startswith("render.ck")]
    assert kept, "nothing was kept"
    sums, scene, report = distributed.render_sums(CORNELL, 384, 2, checkpoint=ck, progress=False, **args)
    assert report.samples < 32 * 32 * 384, report  # the kept work is not rendered again
    want = steradian.load_file(CORNELL, res=32).render(384, 2)
    np.testing.assert_array_equal(bits(scene.develop(sums)), bits(want))
    assert not [p for p in os.listdir(tmp_path) if p.startswith("render.ck")], "checkpoint left behind"


def test_a_checkpoint_of_another_render_is_refused(tmp_path):
    scene = steradian.load_file(CORNELL, res=24)
    b = scene.plan(64, 3)["pass_bounds"]
    scene.render_range(0, b[4], 64, 3).save(tmp_path / "ck")
    with pytest.raises(distributed.DistributedError, match="belongs to another render: scene"):
        distributed.render(CORNELL, 64, 3, checkpoint=tmp_path / "ck", progress=False, defaults={"res": 24})
    with pytest.raises(distributed.DistributedError, match="belongs to another render: spp 64, expected 32"):
        distributed.render(CORNELL, 32, 3, checkpoint=tmp_path / "ck", progress=False, defaults={"res": 24})


def test_a_scene_that_fails_on_a_worker_names_file_line_and_column(tmp_path, monkeypatch):
    (tmp_path / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (tmp_path / "scene.xml").write_text(
        '<scene version="3.0.0">\n'
        '  <integrator type="path"/><emitter type="constant"/>\n'
        '  <shape type="obj"><string name="filename" value="tri.obj"/></shape>\n'
        '  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>'
        '<integer name="height" value="8"/></film></sensor>\n'
        "</scene>\n"
    )
    collect = distributed._collect_bundle

    def without_the_mesh(*args):
        bundle = collect(*args)
        del bundle.files["tri.obj"]
        return bundle

    monkeypatch.setattr(distributed, "_collect_bundle", without_the_mesh)
    with pytest.raises(steradian.SceneError, match=r"failed to load on a Ray worker: .*scene\.xml:3:\d+: .*tri\.obj"):
        distributed.render(tmp_path / "scene.xml", 4, progress=False)


def test_bad_input_is_a_clear_error_not_a_hang(tmp_path):
    start = time.time()
    with pytest.raises(distributed.DistributedError, match="cannot reach a Ray cluster at 127.0.0.1:1"):
        distributed.render(CORNELL, 4, address="127.0.0.1:1", progress=False)
    assert time.time() - start < 30
    (tmp_path / "bad.xml").write_text('<scene version="3.0.0"><shape type="nope"/></scene>')
    with pytest.raises(steradian.SceneError, match=r"bad\.xml:1:\d+"):
        distributed.render(tmp_path / "bad.xml", 4, progress=False)


def test_the_command_line_writes_exr_and_png(tmp_path, capsys):
    out = tmp_path / "cornell.exr"
    code = distributed.main([str(CORNELL), "--spp", "16", "--seed", "4", "-D", "res=16", "-o", str(out), "--tasks", "3"])
    assert code == 0
    assert out.is_file() and out.with_suffix(".png").is_file()
    want = steradian.load_file(CORNELL, res=16).render(16, 4)
    np.testing.assert_array_equal(bits(steradian.read_exr(out)), bits(want))
    err = capsys.readouterr().err
    assert "3 tasks" in err and "Msamples/s" in err and "node " in err
