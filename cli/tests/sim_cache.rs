//! The co-simulation cache, as a user meets it: a second run of an unchanged unit builds and
//! simulates nothing and says the same, byte for byte; another seed simulates again on the
//! kept build; changed Verilog misses the cache and its difference is found; `off` builds
//! every time; an edited `include file misses it too. Icarus only (the cheaper build); without
//! it the test says so and passes, unless `TEXRTL_REQUIRE_COSIM=1`.

mod common;
use common::dir;
use std::path::Path;
use std::process::{Command, Output};

fn cosim(cache: &str, out: &Path, extra: &[&str]) -> Output {
    cosim_on("icarus", cache, out, extra)
}

fn cosim_on(sim: &str, cache: &str, out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(["cosim", "--unit", "blend_adjust_153", "--sim", sim])
        .args(["--count", "3000"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .env("TEXRTL_SIM_CACHE", cache)
        .output()
        .unwrap()
}

/// The text of blend-factor adjust unit 153's twin, for a test to change.
fn twin_text() -> String {
    let twin = Path::new(env!("CARGO_MANIFEST_DIR")).join("../rtl/bump/blend_adjust_153.v");
    std::fs::read_to_string(twin).unwrap()
}

fn entries(root: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(root)
        .map(|rd| {
            rd.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn an_unchanged_cosimulation_is_reused_and_a_changed_one_is_not() {
    if !common::simulator("iverilog", "-V") {
        return;
    }
    let d = dir("sim-cache", "reuse");
    let root = d.join("cache");
    let c = root.to_str().unwrap();
    let first = cosim(c, &d.join("a"), &[]);
    assert_eq!(
        first.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let kept = entries(&root);
    assert_eq!(kept.len(), 2, "the build and the run: {kept:?}");
    let out_a = std::fs::read(d.join("a/rtl_out.hex")).unwrap();
    // Again, into another folder: nothing new kept, the same outputs, the same report.
    let second = cosim(c, &d.join("b"), &[]);
    assert_eq!(entries(&root), kept);
    assert_eq!(std::fs::read(d.join("b/rtl_out.hex")).unwrap(), out_a);
    assert!(!d.join("b/sim.vvp").exists(), "nothing was built");
    let said = |o: &Output, dir: &str| String::from_utf8_lossy(&o.stdout).replace(dir, "DIR");
    assert_eq!(said(&second, "/b/"), said(&first, "/a/"));
    // Another seed: the kept build, a new run.
    let seeded = cosim(c, &d.join("c"), &["--seed", "7"]);
    assert_eq!(seeded.status.code(), Some(0));
    assert_eq!(entries(&root).len(), 3);
    assert!(!d.join("c/sim.vvp").exists(), "the build is reused");
    // Changed Verilog: a miss, built and simulated, and its bug found.
    let good = twin_text();
    let mine = d.join("mine.v");
    std::fs::write(&mine, good.replace("{1'b1, u_in};", "{1'b0, u_in};")).unwrap();
    let bad = cosim(c, &d.join("d"), &["--rtl", mine.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(1), "the bug is found");
    assert!(d.join("d/sim.vvp").exists(), "built anew");
    assert_eq!(entries(&root).len(), 5);
    // Off: built every time, nothing kept.
    let off = cosim("off", &d.join("e"), &[]);
    assert_eq!(off.status.code(), Some(0));
    assert!(d.join("e/sim.vvp").exists());
    assert_eq!(entries(&root).len(), 5);
    std::fs::remove_dir_all(&d).unwrap();
}

/// Verilog that includes a header: found beside the source, or in an `--incdir` folder; a
/// `--define` chooses it; editing the header (not the source) builds anew and finds the bug.
#[test]
fn an_included_header_is_found_and_its_edit_is_not_a_stale_build() {
    if !common::simulator("iverilog", "-V") {
        return;
    }
    let d = dir("sim-cache", "include");
    let c = d.join("cache");
    let c = c.to_str().unwrap();
    let good = twin_text();
    let uses = good.replace("{1'b1, u_in};", "{`TOP_BIT, u_in};");
    assert_ne!(uses, good);
    let header = |dir: &Path, bit: &str| {
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(
            dir.join("top_bit.vh"),
            format!("`define TOP_BIT 1'b{bit}\n"),
        )
        .unwrap();
    };
    // Beside the source.
    let beside = d.join("beside.v");
    std::fs::write(&beside, format!("`include \"top_bit.vh\"\n{uses}")).unwrap();
    header(&d, "1");
    let rtl = ["--rtl", beside.to_str().unwrap()];
    assert_eq!(cosim(c, &d.join("a"), &rtl).status.code(), Some(0));
    header(&d, "0");
    assert_eq!(
        cosim(c, &d.join("b"), &rtl).status.code(),
        Some(1),
        "the edit is seen"
    );
    // In a folder of its own, included only under a define.
    let inc = d.join("include");
    header(&inc, "1");
    std::fs::create_dir_all(d.join("src")).unwrap();
    let chosen = d.join("src/chosen.v");
    let text = format!(
        "`ifdef SHARED\n`include \"top_bit.vh\"\n`else\n`define TOP_BIT 1'b0\n`endif\n{uses}"
    );
    std::fs::write(&chosen, text).unwrap();
    let rtl = ["--rtl", chosen.to_str().unwrap()];
    assert_eq!(
        cosim(c, &d.join("c"), &rtl).status.code(),
        Some(1),
        "without SHARED"
    );
    let defined = [&rtl[..], &["--define", "SHARED"]].concat();
    let o = cosim(c, &d.join("e"), &defined);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && err.contains("top_bit.vh"),
        "{err}"
    );
    let found = [&defined[..], &["--incdir", inc.to_str().unwrap()]].concat();
    assert_eq!(cosim(c, &d.join("f"), &found).status.code(), Some(0));
    std::fs::remove_dir_all(&d).unwrap();
}

/// Verilog whose module is named otherwise than the unit's top: refused naming the top the
/// testbench looked for, then instantiated by `--top`.
#[test]
fn a_module_of_another_name_is_the_top_given() {
    if !common::simulator("iverilog", "-V") {
        return;
    }
    let d = dir("sim-cache", "top");
    let c = d.join("cache");
    let good = twin_text();
    let renamed = good.replace("module blend_adjust_153", "module adjust_v2");
    assert_ne!(renamed, good);
    let mine = d.join("adjust_v2.v");
    std::fs::write(&mine, renamed).unwrap();
    let rtl = ["--rtl", mine.to_str().unwrap()];
    let o = cosim(c.to_str().unwrap(), &d.join("a"), &rtl);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && err.contains("instantiates blend_adjust_153"),
        "{err}"
    );
    let top = [&rtl[..], &["--top", "adjust_v2"]].concat();
    assert_eq!(
        cosim(c.to_str().unwrap(), &d.join("b"), &top).status.code(),
        Some(0)
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// A file list as an RTL team keeps one: its sources, `+incdir+` and `+define+` (here in a
/// nested list) reach the build, `-F` reading paths from the list's folder and `-f` from
/// the current one; a macro edited in the nested list alone builds anew and finds the bug; an
/// entry texrtl does not read is refused, naming the list and the line, before anything is
/// written.
#[test]
fn a_file_list_gives_the_sources_folders_and_macros() {
    if !common::simulator("iverilog", "-V") {
        return;
    }
    let d = dir("sim-cache", "filelist");
    let c = d.join("cache");
    let c = c.to_str().unwrap();
    let uses = twin_text().replace("{1'b1, u_in};", "{`TOP_BIT, u_in};");
    let text = format!(
        "`ifdef SHARED\n`include \"top_bit.vh\"\n`else\n`define TOP_BIT 1'b0\n`endif\n{uses}"
    );
    let (rtl, inc) = (d.join("proj/rtl"), d.join("proj/include"));
    std::fs::create_dir_all(&rtl).unwrap();
    std::fs::create_dir_all(&inc).unwrap();
    std::fs::write(rtl.join("adjust.v"), text).unwrap();
    std::fs::write(inc.join("top_bit.vh"), "`define TOP_BIT 1'b1\n").unwrap();
    let files = rtl.join("files.f");
    std::fs::write(
        &files,
        "// blend adjust, our RTL\n+incdir+../include\n-F defines.f\nadjust.v\n",
    )
    .unwrap();
    let defines = |m: &str| std::fs::write(rtl.join("defines.f"), format!("# macros\n{m}\n"));
    defines("+define+SHARED+UNUSED=3").unwrap();
    let list = ["-F", files.to_str().unwrap()];
    let o = cosim(c, &d.join("a"), &list);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    defines("+define+UNUSED=3").unwrap();
    assert_eq!(
        cosim(c, &d.join("b"), &list).status.code(),
        Some(1),
        "without SHARED, the bug"
    );
    // As -f, `../include` is taken from the current folder, where there is none.
    let o = cosim(c, &d.join("c"), &["-f", files.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2)
            && err.contains("-f/--filelist ")
            && err.contains("files.f:2: include folder"),
        "{err}"
    );
    assert!(!d.join("c").exists(), "refused before anything is written");
    defines("+define+SHARED\n-Wall").unwrap();
    let o = cosim(c, &d.join("e"), &list);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("defines.f:3: -Wall: not read"), "{err}");
    assert!(!d.join("e").exists());
}

/// A file list's module library, as an RTL team keeps one: a module found by its name in a
/// library folder (`-y`, `.sv` among the default extensions), another in a library file
/// (`-v`) beside a module that would not build and is never instantiated; both simulators
/// agree throughout; an edit of the library module alone builds anew and finds the bug; a
/// module under an extension the list does not name is not found, and is under `+libext+`;
/// beside the source it is found with no library at all; a missing folder is refused, naming
/// the list and the line, before anything is written.
#[test]
fn a_file_lists_library_gives_the_modules_the_sources_do_not_define() {
    let sims = common::simulators();
    let d = dir("sim-cache", "library");
    let c = d.join("cache");
    let c = c.to_str().unwrap();
    let good = twin_text();
    let uses = good
        .replace(
            "wire [FRAC_BITS:0] u0_c = bypass ? {u_in, 1'b0} : {1'b1, u_in};",
            "wire [FRAC_BITS:0] u0_c;\n    half_up #(.F(FRAC_BITS)) hu (.bypass(bypass), .x(u_in), .y(u0_c));",
        )
        .replace(
            "wire [FRAC_BITS:0] u1_c = bypass ? {u_in, 1'b0} : {1'b0, u_in};",
            "wire [FRAC_BITS:0] u1_c;\n    half_down #(.F(FRAC_BITS)) hd (.bypass(bypass), .x(u_in), .y(u1_c));",
        );
    assert_eq!(uses.matches("half_").count(), 2);
    let half = |name: &str, top: &str| {
        format!(
            "module {name} #(parameter integer F = 8) (input wire bypass, input wire [F-1:0] x, \
             output wire [F:0] y);\n    assign y = bypass ? {{x, 1'b0}} : {{{top}, x}};\nendmodule\n"
        )
    };
    let p = d.join("proj");
    std::fs::create_dir_all(p.join("lib")).unwrap();
    std::fs::write(p.join("adjust.v"), uses).unwrap();
    std::fs::write(p.join("lib/half_up.sv"), half("half_up", "1'b1")).unwrap();
    let cells = format!(
        "{}module never_used;\n    nowhere n ();\nendmodule\n",
        half("half_down", "1'b0")
    );
    std::fs::write(p.join("cells.v"), cells).unwrap();
    let files = p.join("files.f");
    let list = |extra: &str| {
        std::fs::write(&files, format!("adjust.v\n-y lib\n-v cells.v\n{extra}")).unwrap();
    };
    list("");
    let args = ["-F", files.to_str().unwrap()];
    for (k, sim) in sims.iter().enumerate() {
        let o = cosim_on(sim, c, &d.join(format!("a{k}")), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{sim}: {err}");
    }
    std::fs::write(p.join("lib/half_up.sv"), half("half_up", "1'b0")).unwrap();
    for (k, sim) in sims.iter().enumerate() {
        let o = cosim_on(sim, c, &d.join(format!("b{k}")), &args);
        assert_eq!(
            o.status.code(),
            Some(1),
            "{sim}: the library's bug is found"
        );
    }
    // Under an extension the list must name; then beside the source, found without a list.
    std::fs::remove_file(p.join("lib/half_up.sv")).unwrap();
    std::fs::write(p.join("lib/half_up.vlib"), half("half_up", "1'b1")).unwrap();
    for (k, sim) in sims.iter().enumerate() {
        let o = cosim_on(sim, c, &d.join(format!("c{k}")), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            o.status.code() == Some(2) && err.contains("half_up"),
            "{sim}: {err}"
        );
    }
    list("+libext+.vlib\n");
    for (k, sim) in sims.iter().enumerate() {
        let o = cosim_on(sim, c, &d.join(format!("e{k}")), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{sim}: {err}");
    }
    std::fs::rename(p.join("lib/half_up.vlib"), p.join("half_up.v")).unwrap();
    list("");
    for (k, sim) in sims.iter().enumerate() {
        let o = cosim_on(sim, c, &d.join(format!("f{k}")), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{sim}: {err}");
    }
    list("-y gone\n");
    let o = cosim(c, &d.join("g"), &args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && err.contains("files.f:4: library folder"),
        "{err}"
    );
    assert!(!d.join("g").exists(), "refused before anything is written");
    std::fs::remove_dir_all(&d).unwrap();
}

/// The RTL's coverage: Verilator's line and toggle coverage of the user's Verilog under the
/// model's stimulus, summed up in a line naming the blocks never reached (here a branch the
/// random stimulus cannot take), with Verilator's data, an lcov file and the sources
/// annotated; refused with Icarus before anything is written.
#[test]
fn the_rtls_coverage_names_what_the_stimulus_never_reached() {
    if !common::simulator("verilator", "-V") {
        return;
    }
    let d = dir("sim-cache", "coverage");
    let c = d.join("cache");
    let c = c.to_str().unwrap();
    let dead = "    reg dead_r;\n    always @(posedge clk)\n        if (u_in == 8'hA5 && v_in == 8'h5A && bypass && rst)\n            dead_r <= 1'b1;\n";
    let text = twin_text().replace("    generate\n", &format!("{dead}    generate\n"));
    let line = text
        .lines()
        .position(|l| l.contains("dead_r <= 1'b1"))
        .unwrap()
        + 1;
    let mine = d.join("mine.v");
    std::fs::write(&mine, text).unwrap();
    let rtl = ["--rtl", mine.to_str().unwrap(), "--rtl-coverage"];
    let o = cosim_on("verilator", c, &d.join("a"), &rtl);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(0), "{err}");
    let said = format!("{out}{err}");
    let summary = said
        .lines()
        .find(|l| l.starts_with("the RTL's coverage (Verilator): blocks "));
    let summary = summary.expect(&said);
    let named = [line - 1, line].map(|l| format!("never reached: mine.v:{l}"));
    assert!(
        named.iter().any(|n| summary.contains(n.as_str())),
        "{summary}"
    );
    let info = std::fs::read_to_string(d.join("a/coverage.info")).unwrap();
    assert!(info.contains("SF:") && info.contains("mine.v"), "{info}");
    let annotated = std::fs::read_to_string(d.join("a/coverage_annotated/mine.v")).unwrap();
    assert!(annotated.contains("%000000"), "{annotated}");
    let o = cosim_on("icarus", c, &d.join("b"), &rtl);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && err.contains("--rtl-coverage: "),
        "{err}"
    );
    assert!(!d.join("b").exists());
    std::fs::remove_dir_all(&d).unwrap();
}
