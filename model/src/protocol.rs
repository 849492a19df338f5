//! One descriptor per protocol: every name the tree knows a protocol by
//! (its scenario table, core, emulator and monitor, Verilog wrappers,
//! closed loops, cocotb tests, timing diagram), declared once, in the
//! protocol's own module (`model/src/<module>/descriptor.rs`), and listed
//! once, in [`PROTOCOLS`]. `tbgen`, `cosim`, `cosim-params`, the tests and
//! (through `tbgen protocols --json`) the scripts derive their lists from it.
//!
//! A protocol has one name stem, its scenario table (`ssi`, `sar`): the
//! folders `scenarios/<stem>/` and `tbgen/src/<stem>/`, the bench scenario
//! `scenarios/bench/<stem>_bench.toml` and `tbgen decode|timing <stem>` are
//! named by it, and every other name is the stem or begins with `<stem>_`,
//! except the ones in [`Protocol::historical`], each with the reason it
//! stays (a name in a vector file, a module path users import).
//!
//! ```
//! let sar = model::protocol::by_stem("sar").unwrap();
//! assert_eq!(sar.core, "sar_async_host");
//! assert!(model::protocol::PROTOCOLS.iter().any(|p| p.core == "ssi_master"));
//! ```

use serde::Serialize;

/// Everything a protocol is called, outside its own model code.
#[derive(Debug, Serialize)]
pub struct Protocol {
    /// The name stem: the scenario file's table (`[sar]`), `scenarios/<stem>/`,
    /// `tbgen/src/<stem>/`, `scenarios/bench/<stem>_bench.toml`, `tbgen decode <stem>`.
    pub stem: &'static str,
    /// What the protocol is, for people (`SAR58K24 asynchronous serial`).
    pub title: &'static str,
    /// The model's module, `model::<module>` (`model/src/<module>/`).
    pub module: &'static str,
    /// The Verilog core the vectors drive: `hdl/rtl/<core>.v`,
    /// `hdl/tb/<core>/`, `vectors/<core>/`.
    pub core: &'static str,
    /// The encoder emulator of `cosim` (and its monitor), if there is one.
    pub emulator: Option<Emulator>,
    /// The closed-loop testbenches of our own cores against that emulator.
    pub closed_loops: &'static [ClosedLoop],
    /// The WaveDrom diagram of the protocol's main transaction
    /// (`scripts/timing_diagrams.py`), if it has one.
    pub diagram: Option<Diagram>,
    /// The names that do not follow the stem, and why each stays.
    pub historical: &'static [Historical],
    /// The protocol's rule book (`model::<module>::rules::RULES`): every
    /// timing limit its seed states for a master ([`crate::rules`]).
    #[serde(skip)]
    pub rules: &'static [&'static crate::rules::Rule],
}

/// A `cosim` emulator and the monitor beside it.
#[derive(Debug, Serialize)]
pub struct Emulator {
    /// `cosim::open`'s kind; `<kind>_monitor` is the monitor's. The Verilog
    /// wrapper reads its configuration from the plusarg `+<kind>_emu_config`.
    pub kind: &'static str,
    /// Other names `cosim::open` takes for the emulator (`<alias>_monitor`
    /// for the monitor), with what each reaches.
    pub aliases: &'static [&'static str],
    /// The Verilog wrapper `hdl/emu/<module>.v`.
    pub module: &'static str,
    /// The Verilog monitor `hdl/emu/<monitor_module>.v`.
    pub monitor_module: &'static str,
}

/// A closed-loop testbench: one of our cores against the protocol's
/// emulator, `hdl/tb_cosim/<name>/tb_cosim_<name>.v` with its
/// `configs/*.toml` (`scripts/cosim.sh <name>`).
#[derive(Debug, Serialize)]
pub struct ClosedLoop {
    /// The testbench's folder and `scripts/cosim.sh`'s core argument.
    pub name: &'static str,
    /// The Verilog core it drives (`hdl/rtl/<top>.v`).
    pub top: &'static str,
    /// `make test`'s Icarus configuration (`configs/<quick>.toml`,
    /// `scripts/cosim_regress.sh --quick`): the fewest Icarus seconds per
    /// transaction, so that Icarus spends its time on transactions rather
    /// than on long cables, slow clocks and idle gaps. Measured on 60
    /// transactions of each configuration, start-up included, the 2-core
    /// machine loaded about 3, after the cores' counters moved out of their
    /// state machines' `always @*` blocks; the figures are beside each.
    pub quick: &'static str,
    /// Transactions of `make bench`'s closed-loop row in Icarus (Verilator
    /// runs ten times as many): about 100 000 cycles (`scripts/bench.sh`).
    pub bench_transactions: u32,
    /// The cocotb test `hdl/cocotb/test_<cocotb>.py`, on the scenario file
    /// `hdl/cocotb/configs/<cocotb>.toml`, if the loop has one.
    pub cocotb: Option<&'static str>,
}

/// A WaveDrom diagram, `docs/wavedrom/<file>.json` and `.svg`.
#[derive(Debug, Serialize)]
pub struct Diagram {
    /// The file stem.
    pub file: &'static str,
    /// The built-in scenario whose first transaction it shows.
    pub scenario: &'static str,
    /// Its caption: what it shows and the seed document and section.
    pub title: &'static str,
}

/// A name that does not follow the stem, and why it stays.
#[derive(Debug, Serialize)]
pub struct Historical {
    /// The name.
    pub name: &'static str,
    /// Why it is not renamed.
    pub why: &'static str,
}

/// The protocol list, the one place a protocol is registered: `stem =>
/// Variant(module)`, in listing order (`tbgen list`, `tbgen protocols`).
/// Hands the list to the macro `$callback` of the caller's crate: here it
/// makes [`PROTOCOLS`], in `tbgen` the scenario file's tables and the
/// `Setup` enum. Adding a protocol is one line here, beside its modules.
#[macro_export]
macro_rules! with_protocols {
    ($callback:ident) => {
        $callback! {
            ssi => Ssi(ssi),
            uart => Uart(uart),
            tformat => Tformat(tformat),
            biss => Biss(biss),
            endat => Endat(endat),
            esl => Esl(esl),
            sar => Sar(sar58k24),
            modbus => Modbus(modbus),
            can => Can(can),
            canopen => Canopen(canopen),
        }
    };
}

macro_rules! descriptors {
    ($($stem:ident => $variant:ident($module:ident)),+ $(,)?) => {
        /// Every protocol's descriptor, in listing order ([`with_protocols`]).
        pub static PROTOCOLS: &[&Protocol] = &[$(&crate::$module::descriptor::PROTOCOL),+];
    };
}
crate::with_protocols!(descriptors);

/// The protocol whose stem (scenario table) is `stem`.
pub fn by_stem(stem: &str) -> Option<&'static Protocol> {
    PROTOCOLS.iter().copied().find(|p| p.stem == stem)
}

/// The protocol whose core is `core`.
pub fn by_core(core: &str) -> Option<&'static Protocol> {
    PROTOCOLS.iter().copied().find(|p| p.core == core)
}

/// Every closed loop, with its protocol, in listing order.
pub fn closed_loops() -> impl Iterator<Item = (&'static Protocol, &'static ClosedLoop)> {
    PROTOCOLS
        .iter()
        .flat_map(|p| p.closed_loops.iter().map(move |l| (*p, l)))
}

/// The closed loop named `name` (`hdl/tb_cosim/<name>/`), with its protocol.
pub fn closed_loop(name: &str) -> Option<(&'static Protocol, &'static ClosedLoop)> {
    closed_loops().find(|(_, l)| l.name == name)
}

impl Protocol {
    /// The monitor's kind (`cosim::open`): `<emulator kind>_monitor`.
    pub fn monitor_kind(&self) -> Option<String> {
        self.emulator
            .as_ref()
            .map(|e| format!("{}_monitor", e.kind))
    }

    /// Every name of the protocol outside its model code, for the stem
    /// check: each is the stem, begins with `<stem>_`, or is historical.
    pub fn names(&self) -> Vec<&'static str> {
        let mut names = vec![self.module, self.core];
        if let Some(e) = &self.emulator {
            names.extend([e.kind, e.module, e.monitor_module]);
            names.extend(e.aliases);
        }
        for l in self.closed_loops {
            names.push(l.name);
            names.extend(l.cocotb);
        }
        names.extend(self.diagram.as_ref().map(|d| d.file));
        names
    }
}
