//! Stage 1 of loading: XML text → the scene tree ([`crate::tree`]), following Mitsuba 3's
//! `src/core/xml.cpp` (the rules are in the crate docs).
//!
//! | file           | holds |
//! |----------------|-------|
//! | `parser.rs`    | the parser proper: documents, `<include>`s, elements, objects; the entry points |
//! | `attrs.rs`     | one element's attributes, and the number/list syntax of attribute values |
//! | `params.rs`    | `$name` parameters: defines and `<default>`s |
//! | `values.rs`    | property elements (`<float>`, `<rgb>`, `<spectrum>`, …) → typed values |
//! | `transform.rs` | the operations inside `<transform>` |
//! | `typed_spectrum.rs` | `<spectrum type="d65">` and the other spectrum plugins → values |
//! | `link.rs`      | ids, `<alias>`es and `<ref>`s: linking the objects read into the shared tree |
//!
//! Imports run one way: `parser` uses every other file here; `params`, `values` and
//! `transform` use `attrs`; `attrs`, `link` and `typed_spectrum` use none of them.

mod attrs;
mod link;
mod params;
mod parser;
mod transform;
mod typed_spectrum;
mod values;

pub use parser::{parse_file, parse_string, parse_string_named};
