//! sat_acc modelled with texrtl: one descriptor gives the command line its testbench, its Verilog
//! twin (`rtl/sat_acc.v`) and its bit-accuracy vectors (`vectors/`). `cargo run` is the regression.
pub mod tb;
pub mod unit;

use hdl::kernel::Signal;
use std::path::Path;
use verif::cosim::{CosimUnit, Twin};
use verif::project::{Project, Unit};
use verif::vectors::{Field, UnitVectors};

/// The unit against its Verilog: inputs set from raw bits in port order (valid_in, x); the
/// drive keeps its own type (`with_drive`), so `bench` inlines it.
pub fn twin() -> impl CosimUnit {
    let drive = |d: &mut unit::SatAcc, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.x], v);
    };
    Twin::with_drive(unit::SatAcc::default, drive)
        .sources([Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/sat_acc.v")])
}

/// Fixed stimuli: every input value, then 64 steps up into the upper rail, 128 down past the lower.
fn vectors() -> Result<UnitVectors, String> {
    let mut m = twin().model()?;
    let xs = (0..256u64).chain([0x7f; 64]).chain([0x80; 128]);
    let rows = xs.map(|x| (vec![x], vec![m.cycle(false, &[1, x])[1]])).collect();
    let (inputs, outputs) = (vec![Field::new("x", 8)], vec![Field::new("acc", 10)]);
    let description = "the accumulator after each x, valid every cycle, from reset".into();
    Ok(UnitVectors { unit: "sat_acc".into(), description, inputs, outputs, rows })
}

/// The project: its one unit, described once.
pub fn project() -> Project {
    let unit = Unit::new("sat_acc", "a saturating accumulator, acc <= sat(acc + x)")
        .testbench(tb::SatAccTb)
        .twin(twin())
        .vectors(vectors);
    let kept = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors");
    Project::new("sat_acc", env!("CARGO_PKG_VERSION")).vectors_dir(kept).unit(unit)
}
