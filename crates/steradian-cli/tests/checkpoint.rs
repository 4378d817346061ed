//! `steradian render --checkpoint/--resume`: a render killed at any moment (SIGKILL) or
//! stopped with Ctrl-C, then resumed, writes the uninterrupted render's image bit for bit;
//! checkpoints of another render are refused with a clear message.

#![cfg(unix)]

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use steradian::film::read_exr;
use steradian::testkit::temp_dir;

const BIN: &str = env!("CARGO_BIN_EXE_steradian");

/// The built-in Cornell box, small, at enough samples to take a few seconds.
const SCENE: [&str; 7] = ["render", "-D", "res=24", "--spp", "1536", "--seed", "3"];

fn run(dir: &Path, extra: &[&str]) -> Output {
    let mut args: Vec<&str> = SCENE.to_vec();
    args.extend_from_slice(extra);
    Command::new(BIN).args(&args).current_dir(dir).output().expect("runs steradian")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn bits(path: &Path) -> Vec<u32> {
    let img = read_exr(path).unwrap_or_else(|e| panic!("{e}"));
    img.data.iter().map(|v| v.to_bits()).collect()
}

/// Starts the render with `extra`, waits until the checkpoint `ck` has been written at least
/// once and `more` has passed, then sends `signal`.
fn interrupt(dir: &Path, extra: &[&str], ck: &Path, more: Duration, signal: &str) -> Output {
    let before = std::fs::metadata(ck).and_then(|m| m.modified()).ok();
    let mut args: Vec<&str> = SCENE.to_vec();
    args.extend_from_slice(extra);
    let child = Command::new(BIN)
        .args(&args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs steradian");
    let start = Instant::now();
    loop {
        let now = std::fs::metadata(ck).and_then(|m| m.modified()).ok();
        if now.is_some() && now != before {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no checkpoint written");
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(more);
    let pid = child.id().to_string();
    assert!(Command::new("kill").args([signal, &pid]).status().expect("kill").success());
    child.wait_with_output().expect("waits")
}

#[test]
fn killed_and_resumed_renders_are_the_uninterrupted_render() {
    let dir = temp_dir("checkpoint");
    let full = run(&dir, &["-o", "full.exr", "--quiet"]);
    assert!(full.status.success(), "{}", text(&full.stderr));
    let ck = dir.join("render.ck");
    let ck_arg = ck.to_str().expect("utf-8 path");

    // SIGKILL right after a checkpoint write, while the next passes render
    let killed = interrupt(
        &dir,
        &["-o", "out.exr", "--checkpoint", ck_arg, "--checkpoint-interval", "0", "--quiet"],
        &ck,
        Duration::from_millis(150),
        "-KILL",
    );
    assert!(!killed.status.success(), "the render finished before it was killed");
    assert!(ck.exists() && !dir.join("out.exr").exists());

    // resumed, then stopped with Ctrl-C: the checkpoint is rewritten and says so
    let stopped = interrupt(
        &dir,
        &["-o", "out.exr", "--resume", ck_arg, "--checkpoint-interval", "0", "--quiet"],
        &ck,
        Duration::from_millis(150),
        "-INT",
    );
    let stderr = text(&stopped.stderr);
    assert_eq!(stopped.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("checkpoint: ") && stderr.contains("continue with --resume"),
        "{stderr}"
    );

    // resumed to the end: the uninterrupted image, bit for bit; the checkpoint is gone
    let done = run(&dir, &["-o", "out.exr", "--resume", ck_arg, "--quiet"]);
    let stdout = text(&done.stdout);
    assert!(done.status.success(), "{}", text(&done.stderr));
    assert!(stdout.contains("resumed from the checkpoint"), "{stdout}");
    assert_eq!(bits(&dir.join("out.exr")), bits(&dir.join("full.exr")));
    assert!(!ck.exists(), "a finished render removes its checkpoint");
}

#[test]
fn a_checkpoint_of_another_render_is_refused() {
    let dir = temp_dir("checkpoint-mismatch");
    let ck = dir.join("other.ck");
    let ck_arg = ck.to_str().expect("utf-8 path");
    let stopped = interrupt(
        &dir,
        &["-o", "a.exr", "--checkpoint", ck_arg, "--checkpoint-interval", "0", "--quiet"],
        &ck,
        Duration::ZERO,
        "-KILL",
    );
    assert!(!stopped.status.success());
    let refused = |args: &[&str], needle: &str| {
        let out = Command::new(BIN).args(args).current_dir(&dir).output().expect("runs");
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    };
    let with = |res: &'static str, spp: &'static str, seed: &'static str, more: &[&'static str]| {
        let mut a = vec!["render", "--resume", ck_arg, "-D", res, "--spp", spp, "--seed", seed];
        a.extend_from_slice(more);
        a
    };
    refused(&with("res=24", "1536", "4", &[]), "seed 4, expected 3");
    refused(&with("res=24", "1024", "3", &[]), "spp 1024, expected 1536");
    // the scene's own spp, whose passes the checkpoint's range does not fit: still named
    refused(&["render", "--resume", ck_arg, "-D", "res=24", "--seed", "3"], "expected 1536");
    refused(&with("res=16", "1536", "3", &[]), "resolution 16x16, expected 24x24");
    refused(&with("res=24", "1536", "3", &["-D", "spp=8"]), "scene (digest of its files");
    std::fs::write(dir.join("junk.ck"), "not a checkpoint").expect("writes");
    let junk = dir.join("junk.ck");
    let junk = junk.to_str().expect("utf-8");
    refused(&["render", "--resume", junk], "not a steradian sums record");
    refused(&["render", "--resume", "missing.ck"], "cannot read checkpoint missing.ck");
}

/// `--time-limit`: the render ends near the limit with whole passes, says so, and with
/// `--checkpoint` a later `--resume` completes it to the uninterrupted image.
#[test]
fn a_time_limited_render_ends_in_time_and_resumes() {
    let dir = temp_dir("time-limit");
    let ck = dir.join("t.ck");
    let ck_arg = ck.to_str().expect("utf-8 path");
    let start = Instant::now();
    let out = run(&dir, &["-o", "t.exr", "--time-limit", "0.5", "--checkpoint", ck_arg, "--quiet"]);
    let took = start.elapsed();
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("time limit reached: the image holds "), "{stderr}");
    assert!(took < Duration::from_secs(30), "took {took:?}");
    assert!(dir.join("t.exr").exists() && ck.exists(), "image and checkpoint written");
    let done = run(&dir, &["-o", "t.exr", "--resume", ck_arg, "--quiet"]);
    assert!(done.status.success(), "{}", text(&done.stderr));
    let full = run(&dir, &["-o", "full.exr", "--quiet"]);
    assert!(full.status.success());
    assert_eq!(bits(&dir.join("t.exr")), bits(&dir.join("full.exr")));
    for bad in ["0", "-1", "nan"] {
        let out = Command::new(BIN)
            .args(["render", &format!("--time-limit={bad}")])
            .current_dir(&dir)
            .output()
            .expect("runs");
        assert_eq!(out.status.code(), Some(1), "--time-limit {bad}");
        assert!(text(&out.stderr).contains("--time-limit must be a positive number"), "{bad}");
    }
}
