"""Distributed renders on a Ray cluster, bit for bit the image of one process.

>>> from steradian import distributed
>>> image = distributed.render("scene.xml", spp=4096)                  # a local Ray
>>> image = distributed.render("scene.xml", spp=4096, address="auto")  # the running cluster

**How.** A render is a sequence of passes (``Scene.plan()["pass_bounds"]``); each task renders a
contiguous range of them with ``Scene.render_range`` and returns the range's raw sums. The
driver joins the sums in range order (``Sums.append``), which gives exactly the sums of one
process rendering every pass: the image equals ``Scene.render`` with the same scene, spp and
seed, bit for bit, whatever the number of tasks, workers or machines, and whichever tasks were
retried.

**The scene travels with its files.** The driver loads the scene once (so a bad scene fails
here, with its ``file:line:col``), collects every file the loader read (``Scene.files``: the
XML, its includes, meshes, images), puts them in Ray's object store as one bundle, and each
worker writes the bundle to a temporary folder and loads it once (kept per worker process). No
shared file system is needed; the cluster needs this package installed (``pip install .``).
Files the scene names by an absolute path are looked up at that path on the workers (the
bundle keeps them, but the XML still points elsewhere): give relative names, as Mitsuba's
exporters write them.

**Faults.** Tasks are deterministic, so a task whose worker dies is run again by Ray
(``max_retries``) with identical sums; the summary names the tasks that ran more than once.
With ``checkpoint=FILE`` the joined prefix is saved atomically to FILE and finished tasks that
arrive out of order to ``FILE.part-FIRST-END``: a driver killed at any moment resumes from
them with the same call.

**Sizing.** The passes are the unit of work: a render of N spp has about 32 + log2(N/32)
passes (one pass per sample for ``ptracer``), so a render is split into at most that many tasks;
``tasks`` (default: one per pass) groups the passes into that many ranges of about equal
samples. A task costs one scene load per worker (once), one film of float64 sums per pass it
holds on the way back (64 bytes a pixel), and a film-sized addition per pass at the driver.
``benches/ray_vs_local.py`` measures these; ``docs/design/2026-12-06-ray-scaling.md`` turns
them into a model of the speed-up on larger clusters.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import socket
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np

from . import _steradian

Sums = _steradian.Sums

__all__ = ["DistributedError", "Report", "render", "render_sums", "main"]


class DistributedError(RuntimeError):
    """A distributed render that cannot go on: no cluster, a task that failed for good, a
    checkpoint of another render."""


@dataclass
class Report:
    """What a distributed render did."""

    #: Tasks run (ranges of passes), not counting those a checkpoint already held.
    tasks: int = 0
    #: Samples per pixel resumed from the checkpoint.
    spp_resumed: int = 0
    #: Seconds each task's render took on its worker, by task index.
    task_seconds: Dict[int, float] = field(default_factory=dict)
    #: Per node id: tasks, samples rendered and seconds spent rendering.
    nodes: Dict[str, Dict[str, float]] = field(default_factory=dict)
    #: Tasks started more than once (their worker died), as (index, first, end).
    retried: List[Tuple[int, int, int]] = field(default_factory=list)
    #: Bytes of the scene bundle (the scene's files).
    bundle_bytes: int = 0
    #: Wall-clock seconds of the whole call (scene load and bundle included).
    seconds: float = 0.0
    #: Samples rendered by the tasks (pixels × spp of their ranges).
    samples: int = 0

    def summary(self) -> str:
        lines = [
            f"{self.tasks} tasks, {self.samples / max(self.seconds, 1e-9) / 1e6:.2f} Msamples/s "
            f"over {self.seconds:.2f} s, bundle {self.bundle_bytes / 1e6:.2f} MB"
            + (f", {self.spp_resumed} spp resumed" if self.spp_resumed else "")
        ]
        for node, n in sorted(self.nodes.items()):
            rate = n["samples"] / max(n["seconds"], 1e-9) / 1e6
            lines.append(
                f"  node {node[:12]}: {int(n['tasks'])} tasks, {n['seconds']:.2f} s rendering, "
                f"{rate:.2f} Msamples/s per task"
            )
        for i, first, end in self.retried:
            lines.append(f"  task {i} (samples {first}..{end}) was run again after its worker died")
        return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# the scene bundle


@dataclass
class _Bundle:
    """The scene's files, relative to their common folder, and what loads them."""

    scene: str
    files: Dict[str, bytes]
    defaults: Dict[str, Any]
    digest: int
    root: str

    @property
    def size(self) -> int:
        return sum(len(b) for b in self.files.values())


def _collect_bundle(scene: Any, scene_path: str, defaults: Dict[str, Any]) -> _Bundle:
    paths = [os.path.abspath(p) for p in scene.files] or [os.path.abspath(scene_path)]
    main_file = os.path.abspath(scene_path)
    if main_file not in paths:
        paths.insert(0, main_file)
    root = os.path.commonpath([os.path.dirname(p) for p in paths])
    files: Dict[str, bytes] = {}
    h = hashlib.sha256()
    for p in paths:
        rel = os.path.relpath(p, root)
        with open(p, "rb") as f:
            data = f.read()
        files[rel] = data
    for rel in sorted(files):
        h.update(rel.encode() + b"\0" + len(files[rel]).to_bytes(8, "little") + files[rel])
    for k in sorted(defaults):
        h.update(f"{k}={defaults[k]!r}\0".encode())
    digest = int.from_bytes(h.digest()[:8], "little")
    return _Bundle(os.path.relpath(main_file, root), files, dict(defaults), digest, root)


# Scenes loaded in this worker process, by bundle digest: each worker loads a scene once.
_WORKER_SCENES: Dict[int, Any] = {}


def _worker_scene(bundle: _Bundle) -> Any:
    scene = _WORKER_SCENES.get(bundle.digest)
    if scene is None:
        folder = tempfile.mkdtemp(prefix="steradian-bundle-")
        for rel, data in bundle.files.items():
            path = os.path.join(folder, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(data)
        try:
            scene = _steradian.load_file(os.path.join(folder, bundle.scene), **bundle.defaults)
        except _steradian.SceneError as e:
            # name the driver's files, not this worker's copies
            raise _steradian.SceneError(str(e).replace(folder, bundle.root)) from None
        _WORKER_SCENES[bundle.digest] = scene
    return scene


def _render_task(
    bundle: _Bundle, log: Any, index: int, job: Dict[str, Any], first: int, end: int
) -> Tuple[bytes, str, float]:
    """One task: the sums of samples first..end, as bytes, with the node id and seconds."""
    import ray

    node = ray.get_runtime_context().get_node_id()
    if log is not None:
        # waited for, so that a worker killed right after is still on record
        ray.get(log.started.remote(index, os.getpid(), node))
    scene = _worker_scene(bundle)
    t0 = time.perf_counter()
    sums = scene.render_range(
        first,
        end - first,
        job["spp"],
        job["seed"],
        job["sensor"],
        quantity=job["quantity"],
        branches=job["branches"],
        scene_digest=bundle.digest,
        threads=job["threads"],
    )
    return sums.to_bytes(), node, time.perf_counter() - t0


class _TaskLog:
    """Which worker started which task (a task started twice was retried)."""

    def __init__(self) -> None:
        self.starts: Dict[int, List[Tuple[int, str]]] = {}

    def started(self, index: int, pid: int, node: str) -> None:
        self.starts.setdefault(index, []).append((pid, node))

    def get(self) -> Dict[int, List[Tuple[int, str]]]:
        return self.starts


# ---------------------------------------------------------------------------------------------
# Ray


def _connect(address: Optional[str]) -> None:
    try:
        import ray
    except ImportError as e:  # pragma: no cover - depends on the installation
        raise DistributedError(
            "distributed renders need Ray: pip install 'ray>=2.9' (or steradian[ray])"
        ) from e
    if address not in (None, "auto", "local") and "://" not in address:
        host, _, port = address.rpartition(":")
        try:
            with socket.create_connection((host or "127.0.0.1", int(port)), timeout=5):
                pass
        except (OSError, ValueError) as e:
            raise DistributedError(
                f"cannot reach a Ray cluster at {address}: {e} (start one with `ray start "
                "--head`, or pass address=None for a local Ray)"
            ) from None
    if ray.is_initialized():
        return
    try:
        if address is None or address == "local":
            ray.init(include_dashboard=False, log_to_driver=False, configure_logging=False)
        else:
            ray.init(address=address, log_to_driver=False, configure_logging=False)
    except Exception as e:  # Ray raises ConnectionError, RuntimeError, ValueError...
        raise DistributedError(f"cannot connect to the Ray cluster at {address}: {e}") from None


def _groups(bounds: Sequence[int], count: int) -> List[Tuple[int, int]]:
    """`bounds` (pass boundaries) cut into at most `count` contiguous ranges of about equal
    samples, each holding at least one pass."""
    first, last = bounds[0], bounds[-1]
    count = max(1, min(count, len(bounds) - 1))
    cuts = [first]
    for k in range(1, count):
        target = first + (last - first) * k / count
        # the first boundary at or past the target that leaves room for the ranges after it
        i = next(j for j, b in enumerate(bounds) if b >= target)
        i = min(max(i, bounds.index(cuts[-1]) + 1), len(bounds) - 1 - (count - k))
        cuts.append(bounds[i])
    cuts.append(last)
    return [(a, b) for a, b in zip(cuts, cuts[1:]) if b > a]


# ---------------------------------------------------------------------------------------------
# checkpoints


def _part_path(checkpoint: str, first: int, end: int) -> str:
    return f"{checkpoint}.part-{first}-{end}"


def _check_sums(sums: Any, expect: Dict[str, Any], what: str) -> None:
    for key in ("spp", "seed", "size", "scene_digest", "sensor", "quantity", "branches"):
        got, want = getattr(sums, key), expect[key]
        if got != want:
            name = "scene (digest of its files and defaults)" if key == "scene_digest" else key
            raise DistributedError(f"{what} belongs to another render: {name} {got}, expected {want}")


def _load_checkpoint(checkpoint: str, expect: Dict[str, Any]) -> Tuple[Optional[Any], Dict[int, Any]]:
    prefix = None
    if os.path.exists(checkpoint):
        try:
            prefix = Sums.load(checkpoint)
        except ValueError as e:
            raise DistributedError(str(e)) from None
        if not prefix.is_prefix:
            raise DistributedError(f"checkpoint {checkpoint} does not start at sample 0")
        _check_sums(prefix, expect, f"checkpoint {checkpoint}")
    parts: Dict[int, Any] = {}
    folder = os.path.dirname(os.path.abspath(checkpoint))
    base = os.path.basename(checkpoint) + ".part-"
    for name in sorted(os.listdir(folder)):
        if name.startswith(base) and not name.endswith(".tmp"):
            try:
                part = Sums.load(os.path.join(folder, name))
            except ValueError:
                continue  # a damaged part is rendered again
            _check_sums(part, expect, f"checkpoint part {name}")
            parts[part.first] = part
    return prefix, parts


def _end(total: Optional[Any]) -> int:
    """Where the joined prefix ends (0 before the first range)."""
    return total.end if total is not None else 0


def _join(total: Optional[Any], waiting: Dict[int, Any], ck: Optional[str]) -> Optional[Any]:
    """Appends to `total` every waiting range that now follows it, in order; saves the new
    prefix to the checkpoint and deletes the parts it took in."""
    advanced = False
    while _end(total) in waiting:
        nxt = waiting.pop(_end(total))
        if total is None:
            total = nxt
        else:
            total.append(nxt)
        advanced = True
    if ck and advanced and total is not None:
        total.save(ck)
        folder = os.path.dirname(os.path.abspath(ck))
        base = os.path.basename(ck) + ".part-"
        for name in os.listdir(folder):
            if name.startswith(base) and not name.endswith(".tmp"):
                first = int(name[len(base):].split("-")[0])
                if first < total.end:
                    os.remove(os.path.join(folder, name))
    return total


# ---------------------------------------------------------------------------------------------
# the render


def render_sums(
    scene_path: Union[str, os.PathLike],
    spp: Optional[int] = None,
    seed: int = 0,
    *,
    address: Optional[str] = None,
    tasks: Optional[int] = None,
    checkpoint: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[int, int], None]] = True,
    sensor: Optional[Union[int, str]] = None,
    quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
    defaults: Optional[Dict[str, Any]] = None,
    max_retries: int = 3,
    threads_per_task: int = 1,
) -> Tuple[Any, Any, Report]:
    """Renders on Ray and returns ``(sums, scene, report)``: the complete render's ``Sums``,
    the scene loaded on the driver (``scene.develop(sums)`` is the image) and a ``Report``.
    Arguments as for :func:`render`."""
    t_start = time.perf_counter()
    defaults = dict(defaults or {})
    scene_path = os.fspath(scene_path)
    scene = _steradian.load_file(scene_path, **defaults)  # SceneError: file:line:col
    bundle = _collect_bundle(scene, scene_path, defaults)
    plan = scene.plan(spp, seed, sensor, quantity=quantity)
    bounds: List[int] = plan["pass_bounds"]
    sensor_index = sensor if isinstance(sensor, int) else (
        0 if sensor is None else scene.sensor_ids.index(sensor)
    )
    expect = {
        "spp": plan["spp"],
        "seed": plan["seed"],
        "size": (plan["width"], plan["height"]),
        "scene_digest": bundle.digest,
        "sensor": sensor_index,
        "quantity": quantity,
        "branches": plan["branches"],
    }
    report = Report(bundle_bytes=bundle.size)

    # what a checkpoint already holds
    ck = os.fspath(checkpoint) if checkpoint is not None else None
    total, waiting = (_load_checkpoint(ck, expect) if ck else (None, {}))
    done_to = _end(total)
    report.spp_resumed = done_to
    waiting = {f: p for f, p in waiting.items() if f >= done_to}
    todo: List[Tuple[int, int]] = []
    at = done_to
    for f in sorted(waiting) + [plan["spp"]]:
        if f > at:
            todo.append((at, f))
        at = max(at, waiting[f].end if f in waiting else f)

    _connect(address)
    import ray

    # by default one task per pass: a task's result holds one film of sums per pass it renders,
    # so this keeps results (and the object store) at one film each, and tasks as even as the
    # passes are
    want = tasks if tasks is not None else len(bounds) - 1
    if want < 1:
        raise ValueError("tasks must be at least 1")
    # split the missing spans into tasks in proportion to their samples
    left = sum(b - a for a, b in todo) or 1
    ranges: List[Tuple[int, int]] = []
    for a, b in todo:
        span = [x for x in bounds if a <= x <= b]
        ranges += _groups(span, max(1, round(want * (b - a) / left)))

    job = {
        "spp": plan["spp"],
        "seed": plan["seed"],
        "sensor": sensor_index,
        "quantity": quantity,
        "branches": plan["branches"],
        "threads": threads_per_task,
    }
    remote: Any = ray.remote(num_cpus=threads_per_task, max_retries=max_retries)(_render_task)
    log: Any = ray.remote(num_cpus=0)(_TaskLog).remote()  # type: ignore[call-overload]
    bundle_ref = ray.put(bundle)
    pending = {
        remote.remote(bundle_ref, log, i, job, a, b): (i, a, b) for i, (a, b) in enumerate(ranges)
    }
    report.tasks = len(ranges)
    pixels = plan["width"] * plan["height"]
    samples_total = pixels * sum(b - a for a, b in ranges)
    samples_done = 0
    bar = _Bar(len(ranges), samples_total) if progress is True else None
    t_render = time.perf_counter()
    total = _join(total, waiting, ck)  # parts a checkpoint held that follow its prefix
    try:
        while pending:
            ready, _ = ray.wait(list(pending), num_returns=1, timeout=0.5)
            for ref in ready:
                i, a, b = pending.pop(ref)
                try:
                    data, node, secs = ray.get(ref)
                except ray.exceptions.RayTaskError as e:
                    cause = getattr(e, "cause", None)
                    if isinstance(cause, _steradian.SceneError):
                        raise _steradian.SceneError(
                            f"the scene failed to load on a Ray worker: {cause}"
                        ) from None
                    raise DistributedError(f"task {i} (samples {a}..{b}) failed: {cause or e}") from None
                except ray.exceptions.RayError as e:
                    raise DistributedError(
                        f"task {i} (samples {a}..{b}) was lost after {max_retries} retries: {e}"
                    ) from None
                part = Sums.from_bytes(data)
                report.task_seconds[i] = secs
                n = report.nodes.setdefault(node, {"tasks": 0, "samples": 0, "seconds": 0.0})
                n["tasks"] += 1
                n["samples"] += pixels * (b - a)
                n["seconds"] += secs
                samples_done += pixels * (b - a)
                waiting[a] = part
                if ck and a != _end(total):
                    part.save(_part_path(ck, a, b))
                total = _join(total, waiting, ck)
            if bar is not None:
                bar.update(len(ranges) - len(pending), samples_done, time.perf_counter() - t_render)
            elif callable(progress):
                progress(samples_done, samples_total)
    except BaseException:
        for ref in pending:
            ray.cancel(ref, force=True)
        if bar is not None:
            bar.close()
        raise
    if bar is not None:
        bar.close()
    starts: Dict[int, List[Tuple[int, str]]] = ray.get(log.get.remote())
    ray.kill(log)
    report.retried = [(i, *ranges[i]) for i, s in sorted(starts.items()) if len(s) > 1]
    report.samples = samples_done
    report.seconds = time.perf_counter() - t_start
    if total is None or not total.is_complete:
        raise DistributedError("the render ended without all its samples (a bug)")
    if ck and os.path.exists(ck):
        os.remove(ck)
    if progress is True:
        print(report.summary(), file=sys.stderr)
    return total, scene, report


def render(
    scene_path: Union[str, os.PathLike],
    spp: Optional[int] = None,
    seed: int = 0,
    address: Optional[str] = None,
    tasks: Optional[int] = None,
    checkpoint: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[int, int], None]] = True,
    *,
    sensor: Optional[Union[int, str]] = None,
    quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
    defaults: Optional[Dict[str, Any]] = None,
    max_retries: int = 3,
    threads_per_task: int = 1,
) -> np.ndarray:
    """Renders `scene_path` on Ray and returns the array ``Scene.render`` returns for the same
    scene, spp and seed, bit for bit.

    - `address`: None starts a local Ray (or uses the one this process already started);
      ``"auto"`` joins the cluster this machine belongs to; ``"HOST:PORT"`` a head node.
    - `tasks`: how many ranges of passes to render (default: one per pass; at most the
      passes, about 32 + log2(spp/32)).
    - `checkpoint`: a file that keeps finished work; the same call resumes from it, a
      checkpoint of another render is refused, and it is deleted when the render completes.
    - `progress`: True shows a progress bar and a summary on stderr; a callable gets
      ``(samples_done, samples_total)``; False shows nothing.
    - `defaults`: the scene's ``<default>`` overrides (as ``load_file``'s keywords).
    - `max_retries`: Ray's retries of a task whose worker died.
    - `threads_per_task`: threads (and CPUs reserved) per task.
    """
    sums, scene, _ = render_sums(
        scene_path,
        spp,
        seed,
        address=address,
        tasks=tasks,
        checkpoint=checkpoint,
        progress=progress,
        sensor=sensor,
        quantity=quantity,
        defaults=defaults,
        max_retries=max_retries,
        threads_per_task=threads_per_task,
    )
    return scene.develop(sums)


class _Bar:
    """A one-line progress bar on stderr: tasks, percent, samples/s, time left."""

    def __init__(self, tasks: int, samples: int) -> None:
        self.tasks, self.samples = tasks, samples
        self.tty = sys.stderr.isatty()
        self.last = 0.0

    def update(self, tasks_done: int, samples_done: int, elapsed: float) -> None:
        now = time.perf_counter()
        if now - self.last < 0.5 and tasks_done < self.tasks:
            return
        self.last = now
        rate = samples_done / max(elapsed, 1e-9)
        eta = (self.samples - samples_done) / rate if rate > 0 else float("nan")
        frac = samples_done / max(self.samples, 1)
        width = 30
        bar = "#" * int(frac * width) + "-" * (width - int(frac * width))
        line = (
            f"[{bar}] {100 * frac:5.1f}%  tasks {tasks_done}/{self.tasks}  "
            f"{rate / 1e6:.2f} Msamples/s  ETA {eta:.0f} s"
        )
        print(("\r" + line) if self.tty else line, end="" if self.tty else "\n", file=sys.stderr)

    def close(self) -> None:
        if self.tty:
            print(file=sys.stderr)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """``python -m steradian.distributed SCENE.xml --spp N [--address auto] -o OUT.exr``
    (also installed as ``steradian-ray``)."""
    p = argparse.ArgumentParser(
        prog="steradian-ray",
        description="Render a Mitsuba 3 scene on a Ray cluster: the image `steradian render` "
        "writes for the same scene, spp and seed, bit for bit.",
    )
    p.add_argument("scene")
    p.add_argument("--spp", type=int, default=None, help="samples per pixel (default: the scene's)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--address", default=None, help="Ray cluster: auto, HOST:PORT (default: a local Ray)")
    p.add_argument("--tasks", type=int, default=None, help="ranges of passes to render (default: one per pass)")
    p.add_argument("--checkpoint", default=None, help="keep finished work in FILE; resume from it")
    p.add_argument("--sensor", default=None, help="sensor id")
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    p.add_argument("-o", "--output", default=None, help="output OpenEXR (default: SCENE.exr)")
    p.add_argument("--quiet", action="store_true")
    args = p.parse_args(argv)
    defaults = {}
    for d in args.defines:
        name, eq, value = d.partition("=")
        if not eq or not name:
            p.error(f"-D expects NAME=VALUE, got {d!r}")
        defaults[name] = value
    output = args.output or os.path.splitext(args.scene)[0] + ".exr"
    if not output.lower().endswith(".exr"):
        p.error(f"output file {output!r} must end in .exr")
    try:
        image = render(
            args.scene,
            args.spp,
            args.seed,
            address=args.address,
            tasks=args.tasks,
            checkpoint=args.checkpoint,
            progress=not args.quiet,
            sensor=args.sensor,
            defaults=defaults,
        )
    except (_steradian.SceneError, DistributedError, ValueError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    _steradian.write_exr(output, image[..., :3])
    png = os.path.splitext(output)[0] + ".png"
    _steradian.write_png(png, image[..., :3])
    print(f"wrote {output} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
