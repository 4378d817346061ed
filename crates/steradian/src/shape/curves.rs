//! Mitsuba 3's curve files, read by `linearcurve`: one control point per line, four numbers
//! `x y z radius` (m); an empty line starts a new curve; a curve has at least two control
//! points. As Mitsuba reads them: lines of at most 1024 characters, numbers parsed from the
//! start of the line (anything after the fourth number is ignored), positions and radii finite.
//! steradian also refuses a negative radius (Mitsuba passes it to its ray tracer as it is).

use std::path::Path;

use glam::Vec4;

use super::ShapeError;

/// The longest line Mitsuba's reader takes, characters.
const MAX_LINE: usize = 1024;

/// The curves of a file: each a list of control points (x, y, z, radius), before any
/// transform.
pub fn read_curves(path: &Path) -> Result<Vec<Vec<Vec4>>, ShapeError> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let fail = |what: String| ShapeError(format!("\"{name}\": {what}"));
    let text = std::fs::read(path).map_err(|e| fail(format!("cannot read the file ({e})")))?;
    let text = String::from_utf8(text).map_err(|_| fail("the file is not text".into()))?;
    parse_curves(&text).map_err(fail)
}

/// The curves of a curve file's text (see the module docs); errors name the line.
pub fn parse_curves(text: &str) -> Result<Vec<Vec<Vec4>>, String> {
    let mut curves: Vec<Vec<Vec4>> = Vec::new();
    let mut current: Vec<Vec4> = Vec::new();
    // the line of the current curve's first control point
    let mut start = 0;
    let mut finish = |current: &mut Vec<Vec4>, start: usize| -> Result<(), String> {
        match current.len() {
            0 => Ok(()),
            1 => Err(format!(
                "line {start}: a curve needs at least two control points, this one has one"
            )),
            _ => {
                curves.push(std::mem::take(current));
                Ok(())
            }
        }
    };
    for (i, line) in text.split('\n').enumerate() {
        let number = i + 1;
        if line.len() >= MAX_LINE {
            return Err(format!("line {number} is longer than {MAX_LINE} characters"));
        }
        let words: Vec<&str> = line.split_ascii_whitespace().take(4).collect();
        if words.is_empty() {
            finish(&mut current, start)?;
            continue;
        }
        if current.is_empty() {
            start = number;
        }
        if words.len() < 4 {
            return Err(format!("line {number}: expected four numbers (x y z radius)"));
        }
        let mut v = [0f32; 4];
        for (x, word) in v.iter_mut().zip(&words) {
            *x = word.parse().map_err(|_| {
                format!("line {number}: \"{word}\" is not a number (x y z radius per line)")
            })?;
        }
        if !v[..3].iter().all(|x| x.is_finite()) {
            return Err(format!("line {number}: the position is not finite"));
        }
        if !(v[3].is_finite() && v[3] >= 0.0) {
            return Err(format!(
                "line {number}: the radius must be finite and non-negative, got {}",
                v[3]
            ));
        }
        current.push(Vec4::from_array(v));
    }
    finish(&mut current, start)?;
    if curves.is_empty() {
        return Err("no control points (an empty curve file)".into());
    }
    Ok(curves)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_are_split_at_empty_lines() {
        let c =
            parse_curves("0 0 0 0.1\n1 0 0 0.2\n\n  \n0 1 0 1 extra\n0 2 0 1\n0 3 0 2\n").unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(c[0], vec![Vec4::new(0.0, 0.0, 0.0, 0.1), Vec4::new(1.0, 0.0, 0.0, 0.2)]);
        assert_eq!(c[1].len(), 3);
        assert_eq!(c[1][2], Vec4::new(0.0, 3.0, 0.0, 2.0));
    }

    #[test]
    fn bad_files_are_errors_naming_the_line() {
        for (text, needle) in [
            ("0 0 0 1\n0 1 0 1\n\n1 1 1 1\n", "line 4: a curve needs at least two"),
            ("0 0 0 1\n1 1 x 1\n", "line 2: \"x\" is not a number"),
            ("0 0 0\n1 1 1 1\n", "line 1: expected four numbers"),
            ("0 0 0 -1\n1 1 1 1\n", "line 1: the radius must be"),
            ("0 0 inf 1\n1 1 1 1\n", "line 1: the position is not finite"),
            ("\n\n", "empty curve file"),
        ] {
            let e = parse_curves(text).unwrap_err();
            assert!(e.contains(needle), "{text:?}: {e}");
        }
    }
}
