//! A project: the units it models, each described once by a [`Unit`], in the order its
//! regression runs and reports them. Every list the framework's commands need (the testbenches
//! of `regress`, the twins of `cosim` and `bench`, the vectors of `vectors` and of the
//! regression's bit-accuracy row, the report's pictures) is read from it.
//!
//! ```
//! use verif::project::{Project, Unit};
//! let project = Project::new("mychip", "0.1.0").unit(Unit::new("alu_7", "the ALU of figure 7"));
//! assert_eq!(project.names(), ["alu_7"]);
//! assert!(project.twins().next().is_none());
//! ```

use crate::cosim::{CosimUnit, Directed};
use crate::vectors::{UnitVectors, VectorsFn};
use crate::{Registry, TbResult, Testbench};
use std::path::{Path, PathBuf};

/// A picture of the report: its file (in the report's folder) and caption.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    /// The file's name in the report's folder.
    pub file: String,
    /// What it shows, in a sentence.
    pub caption: String,
}

/// Writes a unit's pictures into a folder, from the results of the run (those of this unit's
/// testbenches among them); called only when one of its testbenches ran.
pub type PicturesFn = dyn Fn(&Path, &[TbResult]) -> Result<Vec<Picture>, String> + Send + Sync;

/// The directed co-simulation runs of a unit (`cosim --stimulus vectors`).
pub type DirectedFn = dyn Fn() -> Result<Vec<Directed>, String> + Send + Sync;

/// Everything the framework knows about one unit, said once: its name (the module's kind,
/// the waveform scope, the Verilog module, the vectors' file), its testbenches, its Verilog
/// twin, its bit-accuracy vectors and its report pictures. Each part but the name is optional.
pub struct Unit {
    name: &'static str,
    about: &'static str,
    testbenches: Vec<Box<dyn Testbench>>,
    twin: Option<Box<dyn CosimUnit>>,
    directed: Option<Box<DirectedFn>>,
    vectors: Option<Box<VectorsFn>>,
    no_vectors: Option<&'static str>,
    pictures: Option<Box<PicturesFn>>,
}

impl Unit {
    /// A unit named `name`, `about` saying in one line what it is.
    pub fn new(name: &'static str, about: &'static str) -> Unit {
        Unit {
            name,
            about,
            testbenches: Vec::new(),
            twin: None,
            directed: None,
            vectors: None,
            no_vectors: None,
            pictures: None,
        }
    }
    /// A testbench of the unit (regress runs them in the order given).
    pub fn testbench(mut self, tb: impl Testbench + 'static) -> Unit {
        self.testbenches.push(Box::new(tb));
        self
    }
    /// The unit's Verilog twin: co-simulated by `cosim` and `regress`, measured by `bench`.
    /// Its name must be the unit's.
    pub fn twin(mut self, twin: impl CosimUnit + 'static) -> Unit {
        self.twin = Some(Box::new(twin));
        self
    }
    /// Directed co-simulation runs (for example the vectors' transactions), for
    /// `cosim --stimulus vectors`.
    pub fn directed(
        mut self,
        f: impl Fn() -> Result<Vec<Directed>, String> + Send + Sync + 'static,
    ) -> Unit {
        self.directed = Some(Box::new(f));
        self
    }
    /// The unit's bit-accuracy vectors, made by `f` from fixed stimuli.
    pub fn vectors(
        mut self,
        f: impl Fn() -> Result<UnitVectors, String> + Send + Sync + 'static,
    ) -> Unit {
        self.vectors = Some(Box::new(f));
        self
    }
    /// Why the unit keeps no vectors (a project's tests can require every unit with a
    /// testbench to have vectors or a reason).
    pub fn without_vectors(mut self, reason: &'static str) -> Unit {
        self.no_vectors = Some(reason);
        self
    }
    /// The unit's pictures in the report.
    pub fn pictures(
        mut self,
        f: impl Fn(&Path, &[TbResult]) -> Result<Vec<Picture>, String> + Send + Sync + 'static,
    ) -> Unit {
        self.pictures = Some(Box::new(f));
        self
    }

    /// The unit's name.
    pub fn name(&self) -> &'static str {
        self.name
    }
    /// What the unit is, in one line.
    pub fn about(&self) -> &'static str {
        self.about
    }
    /// Its Verilog twin, if it has one.
    pub fn twin_unit(&self) -> Option<&dyn CosimUnit> {
        self.twin.as_deref()
    }
    /// Its directed co-simulation runs, if any.
    pub fn directed_runs(&self) -> Option<&DirectedFn> {
        self.directed.as_deref()
    }
    /// What makes its vectors, if it keeps any.
    pub fn vectors_fn(&self) -> Option<&VectorsFn> {
        self.vectors.as_deref()
    }
    /// Why it keeps no vectors, when its descriptor says.
    pub fn no_vectors_reason(&self) -> Option<&'static str> {
        self.no_vectors
    }
    /// What draws its report pictures, if any.
    pub fn pictures_fn(&self) -> Option<&PicturesFn> {
        self.pictures.as_deref()
    }
    /// The names of the unit's testbenches.
    pub fn testbench_names(&self) -> Vec<&'static str> {
        self.testbenches.iter().map(|t| t.name()).collect()
    }
}

/// The units of a project, in run order, with the project's name (which its messages and
/// summaries carry) and version (shards of different versions do not merge).
pub struct Project {
    name: &'static str,
    version: &'static str,
    units: Vec<UnitEntry>,
    registry: Registry,
    vectors_dir: Option<PathBuf>,
}

/// A unit as the project keeps it: the testbenches moved into the project's registry.
struct UnitEntry {
    unit: Unit,
    testbenches: Vec<&'static str>,
}

impl Project {
    /// A project with no unit yet: `name` is the program's (messages, default output folders,
    /// the report's title), `version` the one its summaries carry.
    pub fn new(name: &'static str, version: &'static str) -> Project {
        Project {
            name,
            version,
            units: Vec::new(),
            registry: Registry::new(),
            vectors_dir: None,
        }
    }

    /// Adds a unit. Panics when its name, a testbench's name or its twin's name is already the
    /// project's, or the twin is named differently from the unit: a project is built by the
    /// program that runs it, and such a mistake is the program's.
    pub fn unit(mut self, mut u: Unit) -> Project {
        assert!(self.get(u.name).is_none(), "unit '{}' added twice", u.name);
        if let Some(t) = &u.twin {
            assert_eq!(
                t.name(),
                u.name,
                "the twin of unit '{}' is named otherwise",
                u.name
            );
        }
        let testbenches = u.testbench_names();
        for tb in std::mem::take(&mut u.testbenches) {
            self.registry.register(tb);
        }
        self.units.push(UnitEntry {
            unit: u,
            testbenches,
        });
        self
    }

    /// Where the kept bit-accuracy vectors are (`regress` checks them there, `--bless`
    /// rewrites them); without it, the vectors are only exported.
    pub fn vectors_dir(mut self, dir: impl Into<PathBuf>) -> Project {
        self.vectors_dir = Some(dir.into());
        self
    }

    /// The project's name.
    pub fn name(&self) -> &'static str {
        self.name
    }
    /// The version its summaries carry.
    pub fn version(&self) -> &'static str {
        self.version
    }
    /// The folder of the kept vectors, if the project keeps them.
    pub fn kept_vectors(&self) -> Option<&Path> {
        self.vectors_dir.as_deref()
    }
    /// The project's testbenches, in run order.
    pub fn registry(&self) -> &Registry {
        &self.registry
    }
    /// The units, in run order.
    pub fn units(&self) -> impl Iterator<Item = &Unit> {
        self.units.iter().map(|e| &e.unit)
    }
    /// The units' names, in run order.
    pub fn names(&self) -> Vec<&'static str> {
        self.units().map(Unit::name).collect()
    }
    /// The unit named `name`.
    pub fn get(&self, name: &str) -> Option<&Unit> {
        self.units().find(|u| u.name == name)
    }
    /// The unit whose testbench `tb` is.
    pub fn unit_of(&self, tb: &str) -> Option<&Unit> {
        self.units
            .iter()
            .find(|e| e.testbenches.contains(&tb))
            .map(|e| &e.unit)
    }
    /// The units' testbench names, unit by unit.
    pub fn testbenches_of(&self, unit: &str) -> &[&'static str] {
        self.units
            .iter()
            .find(|e| e.unit.name == unit)
            .map_or(&[], |e| e.testbenches.as_slice())
    }
    /// The units with a Verilog twin, in order.
    pub fn twins(&self) -> impl Iterator<Item = &dyn CosimUnit> {
        self.units().filter_map(Unit::twin_unit)
    }
    /// The twin named `name`, or a message listing the twins there are (naming `option`).
    pub fn twin(&self, name: &str, option: &str) -> Result<&dyn CosimUnit, String> {
        self.get(name).and_then(Unit::twin_unit).ok_or_else(|| {
            let all: Vec<&str> = self.twins().map(|t| t.name()).collect();
            format!(
                "{option} {}: no Verilog twin (there are: {})",
                waves::output::shorten(name),
                all.join(", ")
            )
        })
    }
    /// The units with vectors, in order.
    pub fn vectors(&self) -> impl Iterator<Item = (&str, &VectorsFn)> {
        self.units()
            .filter_map(|u| u.vectors_fn().map(|f| (u.name, f)))
    }
    /// The vectors of `name`, or a message listing the units that have them (naming `option`).
    pub fn vectors_of(&self, name: &str, option: &str) -> Result<UnitVectors, String> {
        match self.get(name).and_then(Unit::vectors_fn) {
            Some(f) => f(),
            None => {
                let all: Vec<&str> = self.vectors().map(|(n, _)| n).collect();
                Err(format!(
                    "{option} {}: no vectors (there are: {})",
                    waves::output::shorten(name),
                    all.join(", ")
                ))
            }
        }
    }
}
