//! Output reproducers: devices, pipes and symbolic links are written through (a
//! write error is exit 2 naming the option's file), regular files are replaced atomically,
//! and a command that fails on bad input or I/O leaves no new file, waves included.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(name: &str) -> common::TestDir {
    common::dir("out", name)
}

fn texrtl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .expect("runs")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The folder's entries, sorted.
fn names(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Exit 2 with one line containing `needle` and no mention of a temporary file.
fn refused(o: &Output, needle: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(needle), "wanted {needle:?}: {err}");
    assert!(!err.contains(".partial"), "{err}");
}

/// A 4x4 height map and two coordinates in `d`.
fn normals_inputs(d: &Path) -> (PathBuf, PathBuf) {
    let h = d.join("h.pgm");
    let mut pgm = b"P5\n4 4\n255\n".to_vec();
    pgm.extend((0..16u8).map(|k| k * 13));
    std::fs::write(&h, pgm).unwrap();
    let c = d.join("c.csv");
    std::fs::write(&c, "u,v\n1.5,1.5\n2,2.25\n").unwrap();
    (h, c)
}

fn normals(h: &Path, c: &Path, out: &str, extra: &[&str]) -> Output {
    let mut a = vec!["normals", "--height", s(h), "--coords", s(c), "--out", out];
    a.extend_from_slice(extra);
    texrtl(&a)
}

#[cfg(target_os = "linux")]
#[test]
fn devices_are_written_through() {
    use std::os::unix::fs::FileTypeExt;
    let d = dir("devices");
    let (h, c) = normals_inputs(&d);
    let o = normals(&h, &c, "/dev/null", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let null = std::fs::metadata("/dev/null").unwrap();
    assert!(null.file_type().is_char_device(), "/dev/null was replaced");
    refused(&normals(&h, &c, "/dev/full", &[]), "/dev/full");
    // The failed write also takes the waveform written before it.
    let vcd = d.join("w.vcd");
    refused(
        &normals(&h, &c, "/dev/full", &["--vcd", s(&vcd)]),
        "/dev/full",
    );
    assert_eq!(names(&d), ["c.csv", "h.pgm"]);
    let out = d.join("n.csv");
    refused(
        &normals(&h, &c, s(&out), &["--vcd", "/dev/full"]),
        "/dev/full",
    );
    assert!(!Path::new("/dev/full.gtkw").exists());
    assert_eq!(names(&d), ["c.csv", "h.pgm"]);
    // A VCD to /dev/null: no view file beside a device.
    let o = normals(&h, &c, s(&out), &["--vcd", "/dev/null"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!Path::new("/dev/null.gtkw").exists());
}

#[cfg(unix)]
#[test]
fn symlinks_are_written_through_and_stay_links() {
    let d = dir("symlink");
    let (h, c) = normals_inputs(&d);
    let target = d.join("real.csv");
    std::fs::write(&target, "old").unwrap();
    let link = d.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let o = normals(&h, &c, s(&link), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
    let text = std::fs::read_to_string(&target).unwrap();
    assert!(text.starts_with("u,v,nx,ny,nz\n"), "{text}");
    assert_eq!(names(&d), ["c.csv", "h.pgm", "link.csv", "real.csv"]);
}

#[cfg(unix)]
#[test]
fn a_pipe_is_written_through() {
    let d = dir("fifo");
    let (h, c) = normals_inputs(&d);
    let fifo = d.join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    let o = normals(&h, &c, s(&fifo), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = reader.join().unwrap();
    assert_eq!(text.lines().count(), 3, "{text}");
    let meta = std::fs::symlink_metadata(&fifo).unwrap();
    assert!(!meta.is_file(), "the pipe was replaced by a file");
}

#[test]
fn a_missing_folder_is_exit_2_naming_the_option_and_nothing_is_left() {
    let d = dir("nodir");
    let (h, c) = normals_inputs(&d);
    let vcd = d.join("no").join("w.vcd");
    let out = d.join("n.csv");
    refused(&normals(&h, &c, s(&out), &["--vcd", s(&vcd)]), "--vcd");
    let bad = d.join("no").join("n.csv");
    let here = d.join("w.vcd");
    refused(&normals(&h, &c, s(&bad), &["--vcd", s(&here)]), "--out");
    assert_eq!(names(&d), ["c.csv", "h.pgm"]);
    let t = d.join("trace.csv");
    std::fs::write(&t, "addr\n0\n1\n").unwrap();
    refused(
        &texrtl(&["dram", "--trace", s(&t), "--vcd", s(&vcd)]),
        "--vcd",
    );
    assert_eq!(names(&d), ["c.csv", "h.pgm", "trace.csv"]);
    // A folder where the waveform should go: named, with its option.
    let folder = d.join("dram.vcd");
    std::fs::create_dir(&folder).unwrap();
    let o = texrtl(&["dram", "--trace", s(&t), "--vcd", s(&folder)]);
    refused(&o, &format!("--vcd {}: is a directory", folder.display()));
}

fn pgm(d: &Path, name: &str) -> PathBuf {
    let p = d.join(name);
    let mut v = b"P5\n8 8\n255\n".to_vec();
    v.extend((0..64u8).map(|k| k.wrapping_mul(37)));
    std::fs::write(&p, v).unwrap();
    p
}

#[test]
fn mipmap_refuses_a_folder_for_stats_and_an_input_inside_its_output() {
    let d = dir("mipmap");
    let f = pgm(&d, "f.pgm");
    let out = d.join("out");
    std::fs::create_dir_all(out.join("stats.json")).unwrap();
    let vcd = d.join("m.vcd");
    let o = texrtl(&["mipmap", "--in", s(&f), "--out", s(&out), "--vcd", s(&vcd)]);
    refused(&o, "stats.json");
    assert_eq!(names(&out), ["stats.json"]);
    assert_eq!(names(&d), ["f.pgm", "out"]);
    // A frame named level0.pgm in the output folder would be overwritten by the first level.
    let inside = pgm(&d, "level0.pgm");
    let o = texrtl(&["mipmap", "--in", s(&inside), "--out", s(&d)]);
    refused(&o, "--in");
    assert_eq!(names(&d), ["f.pgm", "level0.pgm", "out"]);
}

#[test]
fn mipmap_on_bad_io_removes_the_folder_it_made() {
    let d = dir("mipmap-io");
    let f = pgm(&d, "f.pgm");
    let out = d.join("made");
    // A VCD into a folder that does not exist: refused before the output folder is made.
    let vcd = d.join("no").join("m.vcd");
    let o = texrtl(&["mipmap", "--in", s(&f), "--out", s(&out), "--vcd", s(&vcd)]);
    refused(&o, "--vcd");
    assert_eq!(names(&d), ["f.pgm"]);
}

#[test]
fn merge_refuses_to_overwrite_a_shard() {
    let d = dir("merge");
    let a = d.join("a.json");
    std::fs::write(&a, "{}").unwrap();
    let o = texrtl(&["merge", "--out", s(&a), s(&a)]);
    refused(&o, "the same file as the input");
    assert_eq!(std::fs::read_to_string(&a).unwrap(), "{}");
}
