"""Renders as sums (`Scene.plan`, `Scene.render_range`, `Sums`): ranges joined in order are
the render bit for bit, in any process; sums travel as bytes and pickles; foreign sums are
refused."""

import pickle

import numpy as np
import pytest

import steradian
from conftest import CORNELL

SPP, SEED = 48, 5


@pytest.fixture(scope="module")
def cornell():
    return steradian.load_file(CORNELL, res=24)


@pytest.fixture(scope="module")
def plan(cornell):
    return cornell.plan(SPP, SEED)


def bits(a):
    return np.ascontiguousarray(a).view(np.uint32)


def test_plan_names_passes_and_branches(cornell, plan):
    assert plan["spp"] == SPP and plan["seed"] == SEED
    assert (plan["width"], plan["height"]) == (24, 24)
    b = plan["pass_bounds"]
    assert b[0] == 0 and b[-1] == SPP and all(x < y for x, y in zip(b, b[1:]))
    assert plan["branches"] >= 1  # the pilot's choice for `path`


def test_ranges_joined_in_order_are_the_render(cornell, plan):
    whole = cornell.render(SPP, SEED)
    b = plan["pass_bounds"]
    cuts = [0, b[3], b[len(b) // 2], SPP]
    total = None
    for k, (first, end) in enumerate(zip(cuts, cuts[1:])):
        part = cornell.render_range(first, end - first, SPP, SEED, branches=plan["branches"], threads=1 + k % 2)
        assert (part.first, part.end, part.is_prefix) == (first, end, first == 0)
        part = pickle.loads(pickle.dumps(part))  # as it travels between processes
        if total is None:
            total = part
        else:
            total.append(part)
    assert total.is_complete
    np.testing.assert_array_equal(bits(total.image()), bits(whole))
    np.testing.assert_array_equal(bits(cornell.develop(total)), bits(whole))
    # the raw sums are what the image is made of
    a = total.arrays()
    assert a["wl"].shape == (24, 24, 3) and a["w"].shape == (24, 24) and a["wl"].dtype == np.float64
    np.testing.assert_allclose(a["wl"] / a["w"][..., None], whole, rtol=1e-6)
    assert (a["wl2"] * a["w"][..., None] >= a["wl"] ** 2 * (1 - 1e-9)).all()  # Cauchy-Schwarz


def test_resume_and_save_load(cornell, plan, tmp_path):
    whole = cornell.render(SPP, SEED)
    b = plan["pass_bounds"]
    head = cornell.render_range(0, b[5], SPP, SEED)
    head.save(tmp_path / "ck")
    head = steradian.Sums.load(tmp_path / "ck")
    rest = cornell.render_range(b[5], SPP - b[5], SPP, SEED, resume=head)
    assert rest.is_complete
    np.testing.assert_array_equal(bits(rest.image()), bits(whole))
    assert rest.stderr().shape == (24, 24, 3) and (rest.stderr() >= 0).all()


def test_foreign_or_misplaced_sums_are_refused(cornell, plan):
    b = plan["pass_bounds"]
    head = cornell.render_range(0, b[2], SPP, SEED)
    other_seed = cornell.render_range(b[2], b[3] - b[2], SPP, SEED + 1)
    with pytest.raises(ValueError, match="seed"):
        head.append(other_seed)
    later = cornell.render_range(b[3], b[4] - b[3], SPP, SEED)
    with pytest.raises(ValueError, match=f"start at sample {b[2]}"):
        head.append(later)
    with pytest.raises(ValueError, match="pass boundaries"):
        cornell.render_range(0, b[2] + 1 if b[2] + 1 not in b else b[3] + 1, SPP, SEED)
    with pytest.raises(ValueError, match="not a steradian sums record"):
        steradian.Sums.from_bytes(b"junk")
    data = head.to_bytes()
    with pytest.raises(ValueError, match="truncated"):
        steradian.Sums.from_bytes(data[:-8])


def test_files_lists_what_the_loader_read(cornell, tmp_path):
    assert [str(CORNELL)] == cornell.files
    (tmp_path / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (tmp_path / "part.xml").write_text(
        '<scene version="3.0.0"><shape type="obj"><string name="filename" value="tri.obj"/></shape></scene>'
    )
    (tmp_path / "main.xml").write_text(
        '<scene version="3.0.0"><integrator type="path"/><include filename="part.xml"/><sensor type="perspective"/></scene>'
    )
    scene = steradian.load_file(tmp_path / "main.xml")
    assert [p.rsplit("/", 1)[-1] for p in scene.files] == ["main.xml", "part.xml", "tri.obj"]


class Stop(Exception):
    pass


def test_a_stopped_render_resumes_from_its_checkpoint(cornell, tmp_path):
    ck = tmp_path / "render.ck"
    whole = cornell.render(SPP, SEED)
    calls = []

    def stop_early(done, total):
        calls.append(done)
        if done > 0:
            raise Stop

    with pytest.raises(Stop):
        cornell.render(SPP * 8, SEED, progress=stop_early, checkpoint=ck, checkpoint_interval=0)
    assert ck.is_file(), "the stopped render kept nothing"
    kept = steradian.Sums.load(ck)
    assert kept.is_prefix and 0 < kept.end < SPP * 8
    with pytest.raises(ValueError, match="cannot resume from .*seed"):
        cornell.render(SPP * 8, SEED + 1, checkpoint=ck)
    again = cornell.render(SPP * 8, SEED, checkpoint=ck)
    assert not ck.exists(), "a completed render deletes its checkpoint"
    np.testing.assert_array_equal(bits(again), bits(cornell.render(SPP * 8, SEED)))
    assert whole.shape == again.shape


def test_a_time_limit_ends_render_and_measure_early(cornell):
    import time

    t = time.perf_counter()
    image = cornell.render(1 << 20, SEED, time_limit=0.5)
    assert time.perf_counter() - t < 30
    assert image.shape == (24, 24, 3) and np.isfinite(image).all() and image.max() > 0
    meter = steradian.load_file(CORNELL.parent / "validation" / "disk_on_axis_irradiance.xml")
    m = meter.measure(10**9, time_limit=0.5)
    assert 0 < m.spp < 10**9 and (m.stderr > 0).all()
    with pytest.raises(ValueError, match="time_limit must be a positive number"):
        cornell.render(4, time_limit=0)
