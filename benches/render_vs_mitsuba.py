#!/usr/bin/env python3
"""Benchmark steradian against Mitsuba 3 on the reference scenes, in one run.

    python3 benches/render_vs_mitsuba.py [--scenes cornell,furnace,pointlight] [--spp 64]
        [--variant llvm_ad_rgb[,scalar_rgb]] [--repeat 3] [--threads N] [--json FILE|-]
        [--pgo] [--no-build] [--allocation auto|adaptive|uniform]

For every scene, in one process and alternating (steradian, then each Mitsuba variant, then
steradian again, ...) so that all see the same machine:

  steradian  the default release build (`cargo build --release`; --pgo: the profile-guided
             build of scripts/build-pgo.sh, the images are the same bit for bit), run as
             `steradian render SCENE --spp N --seed S -o OUT.exr --quiet`, timed as a whole
             process (wall clock of the subprocess: start-up, XML load, BVH build, render,
             EXR + PNG writing). The render time steradian prints itself is reported too.
  Mitsuba 3  the pip package, in this Python process. The scene is loaded and rendered once
             untimed (JIT compile for llvm_* variants), then each timed render is a *warm*
             `mi.render(scene, spp=N, seed=S)` until the image is on the host (no load, no
             write).

Each renderer renders the scene at --pairs pairs of seeds (S + 2k and S + 2k + 1), --repeat
times each, alternating; its reported time is the median of all those timings. The error is
measured free of the reference's own noise, from each pair of seeds, and averaged over the
pairs (one pair's e is itself noisy where fireflies dominate: on glossy_spheres one pair's
Mitsuba e ranged over 2.2e-3 to 5.0e-3) (ref = the scene's reference `<scene>-ref.exr`,
thousands of spp rendered by Mitsuba 3, used only as the scale of the relative error):

  e      = mean((a1 - a2)^2 / (ref^2 + 1e-2)) / 2  over pixels and RGB, averaged over the pairs:
           the relative MSE of one render against its own expectation, whatever the
           reference's noise
  t@1e-3 = time * e / 1e-3: the time needed to reach relMSE 1e-3 (e ~ 1/spp: unbiased Monte Carlo)
  speed-up = Mitsuba t@1e-3 / steradian t@1e-3  (> 1: steradian reaches the target sooner)

and the geometric mean of the speed-ups over the scenes: the headline figure. Bias is checked
separately, against the reference: the ratio of the seeds' mean image to the reference's
mean per channel, and z_bias = (mean of m - mean of ref) / its standard error, m the mean
image over all seeds; |z_bias| stays within about 3 for an unbiased renderer when the
reference's own noise is small against the renders'. Scenes steradian cannot load
yet (e.g. an unknown BSDF plugin) are skipped with the reason.

The speed-up depends on the CPU's vector width, which the report names: Mitsuba's LLVM
variants trace 16 paths per instruction on a CPU with AVX-512, 8 on one with AVX2 only, and
steradian one path at a time on both (cornell: 2.15x on a Zen 3 EPYC with AVX2 only,
2026-12-07; 1.4x to 1.6x on the Xeons and EPYCs of the runs before, those whose flags were
logged having AVX-512). Compare speed-ups between runs on CPUs of the same width only.

The repository is self-contained: scenes and references are read from
crates/steradian-mitsuba/tests/reference/.
"""
import argparse
import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REF_DIR = os.path.join(REPO, "crates", "steradian-mitsuba", "tests", "reference")
TARGET = 1e-3
EPS = 1e-2


# ----------------------------------------------------------------------------- Mitsuba set-up

def pick_libllvm():
    """Point Dr.Jit at the newest libLLVM >= 17 that `ldconfig -p` lists, unless
    DRJIT_LIBLLVM_PATH is already set. drjit 1.5 (mitsuba 3.9) crashes with LLVM 15/16
    ("Cannot select ... fminimum") and rejects LLVM 14. Must run before drjit is imported."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return os.environ["DRJIT_LIBLLVM_PATH"]
    try:
        txt = subprocess.run(["ldconfig", "-p"], capture_output=True, text=True, check=False).stdout
    except OSError:
        return None
    best = None
    for line in txt.splitlines():
        m = re.match(r"\s*(libLLVM[-.]?(?:so\.)?(\d+)[^ ]*)\s.*=>\s*(\S+)", line)
        if m and int(m.group(2)) >= 17:
            cand = (int(m.group(2)), m.group(3))
            best = max(best, cand) if best else cand
    if best:
        os.environ["DRJIT_LIBLLVM_PATH"] = best[1]
        return best[1]
    return None


def import_mitsuba(variants, threads):
    if any(v.startswith("llvm") for v in variants):
        if pick_libllvm() is None:
            sys.exit("no libLLVM >= 17 found (ldconfig -p); install it: apt-get install -y libllvm19 "
                     "(see benches/README.md), or run with --variant scalar_rgb")
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:
        sys.exit(f"cannot import mitsuba ({e}); install it: pip install mitsuba==3.9.1 numpy")
    for v in variants:
        if v not in mi.variants():
            sys.exit(f"Mitsuba variant '{v}' is not available (have: {', '.join(mi.variants())})")
    if threads:
        dr.set_thread_count(threads)
    return mi, dr


# ----------------------------------------------------------------------------- images

def load_exr(mi, dr, np, path):
    # Mitsuba 3.9.1 / drjit 1.5 deadlock in Bitmap's (OpenEXR) read when the thread count is 1
    # (readPixels waits on a pool with no worker), so read with at least 2 threads.
    tc = dr.thread_count()
    if tc < 2:
        dr.set_thread_count(2)
    try:
        arr = np.array(mi.Bitmap(path), dtype=np.float64)
    finally:
        if tc < 2:
            dr.set_thread_count(tc)
    if arr.ndim == 2:
        arr = arr[..., None]
    return arr[..., :3]


def metrics(np, pairs, ref):
    """Pairs of renders at different seeds against the reference (see the module docs):
    e (relative MSE of one render, free of the reference's noise, averaged over the pairs),
    the mean ratio per channel and z_bias."""
    for a1, a2 in pairs:
        if a1.shape != ref.shape or a2.shape != ref.shape:
            raise ValueError(f"image shape {a1.shape} differs from the reference's {ref.shape}")
    w = 1.0 / (ref * ref + EPS)
    # per pixel, the variance of one render, from each pair
    e_pix = sum((a1 - a2) ** 2 / 2 for a1, a2 in pairs) / len(pairs)
    e = float(np.mean(e_pix * w))
    k = 2 * len(pairs)
    m = sum(a1 + a2 for a1, a2 in pairs) / k
    mm = m.reshape(-1, m.shape[-1]).mean(0)
    mr = np.maximum(ref.reshape(-1, ref.shape[-1]).mean(0), 1e-30)
    # the variance of the image mean: sum over pixels of (one render's variance / k) / n^2
    n = m.size
    se = float(np.sqrt(np.sum(e_pix / k)) / n)
    z = float((m.mean() - ref.mean()) / se) if se > 0 else 0.0
    return e, [float(x) for x in mm / mr], z


# ----------------------------------------------------------------------------- steradian

PGO_EXE = os.path.join(REPO, "target", "pgo", "release", "steradian")
RELEASE_EXE = os.path.join(REPO, "target", "release", "steradian")


def build_steradian_pgo():
    """scripts/build-pgo.sh: the release build with profile-guided optimisation, trained on
    scenes outside this benchmark; returns the path of the binary."""
    print("building: bash scripts/build-pgo.sh (profile-guided release build)", file=sys.stderr, flush=True)
    p = subprocess.run(["bash", os.path.join(REPO, "scripts", "build-pgo.sh")], cwd=REPO, stdout=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("scripts/build-pgo.sh failed")
    exe = p.stdout.strip().splitlines()[-1] if p.stdout.strip() else ""
    if not os.path.exists(exe):
        sys.exit("scripts/build-pgo.sh did not print the steradian executable")
    return exe


def build_steradian():
    """cargo build --release -p steradian-cli; returns the path of the binary."""
    cmd = ["cargo", "build", "--release", "-p", "steradian-cli", "--message-format=json-render-diagnostics"]
    print("building: " + " ".join(cmd[:5]), file=sys.stderr, flush=True)
    p = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("cargo build failed")
    exe = None
    for line in p.stdout.splitlines():
        try:
            msg = json.loads(line)
        except ValueError:
            continue
        if msg.get("reason") == "compiler-artifact" and msg.get("executable") and \
                msg.get("target", {}).get("name") == "steradian":
            exe = msg["executable"]
    if not exe or not os.path.exists(exe):
        sys.exit("cargo build did not report the steradian executable")
    return exe


RENDERED = re.compile(r"rendered (\d+)x(\d+) at (\d+) spp in ([0-9.]+) s")
ALLOCATION = re.compile(r"allocation: a pilot of (\d+) spp \(([0-9.]+) s\) predicted ([0-9.]+)\S* "
                        r"lower relative variance adaptive: (adaptive|uniform)")


def run_steradian(exe, scene, spp, seed, threads, out, allocation=None):
    cmd = [exe, "render", scene, "--spp", str(spp), "--seed", str(seed), "-o", out, "--quiet"]
    if threads:
        cmd += ["--threads", str(threads)]
    if allocation:
        cmd += ["--allocation", allocation]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    if p.returncode != 0:
        return dict(error=(p.stderr.strip() or p.stdout.strip() or f"exit status {p.returncode}"))
    m = RENDERED.search(p.stdout)
    res = dict(wall=wall, cpu=cpu)
    if m:
        res["res"] = [int(m.group(1)), int(m.group(2))]
        res["render_s"] = float(m.group(4))
        if int(m.group(3)) != spp:
            res["error"] = f"steradian rendered {m.group(3)} spp instead of {spp}"
    a = ALLOCATION.search(p.stdout)
    res["allocation"] = dict(kind=a.group(4), pilot_s=float(a.group(2)),
                             predicted_gain=float(a.group(3))) if a else dict(kind="uniform")
    return res


# ----------------------------------------------------------------------------- Mitsuba

class MitsubaScene:
    """One scene loaded in one variant, compiled by an untimed first render."""

    def __init__(self, mi, np, variant, path, spp, seed):
        self.mi, self.np, self.variant, self.spp, self.seed = mi, np, variant, spp, seed
        mi.set_variant(variant)
        t0 = time.perf_counter()
        self.scene = mi.load_file(path)
        self.load_s = time.perf_counter() - t0
        t0 = time.perf_counter()
        self.image = self._render()
        self.cold_s = time.perf_counter() - t0  # includes the JIT compile (or a kernel-cache hit)

    def _render(self, seed=None):
        img = self.mi.render(self.scene, spp=self.spp, seed=self.seed if seed is None else seed)
        return self.np.array(img, dtype=self.np.float64)  # forces evaluation and the copy to host

    def timed(self, seed):
        """(wall s, cpu s, image) of a warm render at `seed`."""
        self.mi.set_variant(self.variant)
        t0 = time.perf_counter()
        c0 = time.process_time()
        image = self._render(seed)
        return time.perf_counter() - t0, time.process_time() - c0, image


# ----------------------------------------------------------------------------- benchmark

def scene_paths(name):
    if name.endswith(".xml"):
        xml = os.path.abspath(name)
        ref = xml[:-4] + "-ref.exr"
    else:
        xml = os.path.join(REF_DIR, name + ".xml")
        ref = os.path.join(REF_DIR, name + "-ref.exr")
    return os.path.splitext(os.path.basename(xml))[0], xml, ref


def fmt_t(x):
    return "-" if x is None else (f"{x:.3f}" if x < 10 else f"{x:.1f}")


def cpu_description():
    """The CPU's model and the SIMD width Mitsuba's LLVM variants run at on it. The speed-up
    depends on it: Dr.Jit's LLVM backend evaluates 16 paths per instruction where the CPU has
    AVX-512 (feature avx512vl), 8 with AVX and 4 with SSE 4.2 (drjit-core's rule), while
    steradian traces one path at a time on any of them."""
    info = {}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key, _, value = line.partition(":")
                key = key.strip()
                if key in ("model name", "cpu family", "model", "flags") and key not in info:
                    info[key] = value.strip()
    except OSError:
        return dict(model=platform.processor() or platform.machine(), llvm_lanes=None)
    flags = set(info.get("flags", "").split())
    lanes = 16 if "avx512vl" in flags else 8 if "avx" in flags else 4 if "sse4_2" in flags else 1
    return dict(model=info.get("model name", "?"), family=info.get("cpu family"), cpu_model=info.get("model"),
                avx512="avx512vl" in flags, llvm_lanes=lanes)


def run(scenes, spp, variants, repeat, threads, seed=0, keep=None, build=True, log=sys.stderr, pgo=False,
        pairs=1, allocation=None):
    """Runs the benchmark; returns a JSON-able dict (and prints progress to `log`).
    `pgo`: time the profile-guided build (scripts/build-pgo.sh), else the plain release build;
    `build`: build it first, else use the binary already there; `allocation`: steradian's
    --allocation (None: its default)."""
    import numpy as np
    mi, dr = import_mitsuba(variants, threads)
    if build:
        exe = build_steradian_pgo() if pgo else build_steradian()
    else:
        exe = PGO_EXE if pgo else RELEASE_EXE
    workdir = keep or tempfile.mkdtemp(prefix="steradian_bench_")
    os.makedirs(workdir, exist_ok=True)
    result = dict(spp=spp, seed=seed, pairs=pairs, repeat=repeat, threads=threads or os.cpu_count(),
                  variants=variants, target_relmse=TARGET, cpu_count=os.cpu_count(),
                  loadavg_start=[round(x, 2) for x in os.getloadavg()], scenes=[], skipped=[],
                  libllvm=os.environ.get("DRJIT_LIBLLVM_PATH"), mitsuba_version=mi.__version__,
                  steradian=exe, steradian_build="profile-guided release" if pgo else "release",
                  allocation=allocation or "default (auto)", cpu=cpu_description())
    try:
        for name in scenes:
            sname, xml, ref = scene_paths(name)
            if not os.path.exists(xml) or not os.path.exists(ref):
                result["skipped"].append(dict(scene=sname, reason=f"no scene or reference ({xml}, {ref})"))
                print(f"[{sname}] SKIPPED: missing {xml} or {ref}", file=log, flush=True)
                continue
            # Probe: 1 spp, untimed; checks steradian can load the scene and warms the page cache.
            probe = run_steradian(exe, xml, 1, seed, threads, os.path.join(workdir, f"{sname}-probe.exr"))
            if "error" in probe:
                err = re.sub(r"^error: ", "", probe["error"].splitlines()[-1])
                why = "steradian cannot load it yet" if "unknown" in err and "plugin" in err \
                    else "steradian fails on it"
                result["skipped"].append(dict(scene=sname, reason=f"{why}: {err}"))
                print(f"[{sname}] SKIPPED ({why}): {err}", file=log, flush=True)
                continue
            print(f"[{sname}] loading + compiling in Mitsuba ({', '.join(variants)}) ...", file=log, flush=True)
            peers = {v: MitsubaScene(mi, np, v, xml, spp, seed) for v in variants}
            seeds = list(range(seed, seed + 2 * pairs))
            st_outs = [os.path.join(workdir, f"{sname}-steradian-{k}.exr") for k in seeds]
            st_runs, mi_runs = [], {v: [] for v in variants}
            mi_imgs = {v: {} for v in variants}
            for i in range(repeat):
                for k, st_out in zip(seeds, st_outs):
                    r = run_steradian(exe, xml, spp, k, threads, st_out, allocation)
                    if "error" in r:
                        raise RuntimeError(f"[{sname}] steradian: {r['error']}")
                    st_runs.append(r)
                    line = f"[{sname}] run {i + 1}/{repeat}, seed {k}: steradian {r['wall']:.3f} s"
                    for v in variants:
                        wall, cpu, img = peers[v].timed(k)
                        mi_runs[v].append((wall, cpu))
                        mi_imgs[v][k] = img
                        line += f", {v} {wall:.3f} s"
                    print(line, file=log, flush=True)
            refimg = load_exr(mi, dr, np, ref)
            st_imgs = [load_exr(mi, dr, np, o) for o in st_outs]
            st_e, st_ratio, st_z = metrics(np, list(zip(st_imgs[0::2], st_imgs[1::2])), refimg)
            st_wall = statistics.median(r["wall"] for r in st_runs)
            st = dict(time_s=st_wall, cpu_s=statistics.median(r["cpu"] for r in st_runs),
                      render_s=statistics.median(r.get("render_s", float("nan")) for r in st_runs),
                      times=[round(r["wall"], 4) for r in st_runs],
                      relmse=st_e, mean_ratio=st_ratio, z_bias=st_z, t_target_s=st_wall * st_e / TARGET,
                      allocation=st_runs[0]["allocation"])
            entry = dict(scene=sname, spp=spp, seeds=list(seeds), res=st_runs[0].get("res"),
                         steradian=st, mitsuba={})
            for v in variants:
                if keep:
                    for k in seeds:
                        mi.Bitmap(mi_imgs[v][k].astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(
                            os.path.join(workdir, f"{sname}-{v}-{k}.exr"))
                imgs = [mi_imgs[v][k] for k in seeds]
                e, ratio, z = metrics(np, list(zip(imgs[0::2], imgs[1::2])), refimg)
                t = statistics.median(x[0] for x in mi_runs[v])
                tt = t * e / TARGET
                entry["mitsuba"][v] = dict(
                    time_s=t, cpu_s=statistics.median(x[1] for x in mi_runs[v]),
                    times=[round(x[0], 4) for x in mi_runs[v]],
                    load_s=peers[v].load_s, first_render_s=peers[v].cold_s,
                    relmse=e, mean_ratio=ratio, z_bias=z, t_target_s=tt,
                    time_ratio=t / st_wall,
                    speedup=tt / st["t_target_s"] if st["t_target_s"] > 0 else None)
            result["scenes"].append(entry)
            del peers
    finally:
        if not keep:
            shutil.rmtree(workdir, ignore_errors=True)
    result["loadavg_end"] = [round(x, 2) for x in os.getloadavg()]
    result["geomean_speedup"] = {}
    for v in variants:
        sp = [e["mitsuba"][v]["speedup"] for e in result["scenes"] if e["mitsuba"][v]["speedup"]]
        result["geomean_speedup"][v] = math.exp(sum(map(math.log, sp)) / len(sp)) if sp else None
    return result


def report(res, out=sys.stdout):
    p = lambda s="": print(s, file=out)
    p(f"steradian vs Mitsuba {res['mitsuba_version']} ({', '.join(res['variants'])}), "
      f"{res['spp']} spp, seed {res['seed']}, median of {res['repeat']}, "
      f"{res['threads']} threads on {res['cpu_count']} cores")
    p(f"load average at start {res['loadavg_start']}, at end {res['loadavg_end']}")
    cpu = res.get("cpu")
    if cpu:
        p(f"CPU: {cpu['model']} (family {cpu.get('family')}, model {cpu.get('cpu_model')}), "
          f"AVX-512 {'yes' if cpu.get('avx512') else 'no'}: Mitsuba's LLVM variants trace "
          f"{cpu['llvm_lanes']} paths per vector instruction, steradian one path at a time "
          f"(compare speed-ups only between CPUs of the same width)")
    p(f"steradian: {res.get('steradian_build', 'release')} build ({res['steradian']})")
    p("steradian time = whole process (load + render + write); Mitsuba time = warm mi.render() only")
    p("e = mean((a1 - a2)^2 / (ref^2 + 0.01)) / 2, averaged over the pairs of seeds "
      + (", ".join(map(str, res["scenes"][0]["seeds"])) if res["scenes"] else "-"))
    p("t@1e-3 = time x e / 1e-3 (e ~ 1/spp); speed-up = Mitsuba t@1e-3 / steradian t@1e-3")
    p("bias: mean ratio to the reference per channel, z_bias = (image mean - reference mean) / its stderr")
    p("own s = the render time steradian prints itself (no start-up, load or writing)")
    p(f"steradian sample allocation: {res.get('allocation', 'default (auto)')}")
    p()
    hdr = f"{'scene':<14} {'renderer':<12} {'spp':>4} {'time s':>7} {'own s':>6} {'cpu s':>7} {'e':>9} " \
          f"{'mean ratio R,G,B':<22} {'z_bias':>6} {'t@1e-3 s':>8} {'speed-up':>8}"
    p(hdr)
    p("-" * len(hdr))
    for e in res["scenes"]:
        s = e["steradian"]
        p(f"{e['scene']:<14} {'steradian':<12} {e['spp']:>4} {fmt_t(s['time_s']):>7} {fmt_t(s['render_s']):>6} {fmt_t(s['cpu_s']):>7} "
          f"{s['relmse']:>9.3e} {','.join(f'{x:.4f}' for x in s['mean_ratio']):<22} {s['z_bias']:>6.2f} "
          f"{fmt_t(s['t_target_s']):>8} {'':>8}")
        for v, m in e["mitsuba"].items():
            sp = "-" if m["speedup"] is None else f"{m['speedup']:.2f}x"
            p(f"{'':<14} {v:<12} {e['spp']:>4} {fmt_t(m['time_s']):>7} {'':>6} {fmt_t(m['cpu_s']):>7} "
              f"{m['relmse']:>9.3e} {','.join(f'{x:.4f}' for x in m['mean_ratio']):<22} {m['z_bias']:>6.2f} "
              f"{fmt_t(m['t_target_s']):>8} {sp:>8}")
    p()
    for v, g in res["geomean_speedup"].items():
        n = sum(1 for e in res["scenes"] if e["mitsuba"][v]["speedup"])
        p(f"geometric mean speed-up vs {v} over {n} scene(s): " + ("-" if g is None else f"{g:.2f}x"))
    for e in res["scenes"]:
        a = e["steradian"].get("allocation", {})
        if "pilot_s" in a:
            p(f"{e['scene']}: {a['kind']} (pilot {a['pilot_s']:.2f} s, predicted gain {a['predicted_gain']:.2f}x)")
    for s in res["skipped"]:
        p(f"skipped {s['scene']}: {s['reason']}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="cornell,materials,veach",
                    help="comma-separated names in crates/steradian-mitsuba/tests/reference/ "
                         "(or paths to X.xml with X-ref.exr beside); default %(default)s")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--variant", default="llvm_ad_rgb",
                    help="Mitsuba variant(s), comma-separated, e.g. scalar_rgb,llvm_ad_rgb; default %(default)s")
    ap.add_argument("--threads", type=int, default=0, help="worker threads for both renderers (0 = all cores)")
    ap.add_argument("--repeat", type=int, default=3, help="timed runs per renderer; the median is reported")
    ap.add_argument("--seed", type=int, default=0, help="first seed; pairs use seed, seed + 1, ...")
    ap.add_argument("--pairs", type=int, default=1, help="pairs of seeds the error is averaged over")
    ap.add_argument("--json", metavar="FILE", help="also write the results as JSON to FILE ('-' = stdout only)")
    ap.add_argument("--keep", metavar="DIR", help="keep the rendered EXRs in DIR")
    ap.add_argument("--pgo", action="store_true",
                    help="time the profile-guided build (scripts/build-pgo.sh) instead of the "
                         "default release build (cargo build --release)")
    ap.add_argument("--allocation", choices=["auto", "adaptive", "uniform"],
                    help="steradian's --allocation (default: steradian's own default, auto)")
    ap.add_argument("--no-build", action="store_true",
                    help="use the binary already built (target/release/steradian, or "
                         "target/pgo/release/steradian with --pgo)")
    a = ap.parse_args(argv)
    if a.spp < 1 or a.repeat < 1 or a.pairs < 1 or a.threads < 0:
        ap.error("--spp, --repeat and --pairs must be >= 1, --threads >= 0")
    res = run([s for s in a.scenes.split(",") if s], a.spp, [v for v in a.variant.split(",") if v],
              a.repeat, a.threads, a.seed, a.keep, not a.no_build, pgo=a.pgo, pairs=a.pairs,
              allocation=a.allocation)
    if a.json == "-":
        print(json.dumps(res, indent=1))
    else:
        report(res)
        if a.json:
            with open(a.json, "w") as f:
                json.dump(res, f, indent=1)
    return res


if __name__ == "__main__":
    main()
