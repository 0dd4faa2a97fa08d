//! The guide's project: its one unit described once, with its testbench, its Verilog twin
//! (`docs/rtl/blend.v`) and its bit-accuracy vectors. `verif::cli::main(&project())` is a
//! program with texrtl's command line for it.

use crate::blend::Blend;
use crate::blend_tb::BlendTb;
use hdl::kernel::Signal;
use std::path::Path;
use verif::cosim::{CosimUnit, Twin};
use verif::project::{Project, Unit};
use verif::vectors::{Field, UnitVectors};

/// The unit against its Verilog: the inputs set from raw bits in port order. `with_drive`
/// keeps the closure's own type, so that `bench` inlines it into its cycle loop (`Twin::new`
/// takes it as a function pointer and returns a nameable `Twin<Blend>`).
pub fn twin() -> impl CosimUnit {
    let drive = |d: &mut Blend, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.a, &mut d.b, &mut d.alpha], v);
    };
    let rtl = Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/blend.v");
    Twin::with_drive(Blend::default, drive).sources([rtl])
}

/// Fixed stimuli and the unit's outputs: every weight between two colour pairs, one blend
/// a cycle; each row's `out` is the port's value in its cycle, the blend of two rows before.
pub fn vectors() -> Result<UnitVectors, String> {
    let mut m = twin().model()?;
    let blends = (0..256u64).flat_map(|alpha| [(250, 3, alpha), (3, 250, alpha)]);
    let rows = blends
        .chain([(0, 0, 0); 2])
        .map(|(a, b, alpha)| {
            (
                vec![a, b, alpha],
                vec![m.cycle(false, &[1, a, b, alpha])[1]],
            )
        })
        .collect();
    let fields = |n: &[&str]| n.iter().map(|f| Field::new(*f, 8)).collect();
    Ok(UnitVectors {
        unit: "blend".into(),
        description: "every weight between (250, 3) and (3, 250); out two rows late".into(),
        inputs: fields(&["a", "b", "alpha"]),
        outputs: fields(&["out"]),
        rows,
    })
}

/// The project.
pub fn project() -> Project {
    let unit = Unit::new("blend", "a two-stage alpha blend")
        .testbench(BlendTb)
        .twin(twin())
        .vectors(vectors);
    Project::new("blend", env!("CARGO_PKG_VERSION")).unit(unit)
}
