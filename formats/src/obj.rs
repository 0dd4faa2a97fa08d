//! Wavefront OBJ meshes as `texrtl tangents` reads them: `v x y z`, `vt u v`, `vn x y z`,
//! `f` with `p/t` or `p/t/n` corners (1-based, negative counts back), `s N` / `s off`
//! smoothing groups; other statements (`o`, `g`, `usemtl`, `mtllib`, `l`, `#`) are skipped.
//! Every face needs texture coordinates (tangents come from them). Errors name the file, the
//! line and the problem.

/// A face corner: indices (0-based) of its position, texture coordinate and normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Corner {
    pub p: usize,
    pub t: usize,
    pub n: Option<usize>,
}

/// A face: its corners (3 or more), its smoothing group (0: off) and its line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Face {
    pub corners: Vec<Corner>,
    pub smoothing: u32,
    pub line: usize,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f64; 3]>,
    pub uvs: Vec<[f64; 2]>,
    pub normals: Vec<[f64; 3]>,
    pub faces: Vec<Face>,
}

/// Reads `path`.
pub fn read(path: &std::path::Path) -> Result<Mesh, String> {
    let text = crate::read_text_bounded(path, crate::MAX_INPUT_BYTES)?;
    parse(&path.display().to_string(), &text)
}

fn numbers<const N: usize>(words: &[&str], what: &str) -> Result<[f64; N], String> {
    if words.len() < N {
        return Err(format!("{what} needs {N} numbers"));
    }
    let mut out = [0.0; N];
    for (o, w) in out.iter_mut().zip(words) {
        *o = w
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && x.abs() < 1e9)
            .ok_or_else(|| format!("{what}: '{}' is not a number under 1e9", crate::shorten(w)))?;
    }
    Ok(out)
}

/// An OBJ index (1-based, or negative from the end) into a list of `len`.
fn index(w: &str, len: usize, what: &str) -> Result<usize, String> {
    let i: i64 = w
        .parse()
        .map_err(|_| format!("{what} index '{}' is not an integer", crate::shorten(w)))?;
    let k = if i > 0 { i - 1 } else { len as i64 + i };
    if i == 0 || k < 0 || k >= len as i64 {
        return Err(format!("{what} index {i}: {len} defined so far"));
    }
    Ok(k as usize)
}

fn corner(w: &str, m: &Mesh) -> Result<Corner, String> {
    let parts: Vec<&str> = w.split('/').collect();
    if parts.len() > 3 {
        return Err(format!(
            "corner '{}' has {} indices: at most three (v/vt/vn)",
            crate::shorten(w),
            parts.len()
        ));
    }
    let t = parts.get(1).copied().filter(|s| !s.is_empty());
    let Some(t) = t else {
        return Err(format!(
            "corner '{}' has no texture coordinate (tangents need UVs)",
            crate::shorten(w)
        ));
    };
    Ok(Corner {
        p: index(parts[0], m.positions.len(), "position")?,
        t: index(t, m.uvs.len(), "texture coordinate")?,
        n: match parts.get(2).filter(|s| !s.is_empty()) {
            Some(n) => Some(index(n, m.normals.len(), "normal")?),
            None => None,
        },
    })
}

/// Parses `text`; `file` names it in messages.
pub fn parse(file: &str, text: &str) -> Result<Mesh, String> {
    let mut m = Mesh::default();
    let mut smoothing = 0;
    for (i, line) in text.lines().enumerate() {
        let at = |e: String| format!("{file}:{}: {e}", i + 1);
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some((&head, rest)) = words.split_first() else {
            continue;
        };
        match head {
            "v" => m.positions.push(numbers::<3>(rest, "v").map_err(at)?),
            "vt" => m.uvs.push(numbers::<2>(rest, "vt").map_err(at)?),
            "vn" => m.normals.push(numbers::<3>(rest, "vn").map_err(at)?),
            "s" => {
                smoothing = match rest.first() {
                    Some(&"off") | Some(&"0") => 0,
                    Some(w) => w.parse().map_err(|_| {
                        at(format!("s '{}': a group number or off", crate::shorten(w)))
                    })?,
                    None => return Err(at("s needs a group".into())),
                }
            }
            "f" => {
                if rest.len() < 3 {
                    return Err(at(format!("a face needs 3 corners, {} given", rest.len())));
                }
                let corners = rest
                    .iter()
                    .map(|w| corner(w, &m))
                    .collect::<Result<_, _>>()
                    .map_err(at)?;
                m.faces.push(Face {
                    corners,
                    smoothing,
                    line: i + 1,
                });
            }
            _ => {}
        }
    }
    if m.faces.is_empty() {
        return Err(format!("{file}: no faces"));
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quad_with_groups_and_negative_indices() {
        let m = parse(
            "q.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\ns 2\nf 1/1/1 2/2/1 3/3/1 -1/-1\n",
        )
        .unwrap();
        assert_eq!(m.faces.len(), 1);
        let f = &m.faces[0];
        assert_eq!(f.smoothing, 2);
        assert_eq!(
            f.corners[3],
            Corner {
                p: 3,
                t: 3,
                n: None
            }
        );
        assert_eq!(f.corners[0].n, Some(0));
        for (text, needle) in [
            ("v 0 0\n", ":1: v needs 3 numbers"),
            ("v 0 0 nan\n", "not a number"),
            ("v 0 0 0\nf 1 1 1\n", "no texture coordinate"),
            (
                "v 0 0 0\nvt 0 0\nf 1/1 1/1 2/1\n",
                "position index 2: 1 defined",
            ),
            ("v 0 0 0\nvt 0 0\nf 1/1 1/1\n", "3 corners"),
            // Junk after a corner's third index (it was read as v/vt/vn and the rest ignored).
            (
                "v 0 0 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 1/1/1 1/1/x\n",
                "corner '1/1/1/1' has 4 indices",
            ),
            (
                "v 0 0 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 1/1/1 1/1/x\n",
                "normal index",
            ),
            ("# nothing\n", "no faces"),
        ] {
            let e = parse("x.obj", text).unwrap_err();
            assert!(e.contains(needle), "{e}");
        }
    }
}
