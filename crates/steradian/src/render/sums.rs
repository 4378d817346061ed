//! A render's raw sums ([`RenderSums`]): what checkpoints, resumed renders and distributed
//! renders are made of.
//!
//! **What they hold.** Per pixel the f64 sums Σw·L, Σw, Σw·L² and Σw² (and Σw·a per AOV
//! layer) of the samples of a range of the render's passes, and the count of NaN/Inf samples
//! dropped, with a header saying which render they belong to (film size, spp, seed, sampler,
//! branch count, quantity, sensor, scene digest, sample allocation). Nothing is normalised: the image is Σw·L/Σw.
//!
//! **Why they add up bit for bit.** f64 addition is not associative, so sums can only be
//! combined in one fixed order. The order is the render's *pass* structure, which depends on
//! the spp alone (`schedule.rs`): a pass's sums start from zero and take its blocks in item
//! order; the render's sums are the passes folded in pass order, S = ((P₀ + P₁) + P₂) + ….
//! A range that starts at sample 0 (a *prefix*: what a checkpoint holds) keeps that fold, one
//! film. A range that starts later keeps each of its passes apart (and their fold, for its own
//! image), so that appending it to the prefix before it folds the very same passes in the very
//! same order. Hence: the passes of a render, split into any ranges, rendered anywhere (threads,
//! processes, machines, a resumed process) and appended in range order, give the uninterrupted
//! render's sums bit for bit. A later range costs one film per pass it holds; a prefix one.
//!
//! **Bytes.** [`RenderSums::to_bytes`] writes a little-endian record (magic, format version,
//! steradian's version, the header, the range, then each kept film's sums) that
//! [`RenderSums::from_bytes`] reads back exactly; checkpoint files and distributed task results
//! use it. A record from another steradian version is refused: the sums of another build's
//! passes would not be the same samples.

use std::fmt;

use crate::film::{AovLayer, BoxFilter, Film, PixelAccum};
use crate::sampling::SamplerKind;

use super::quantity::PixelQuantity;

/// Which render a set of sums belongs to: two sums combine only when their headers are equal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SumsHeader {
    pub width: u32,
    pub height: u32,
    /// AOV layers kept per pixel (`moment`, `aov`), 0 for most integrators.
    pub aov_layers: u32,
    /// Samples per pixel of the whole render (the pass structure follows from it).
    pub spp: u32,
    pub seed: u64,
    pub sampler: SamplerKind,
    /// Paths continued from each camera ray's first hit (`path`), 0 for other integrators.
    pub branches: u32,
    pub quantity: PixelQuantity,
    /// Index of the sensor rendered.
    pub sensor: u32,
    /// A digest of the scene's files and overrides, set by the front end that knows them
    /// (0: not set). The renderer itself does not read it.
    pub scene_digest: u64,
    /// A digest of an adaptive render's sample densities (`adaptive.rs`), 0 for a uniform
    /// render: sums of different allocations cannot be joined.
    pub allocation: u64,
}

/// Why sums could not be read or combined.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SumsError {
    /// Not a steradian sums record, or a damaged one.
    Malformed(String),
    /// Made by another steradian version (its own version string).
    Version(String),
    /// Of another render: what differs, in words.
    Mismatch(String),
    /// Not the range that follows (the expected first sample, the one given).
    NotContiguous { expected: u32, got: u32 },
}

impl fmt::Display for SumsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SumsError::Malformed(m) => write!(f, "not a steradian sums record: {m}"),
            SumsError::Version(v) => write!(
                f,
                "made by steradian {v}, this is steradian {}: sums of another version cannot be combined",
                crate::VERSION
            ),
            SumsError::Mismatch(m) => write!(f, "belongs to another render: {m}"),
            SumsError::NotContiguous { expected, got } => write!(
                f,
                "the next range must start at sample {expected}, this one starts at sample {got}"
            ),
        }
    }
}

impl std::error::Error for SumsError {}

/// The raw sums of the passes `first..end` (samples per pixel) of a render (module docs).
#[derive(Clone, Debug)]
pub struct RenderSums {
    pub header: SumsHeader,
    first: u32,
    end: u32,
    /// All passes of the range folded in pass order.
    folded: Film,
    /// Each pass apart (its last sample + 1, its sums), for a range that starts after 0.
    passes: Vec<(u32, Film)>,
}

/// Adds `src`'s sums into `dst` (same size and layer count, checked by the callers).
fn fold(dst: &mut Film, src: &Film) {
    let (s_px, s_aov) = src.sums();
    let dropped = src.dropped();
    let (d_px, d_aov, d_dropped) = dst.sums_mut();
    for (d, s) in d_px.iter_mut().zip(s_px) {
        d.add(s);
    }
    for (a, b) in d_aov.iter_mut().zip(s_aov) {
        for c in 0..3 {
            a[c] += b[c];
        }
    }
    *d_dropped += dropped;
}

impl RenderSums {
    /// No samples yet, at sample `first`; `film` (cleared) gives the size and AOV layers.
    pub fn empty(header: SumsHeader, film: &Film, first: u32) -> RenderSums {
        let mut folded = film.clone();
        folded.clear();
        RenderSums { header, first, end: first, folded, passes: Vec::new() }
    }

    /// The first sample per pixel of the range.
    pub fn first(&self) -> u32 {
        self.first
    }

    /// One past the last sample per pixel of the range.
    pub fn end(&self) -> u32 {
        self.end
    }

    /// Whether the range starts at sample 0 (a prefix of the render: its sums are the render's
    /// so far, and develop to its image).
    pub fn is_prefix(&self) -> bool {
        self.first == 0
    }

    /// Whether the sums hold every pass of the render.
    pub fn is_complete(&self) -> bool {
        self.first == 0 && self.end == self.header.spp
    }

    /// The range's passes folded: a film whose develop() is the range's image.
    pub fn film(&self) -> &Film {
        &self.folded
    }

    /// The range's image in the unit of its quantity (illuminance converted from the
    /// irradiance sums), as [`RenderOutput::image`](super::RenderOutput::image) gives it.
    pub fn image(&self) -> crate::film::Image {
        self.in_quantity(self.folded.develop())
    }

    /// The standard error of each pixel of [`image`](Self::image).
    pub fn stderr_image(&self) -> crate::film::Image {
        self.in_quantity(self.folded.develop_stderr())
    }

    fn in_quantity(&self, image: crate::film::Image) -> crate::film::Image {
        match self.header.quantity {
            PixelQuantity::SurfaceIlluminance => image.to_illuminance(),
            PixelQuantity::Sensor | PixelQuantity::SurfaceIrradiance => image,
        }
    }

    /// The film, taken.
    pub fn into_film(self) -> Film {
        self.folded
    }

    /// Adds the next pass, which ends at sample `end` (its blocks already merged into `pass` in
    /// item order, from zero).
    pub fn push_pass(&mut self, end: u32, pass: Film) {
        debug_assert!(end > self.end, "passes come in order");
        fold(&mut self.folded, &pass);
        if self.first > 0 {
            self.passes.push((end, pass));
        }
        self.end = end;
    }

    /// Appends the range that follows (same render, starting at [`end`](Self::end)): the
    /// result is what one render of both ranges holds, bit for bit.
    pub fn append(&mut self, next: RenderSums) -> Result<(), SumsError> {
        self.check_same_render(&next.header)?;
        if next.first != self.end {
            return Err(SumsError::NotContiguous { expected: self.end, got: next.first });
        }
        if next.first == next.end {
            return Ok(());
        }
        if next.first == 0 {
            // self is empty at 0: the next range is the prefix itself
            *self = RenderSums { header: self.header, ..next };
            return Ok(());
        }
        for (end, pass) in next.passes {
            self.push_pass(end, pass);
        }
        Ok(())
    }

    /// Errors unless `other` describes the same render (the scene digest included).
    pub fn check_same_render(&self, other: &SumsHeader) -> Result<(), SumsError> {
        let (a, b) = (&self.header, other);
        let differ = |what: &str, x: String, y: String| {
            Err(SumsError::Mismatch(format!("{what} {y}, expected {x}")))
        };
        if (a.width, a.height) != (b.width, b.height) {
            return differ(
                "resolution",
                format!("{}x{}", a.width, a.height),
                format!("{}x{}", b.width, b.height),
            );
        }
        if a.spp != b.spp {
            return differ("spp", a.spp.to_string(), b.spp.to_string());
        }
        if a.seed != b.seed {
            return differ("seed", a.seed.to_string(), b.seed.to_string());
        }
        if a.scene_digest != b.scene_digest {
            return differ(
                "scene (digest of its files and overrides)",
                format!("{:016x}", a.scene_digest),
                format!("{:016x}", b.scene_digest),
            );
        }
        if a.sensor != b.sensor {
            return differ("sensor", a.sensor.to_string(), b.sensor.to_string());
        }
        if a.quantity != b.quantity {
            return differ("quantity", format!("{:?}", a.quantity), format!("{:?}", b.quantity));
        }
        if a.sampler != b.sampler {
            return differ("sampler", format!("{:?}", a.sampler), format!("{:?}", b.sampler));
        }
        if a.branches != b.branches {
            return differ("branches", a.branches.to_string(), b.branches.to_string());
        }
        if a.aov_layers != b.aov_layers {
            return differ("AOV layers", a.aov_layers.to_string(), b.aov_layers.to_string());
        }
        if a.allocation != b.allocation {
            let name = |d: u64| match d {
                0 => "uniform".to_string(),
                d => format!("adaptive {d:016x}"),
            };
            return differ("sample allocation", name(a.allocation), name(b.allocation));
        }
        Ok(())
    }

    /// The sums as bytes (module docs): a prefix writes its one film, a later range each pass.
    pub fn to_bytes(&self) -> Vec<u8> {
        let pixels = self.header.width as usize * self.header.height as usize;
        let films = if self.first == 0 { 1 } else { self.passes.len() };
        let per_film = 12 + 8 * pixels * (8 + 3 * self.header.aov_layers as usize);
        let mut out = Vec::with_capacity(128 + films * per_film);
        out.extend_from_slice(MAGIC);
        put_u32(&mut out, FORMAT);
        let v = crate::VERSION.as_bytes();
        put_u32(&mut out, v.len() as u32);
        out.extend_from_slice(v);
        let h = &self.header;
        for x in [h.width, h.height, h.aov_layers, h.spp] {
            put_u32(&mut out, x);
        }
        put_u64(&mut out, h.seed);
        put_u32(&mut out, sampler_code(h.sampler));
        put_u32(&mut out, h.branches);
        put_u32(&mut out, quantity_code(h.quantity));
        put_u32(&mut out, h.sensor);
        put_u64(&mut out, h.scene_digest);
        put_u64(&mut out, h.allocation);
        put_u32(&mut out, self.first);
        put_u32(&mut out, self.end);
        put_u32(&mut out, films as u32);
        let mut put_film = |end: u32, film: &Film| {
            put_u32(&mut out, end);
            put_u64(&mut out, film.dropped());
            let (px, aov) = film.sums();
            for p in px {
                for v in p.wl.iter().chain([&p.w]).chain(&p.wl2).chain([&p.w2]) {
                    put_u64(&mut out, v.to_bits());
                }
            }
            for a in aov {
                for v in a {
                    put_u64(&mut out, v.to_bits());
                }
            }
        };
        if self.first == 0 {
            put_film(self.end, &self.folded);
        } else {
            for (end, film) in &self.passes {
                put_film(*end, film);
            }
        }
        out
    }

    /// Reads [`to_bytes`](Self::to_bytes)' record back. The films get a box filter and
    /// unnamed AOV layers: sums are combined and developed, never splatted into.
    pub fn from_bytes(bytes: &[u8]) -> Result<RenderSums, SumsError> {
        let mut r = Reader { bytes, at: 0 };
        if r.take(MAGIC.len())? != MAGIC {
            return Err(SumsError::Malformed("it does not start with steradian's mark".into()));
        }
        let format = r.u32()?;
        if format != FORMAT {
            return Err(SumsError::Malformed(format!(
                "record format {format}, this steradian reads format {FORMAT}"
            )));
        }
        let n = r.u32()? as usize;
        let version = String::from_utf8_lossy(r.take(n.min(256))?).into_owned();
        if version != crate::VERSION {
            return Err(SumsError::Version(version));
        }
        let (width, height, aov_layers, spp) = (r.u32()?, r.u32()?, r.u32()?, r.u32()?);
        let seed = r.u64()?;
        let sampler = match r.u32()? {
            0 => SamplerKind::Sobol,
            1 => SamplerKind::Independent,
            k => return Err(SumsError::Malformed(format!("unknown sampler code {k}"))),
        };
        let branches = r.u32()?;
        let quantity = match r.u32()? {
            0 => PixelQuantity::Sensor,
            1 => PixelQuantity::SurfaceIrradiance,
            2 => PixelQuantity::SurfaceIlluminance,
            k => return Err(SumsError::Malformed(format!("unknown quantity code {k}"))),
        };
        let (sensor, scene_digest, allocation) = (r.u32()?, r.u64()?, r.u64()?);
        let header = SumsHeader {
            width,
            height,
            aov_layers,
            spp,
            seed,
            sampler,
            branches,
            quantity,
            sensor,
            scene_digest,
            allocation,
        };
        let (first, end, films) = (r.u32()?, r.u32()?, r.u32()?);
        if first > end || end > spp || (first == 0 && films != 1) || (first > 0 && films == 0) {
            return Err(SumsError::Malformed(format!(
                "range {first}..{end} of {spp} spp with {films} films"
            )));
        }
        let layers: Vec<AovLayer> = (0..aov_layers)
            .map(|k| AovLayer { name: format!("aov{k}"), channels: vec!["X", "Y", "Z"] })
            .collect();
        let template = Film::new(width, height, BoxFilter::new().into())
            .map_err(SumsError::Malformed)?
            .with_aov_layers(layers);
        let pixels = width as usize * height as usize;
        let need = films as usize * (12 + 8 * pixels * (8 + 3 * aov_layers as usize));
        if r.remaining() != need {
            return Err(SumsError::Malformed(format!(
                "{} bytes of sums where {need} were expected (truncated?)",
                r.remaining()
            )));
        }
        let mut sums = RenderSums::empty(header, &template, first);
        let mut last = first;
        for _ in 0..films {
            let pass_end = r.u32()?;
            if pass_end <= last || pass_end > end {
                return Err(SumsError::Malformed(format!("pass ending at {pass_end}")));
            }
            let mut film = template.clone();
            let (px, aov, dropped) = film.sums_mut();
            *dropped = r.u64()?;
            for p in px.iter_mut() {
                let mut v = [0f64; 8];
                for x in &mut v {
                    *x = f64::from_bits(r.u64()?);
                }
                *p = PixelAccum {
                    wl: [v[0], v[1], v[2]],
                    w: v[3],
                    wl2: [v[4], v[5], v[6]],
                    w2: v[7],
                };
            }
            for a in aov.iter_mut() {
                for x in a.iter_mut() {
                    *x = f64::from_bits(r.u64()?);
                }
            }
            if first == 0 {
                // a prefix is stored folded: it is the fold itself
                sums.folded = film;
                sums.end = pass_end;
            } else {
                sums.push_pass(pass_end, film);
            }
            last = pass_end;
        }
        if sums.end != end {
            return Err(SumsError::Malformed(format!("passes end at {}, not {end}", sums.end)));
        }
        Ok(sums)
    }

    /// Writes [`to_bytes`](Self::to_bytes) to `path` atomically: to `path.tmp`, flushed to
    /// the disk, then renamed over `path`, so that a process killed at any moment leaves
    /// either the old file or the new one, never a part.
    pub fn save(&self, path: &std::path::Path) -> std::io::Result<()> {
        use std::io::Write;
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        let tmp = std::path::PathBuf::from(tmp);
        {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(&self.to_bytes())?;
            f.sync_all()?;
        }
        std::fs::rename(&tmp, path)
    }

    /// Reads sums that [`save`](Self::save) wrote; the message names the file.
    pub fn load(path: &std::path::Path) -> Result<RenderSums, String> {
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read checkpoint {}: {e}", path.display()))?;
        RenderSums::from_bytes(&bytes).map_err(|e| format!("checkpoint {}: {e}", path.display()))
    }

    /// These sums on `film` (the plan's: its filter and named AOV layers), for a render that
    /// continues them.
    pub(super) fn on_film(mut self, film: &Film) -> RenderSums {
        let mut f = film.clone();
        f.clear();
        fold(&mut f, &self.folded);
        self.folded = f;
        for (_, p) in &mut self.passes {
            let mut g = film.clone();
            g.clear();
            fold(&mut g, p);
            *p = g;
        }
        self
    }
}

const MAGIC: &[u8; 8] = b"STERSUMS";
const FORMAT: u32 = 2;

fn sampler_code(s: SamplerKind) -> u32 {
    match s {
        SamplerKind::Sobol => 0,
        SamplerKind::Independent => 1,
    }
}

fn quantity_code(q: PixelQuantity) -> u32 {
    match q {
        PixelQuantity::Sensor => 0,
        PixelQuantity::SurfaceIrradiance => 1,
        PixelQuantity::SurfaceIlluminance => 2,
    }
}

fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_u64(out: &mut Vec<u8>, v: u64) {
    out.extend_from_slice(&v.to_le_bytes());
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], SumsError> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| SumsError::Malformed("the record is truncated".into()))?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, SumsError> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }

    fn u64(&mut self) -> Result<u64, SumsError> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }

    fn remaining(&self) -> usize {
        self.bytes.len() - self.at
    }
}

/// A 64-bit FNV-1a digest of the contents of `files` (in order, each with its length) and of
/// `extra` strings (overrides): what a checkpoint's [`SumsHeader::scene_digest`] records, so
/// that a scene whose files changed, wherever they lie, is told apart. Not a cryptographic hash.
pub fn digest_inputs(files: &[std::path::PathBuf], extra: &[&str]) -> std::io::Result<u64> {
    let mut h = Fnv1a::default();
    for f in files {
        let bytes = std::fs::read(f)?;
        h.write(&(bytes.len() as u64).to_le_bytes());
        h.write(&bytes);
    }
    for e in extra {
        h.write(&(e.len() as u64).to_le_bytes());
        h.write(e.as_bytes());
    }
    Ok(h.0)
}

struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
}
