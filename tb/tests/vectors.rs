//! Bit-accuracy regression: the bit-exact outputs of every unit for fixed stimuli must equal
//! those kept in golden/vectors/. After a deliberate change, `texrtl vectors --bless` rewrites
//! them and prints what changed.

use tb::vectors::vectors_dir;
use verif::project::Project;
use verif::vectors::{bless, check, hash, UnitVectors};

fn project() -> Project {
    tb::project::project()
}

fn unit_vectors(u: &str) -> Result<UnitVectors, String> {
    project().vectors_of(u, "--unit")
}

#[test]
fn outputs_match_the_kept_vectors() {
    let p = project();
    let d = check(&vectors_dir(), p.vectors()).unwrap();
    assert!(
        d.is_empty(),
        "bit-accuracy vectors changed (run `texrtl regress --bless` if deliberate):\n{}",
        d.join("\n")
    );
}

#[test]
fn a_single_flipped_bit_changes_the_hash() {
    for (u, make) in project().vectors() {
        let v = make().unwrap();
        let h = hash(&v);
        for (r, c, bit) in [(0, 0, 0), (v.rows.len() - 1, v.rows[0].1.len() - 1, 3)] {
            let mut w = v.clone();
            w.rows[r].1[c] ^= 1 << bit;
            assert_ne!(
                hash(&w),
                h,
                "{u}: flipping output {c} bit {bit} of row {r} went unnoticed"
            );
        }
    }
}

#[test]
fn readmemh_export() {
    let d = std::env::temp_dir().join(format!("texrtl-vec-{}", std::process::id()));
    let v = unit_vectors("blend_adjust_153").unwrap();
    let files = v.write_readmemh(&d).unwrap();
    let text = std::fs::read_to_string(&files[1]).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with("//")).collect();
    assert_eq!(lines.len(), 512);
    // u = 1, adjust mode: U0 = 0x101, U1 = 0x001 in 9 bits each, packed u0 u1 v0 v1.
    let (u0, u1) = (v.rows[1].1[0], v.rows[1].1[1]);
    assert_eq!((u0, u1), (0x101, 0x001));
    let word = u128::from_str_radix(lines[1], 16).unwrap();
    assert_eq!(word >> 27, 0x101);
    assert_eq!((word >> 18) & 0x1ff, 0x001);
    assert!(text
        .lines()
        .nth(1)
        .unwrap()
        .contains("u0[8:0] u1[8:0] v0[8:0] v1[8:0]"));
    assert!(unit_vectors("nope").is_err());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bless_writes_and_reports_changes() {
    let d = std::env::temp_dir().join(format!("texrtl-bless-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    let proj = project();
    let first = bless(&d, proj.vectors()).unwrap();
    assert_eq!(first.len(), proj.vectors().count(), "all new: {first:?}");
    assert!(check(&d, proj.vectors()).unwrap().is_empty());
    assert!(
        bless(&d, proj.vectors()).unwrap().is_empty(),
        "nothing changed"
    );
    // Tamper with a kept hash: check reports it, bless restores it and says what changed.
    let p = d.join("mipmap_gen_816.json");
    let text = std::fs::read_to_string(&p).unwrap();
    let h = hash(&unit_vectors("mipmap_gen_816").unwrap());
    std::fs::write(&p, text.replace(&h, "0000000000000000")).unwrap();
    let diffs = check(&d, proj.vectors()).unwrap();
    assert_eq!(diffs.len(), 1);
    assert!(
        diffs[0].starts_with("mipmap_gen_816: hash 0000000000000000 ->"),
        "{}",
        diffs[0]
    );
    let changed = bless(&d, proj.vectors()).unwrap();
    assert_eq!(changed.len(), 1);
    assert!(check(&d, proj.vectors()).unwrap().is_empty());
    // A row far past the readable ones changed: named by its index and its field.
    let rows = d.join("texture_unit_602.rows");
    let text = std::fs::read_to_string(&rows).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let k = lines.len() - 3;
    let v = unit_vectors("texture_unit_602").unwrap();
    let (head, out) = lines[k].split_once(" -> ").unwrap();
    let (head, out) = (head.to_string(), out.to_string());
    let first_out = out.split('_').next().unwrap().to_string();
    let flipped = format!(
        "{:0w$x}",
        u64::from_str_radix(&first_out, 16).unwrap() ^ 1,
        w = first_out.len()
    );
    lines[k] = format!("{head} -> {flipped}{}", &out[first_out.len()..]);
    std::fs::write(&rows, lines.join("\n") + "\n").unwrap();
    let diffs = check(&d, proj.vectors()).unwrap();
    assert_eq!(diffs.len(), 1, "{diffs:?}");
    let field = &v.outputs[0].name;
    let want = format!("1 rows changed, the first row {k}: {field} {flipped} -> {first_out}");
    assert!(diffs[0].contains(&want), "{} lacks {want}", diffs[0]);
    let changed = bless(&d, proj.vectors()).unwrap();
    assert!(changed[0].contains(&want), "{changed:?}");
    assert!(check(&d, proj.vectors()).unwrap().is_empty());
    let _ = std::fs::remove_dir_all(&d);
}
