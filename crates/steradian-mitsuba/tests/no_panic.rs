//! Truncated real scenes and random bytes must give `Err`, never a panic.

mod common;

use std::path::{Path, PathBuf};

use steradian_mitsuba::parse_string;

/// A small deterministic PRNG (xorshift64*), so failures reproduce.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

/// The folder that a scene's includes resolve against.
fn folder() -> PathBuf {
    common::reference_scene("")
}

/// Every test scene: name and text.
fn scenes() -> Vec<(String, String)> {
    let v: Vec<(String, String)> = common::all_scenes()
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
        .collect();
    assert!(v.len() >= 15, "{} scenes in tests/reference/ and scenes/validation/", v.len());
    v
}

#[test]
fn truncated_scenes_are_errors() {
    for (name, text) in scenes() {
        assert!(parse_string(&text, &folder(), &[]).is_ok(), "{name} must parse whole");
        // Every prefix that cuts into the closing </scene>: the root is never closed.
        let end = text.rfind("</scene>").unwrap() + "</scene>".len();
        let bounds: Vec<usize> = (0..end).filter(|&i| text.is_char_boundary(i)).collect();
        for &cut in &bounds {
            let r = std::panic::catch_unwind(|| parse_string(&text[..cut], &folder(), &[]));
            match r {
                Ok(res) => assert!(res.is_err(), "{name} truncated at {cut} parsed"),
                Err(_) => panic!("{name} truncated at {cut} panicked"),
            }
        }
    }
}

#[test]
fn random_garbage_is_an_error() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..2000 {
        let len = (rng.next() % 300) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        let text = String::from_utf8_lossy(&bytes).into_owned();
        assert!(parse_string(&text, Path::new("."), &[]).is_err());
    }
}

#[test]
fn mutated_scenes_never_panic() {
    // Random single-byte edits of real scenes from an XML-ish alphabet: may parse or not,
    // must not panic.
    let alphabet = b"<>/=\"' $:,.-0123456789eEnaifxyz_\n";
    let mut rng = Rng(42);
    for (name, text) in scenes() {
        for _ in 0..300 {
            let mut bytes = text.clone().into_bytes();
            for _ in 0..1 + rng.next() % 4 {
                let i = (rng.next() as usize) % bytes.len();
                bytes[i] = alphabet[(rng.next() as usize) % alphabet.len()];
            }
            let Ok(s) = String::from_utf8(bytes) else { continue };
            let r = std::panic::catch_unwind(|| {
                let _ = parse_string(&s, &folder(), &[]);
            });
            assert!(r.is_ok(), "{name} mutated panicked:\n{s}");
        }
    }
}
