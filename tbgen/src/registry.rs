//! The protocol registry: what `tbgen` knows of each protocol.
//!
//! The list itself is the model's (`model::with_protocols!`, beside the
//! descriptors in `model::protocol`), one line per protocol:
//!
//! ```text
//! ssi => Ssi(ssi),
//! ```
//!
//! `ssi` is the protocol's stem: the scenario file's table (and the folders
//! `tbgen/src/ssi/`, `scenarios/ssi/`), `Ssi` the variant of
//! [`crate::Setup`], and `ssi` the model's module, whose `BenchConfig`
//! implements [`model::Setup`] (in `model/src/ssi/`) and [`Protocol`] (in
//! `tbgen/src/ssi/`). From that line the macro [`protocols!`] makes the
//! module `tbgen::ssi`, the scenario file's optional table, the `Setup`
//! variant and its dispatch, and the entry in
//! [`PROTOCOLS`](crate::PROTOCOLS) that `tbgen decode`, `tbgen timing`,
//! `tbgen protocols` and the tests read.

use clap::{ArgMatches, Command};

use crate::{Error, Result};

/// What `tbgen` knows of a protocol beyond its model: implemented in the
/// protocol's folder `tbgen/src/<table>/` on the model's `BenchConfig`.
/// Everything has a default, so a new protocol starts with
/// `impl Protocol for BenchConfig { const TRANSACTION_SIGNALS: ... }`.
pub trait Protocol:
    model::Setup
    + serde::Serialize
    + serde::de::DeserializeOwned
    + schemars::JsonSchema
    + Send
    + 'static
{
    /// The output pulses that end a transaction, the output holding its
    /// result, and the transcript field that must equal it (the whole-flow
    /// test reads the VCD with them).
    const TRANSACTION_SIGNALS: TransactionSignals;

    /// The sigrok decoder that reads this protocol's line in the tests
    /// (`spi`, `uart`), if any; [`Protocol::sigrok`] gives the details.
    const SIGROK_DECODER: Option<&'static str> = None;

    /// The least (scenarios, values) the sigrok test must have compared
    /// for this protocol, so that a check that silently compares nothing fails.
    const SIGROK_MINIMUM: (usize, usize) = (0, 0);

    /// The waveform's scalars that feed the protocol's monitor's pins, as
    /// dotted paths below `top` (`line.ma_master`, a line signal;
    /// `endat_master.o_endat_clk`, a port of the core), in the monitor's order (its
    /// wrapper's `MON_PIN_NAMES`, `hdl/emu/<kind>_monitor.v`): what
    /// [`crate::rule_verdict`] holds to the rule book, on the model's line
    /// (`tbgen timing`) or a capture's (`tbgen decode`). Empty: the
    /// protocol has no monitor.
    const MONITOR_PINS: &'static [&'static str] = &[];

    /// `tbgen decode <table>`: the decoder's command line, if it has one.
    fn decode_command() -> Option<Command> {
        None
    }

    /// Runs `tbgen decode <table>` on its parsed command line; returns the
    /// JSON to print.
    fn decode(_args: &ArgMatches) -> Result<String> {
        Err(Error::Decode(format!(
            "decode {}: this protocol has no decoder yet",
            Self::TABLE
        )))
    }

    /// `tbgen timing <table>`: the budget's command line, if it has one.
    fn timing_command() -> Option<Command> {
        None
    }

    /// Runs `tbgen timing <table>` on its parsed command line; returns the
    /// report to print.
    fn timing(_args: &ArgMatches) -> Result<String> {
        Err(Error::Decode(format!(
            "timing {}: this protocol has no cycle budget yet",
            Self::TABLE
        )))
    }

    /// The Verilog parameters of closed loop `name` (one of the
    /// descriptor's, `hdl/tb_cosim/<name>/`) from the protocol's `table` of
    /// scenario file `origin` (without the emulator's `emulator`, `checks`
    /// and `random`): by default the core's, as `tbgen gen` writes them.
    fn closed_loop(
        name: &str,
        table: toml::Table,
        origin: &str,
    ) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        Ok(crate::closed_loop::LoopParameters {
            core: crate::closed_loop::core::<Self>(table, origin, &[])?,
            harness: Vec::new(),
        })
    }

    /// The names of the values of enumerated signals of the waveform's
    /// `decoded` scope (the state register), as the RTL names them:
    /// `(signal, [(value, NAME)])`. `tbgen gen` writes a GTKWave translate
    /// filter per signal so the waveform shows `IDLE`, not `0`.
    fn wave_names() -> WaveNames {
        Vec::new()
    }

    /// What an independent decoder (sigrok-cli) must read in the waveform of
    /// a run of this configuration whose transcript is `transcript`; `None`
    /// where there is nothing to check.
    fn sigrok(&self, _transcript: &serde_json::Value) -> Option<SigrokCheck> {
        None
    }
}

/// The state names of a waveform's enumerated signals: `(signal, [(value,
/// NAME)])`, as [`Protocol::wave_names`] gives them.
pub type WaveNames = Vec<(&'static str, Vec<(u64, String)>)>;

/// `(value, NAME)` of each of `variants` of a model enum: its discriminant
/// and its Rust name upper-cased, as the RTL spells its states (`NoAck` ->
/// `NOACK`, `hdl/rtl/biss_master.v`).
pub fn enum_names<E: std::fmt::Debug + Copy>(
    variants: &[E],
    code: fn(E) -> u64,
) -> Vec<(u64, String)> {
    variants
        .iter()
        .map(|&v| (code(v), format!("{v:?}").to_uppercase()))
        .collect()
}

/// The output pulses that end a transaction, the output holding its result,
/// and the transcript field that must equal it.
pub type TransactionSignals = (&'static [&'static str], &'static str, &'static str);

/// A sigrok-cli run on the scalars of a generated VCD, one sample per
/// system clock, and what it must print.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SigrokCheck {
    /// The `-P` option: decoder, channels and options
    /// (`uart:rx=line_at_host:baudrate=2500000`).
    pub decoder: String,
    /// The `-A` option: the annotation row printed (`uart=rx-data`).
    pub annotation: &'static str,
    /// The values the decoder must print, in order; `None` where the model
    /// flagged the value as faulty (it must be there, its value is not compared).
    pub expected: Vec<Option<u128>>,
}

impl SigrokCheck {
    /// The value of one annotation (the text after the prefix): a bare hex
    /// number (`spi`, `uart`), or a labelled one as the `can` decoder prints
    /// them: `Identifier: 677 (0x2a5)` and `Data byte 0: 0x00` (hex),
    /// `Data length code: 4` (decimal), `ACK slot: ACK` / `NACK` (1 / 0).
    pub fn value(text: &str) -> Option<u128> {
        let text = text.trim();
        if let Ok(v) = u128::from_str_radix(text, 16) {
            return Some(v);
        }
        let value = text.rsplit(": ").next()?.trim();
        if let Some(hex) = value.rsplit("(0x").next().filter(|_| value.contains("(0x")) {
            return u128::from_str_radix(hex.trim_end_matches(')'), 16).ok();
        }
        if let Some(hex) = value.strip_prefix("0x") {
            return u128::from_str_radix(hex, 16).ok();
        }
        match value {
            "ACK" => Some(1),
            "NACK" => Some(0),
            _ => value.parse().ok(),
        }
    }

    /// The prefix of the decoder's annotation lines (`uart-1: `).
    pub fn prefix(&self) -> String {
        format!("{}-1: ", self.decoder.split(':').next().unwrap_or(""))
    }
}

/// One registered protocol, as the generic code sees it.
pub struct Entry {
    /// The protocol's descriptor: every name the tree knows it by.
    pub protocol: &'static model::protocol::Protocol,
    /// The scenario file's table, the folder names and the `decode`/`timing` subcommand.
    pub table: &'static str,
    /// The Verilog core (`hdl/rtl/<core>.v`, `hdl/tb/<core>/`, `vectors/<core>/`).
    pub core: &'static str,
    /// See [`Protocol::TRANSACTION_SIGNALS`].
    pub transaction_signals: TransactionSignals,
    /// See [`Protocol::SIGROK_DECODER`].
    pub sigrok_decoder: Option<&'static str>,
    /// See [`Protocol::SIGROK_MINIMUM`].
    pub sigrok_minimum: (usize, usize),
    /// See [`Protocol::MONITOR_PINS`].
    pub monitor_pins: &'static [&'static str],
    /// See [`Protocol::decode_command`].
    pub decode_command: fn() -> Option<Command>,
    /// See [`Protocol::decode`].
    pub decode: fn(&ArgMatches) -> Result<String>,
    /// See [`Protocol::timing_command`].
    pub timing_command: fn() -> Option<Command>,
    /// See [`Protocol::timing`].
    pub timing: fn(&ArgMatches) -> Result<String>,
    /// See [`Protocol::wave_names`].
    pub wave_names: fn() -> WaveNames,
    /// See [`Protocol::closed_loop`].
    pub closed_loop: fn(
        &str,
        toml::Table,
        &str,
    ) -> std::result::Result<crate::closed_loop::LoopParameters, String>,
    /// The schema of the protocol's table, derived from its configuration
    /// types (fields, doc comments, defaults, limits): `tbgen fields` reads it.
    pub schema: fn() -> schemars::Schema,
}

impl Entry {
    /// The entry of protocol `P`.
    pub const fn of<P: Protocol>() -> Entry {
        Entry {
            protocol: P::PROTOCOL,
            table: P::TABLE,
            core: P::CORE,
            transaction_signals: P::TRANSACTION_SIGNALS,
            sigrok_decoder: P::SIGROK_DECODER,
            sigrok_minimum: P::SIGROK_MINIMUM,
            monitor_pins: P::MONITOR_PINS,
            decode_command: decode_command_of::<P>,
            decode: decode_of::<P>,
            timing_command: P::timing_command,
            timing: P::timing,
            wave_names: P::wave_names,
            closed_loop: P::closed_loop,
            schema: || schemars::SchemaGenerator::default().into_root_schema_for::<P>(),
        }
    }
}

/// Protocol `P`'s decode command with what every decoder shares: `--map`,
/// which names a logic analyser's channel for each line.
fn decode_command_of<P: Protocol>() -> Option<Command> {
    P::decode_command().map(crate::capture::lines::with_map_option)
}

/// Protocol `P`'s decoder, with the `--map` of `args` in force while it
/// reads its capture.
fn decode_of<P: Protocol>(args: &ArgMatches) -> Result<String> {
    crate::capture::lines::scoped(args, || P::decode(args))
}

/// The registered protocol whose table is `table`.
pub fn by_table(table: &str) -> Option<&'static Entry> {
    crate::PROTOCOLS.iter().find(|e| e.table == table)
}

/// The registered protocol whose core is `core`.
pub fn by_core(core: &str) -> Option<&'static Entry> {
    crate::PROTOCOLS.iter().find(|e| e.core == core)
}

/// Something done with a scenario's set-up whatever its protocol: the
/// generic code in `generate` and `main` is written once against
/// [`model::Setup`] and reached through [`crate::Setup::accept`].
pub trait Visitor {
    /// What the visit returns.
    type Output;
    /// Does the work for one protocol's configuration.
    fn visit<S: Protocol>(self, setup: &S) -> Self::Output;
}

/// `tbgen decode <protocol> ...` or `tbgen timing <protocol> ...`: which
/// protocol, and its own command line, parsed by its own `clap` parser.
#[derive(Debug, Clone)]
pub struct ToolCall {
    /// The protocol's table.
    pub protocol: String,
    /// Its arguments.
    pub args: ArgMatches,
}

impl ToolCall {
    fn from_matches(m: &ArgMatches) -> std::result::Result<ToolCall, clap::Error> {
        let (name, sub) = m
            .subcommand()
            .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::MissingSubcommand))?;
        Ok(ToolCall {
            protocol: name.to_string(),
            args: sub.clone(),
        })
    }
}

/// Generates the `clap` glue of a per-protocol subcommand family from the registry.
macro_rules! tool_family {
    ($name:ident, $command:ident, $run:ident, $doc:literal) => {
        tool_family!($name, $command, $run, $doc, |_, cmd| cmd, |_, _| Ok(()));
    };
    ($name:ident, $command:ident, $run:ident, $doc:literal, $augment:expr, $after:expr) => {
        #[doc = $doc]
        #[derive(Debug, Clone)]
        pub struct $name(pub ToolCall);

        impl $name {
            /// Runs the protocol's tool and returns what it prints.
            pub fn run(&self) -> Result<String> {
                let entry =
                    by_table(&self.0.protocol).expect("clap only accepts registered protocols");
                let out = (entry.$run)(&self.0.args)?;
                let after: fn(&Entry, &ArgMatches) -> Result<()> = $after;
                after(entry, &self.0.args)?;
                Ok(out)
            }
        }

        impl clap::FromArgMatches for $name {
            fn from_arg_matches(m: &ArgMatches) -> std::result::Result<Self, clap::Error> {
                ToolCall::from_matches(m).map($name)
            }
            fn update_from_arg_matches(
                &mut self,
                m: &ArgMatches,
            ) -> std::result::Result<(), clap::Error> {
                *self = Self::from_arg_matches(m)?;
                Ok(())
            }
        }

        impl clap::Subcommand for $name {
            fn augment_subcommands(cmd: Command) -> Command {
                let augment: fn(&Entry, Command) -> Command = $augment;
                cmd.subcommands(
                    crate::PROTOCOLS
                        .iter()
                        .filter_map(|e| (e.$command)().map(|c| augment(e, c))),
                )
            }
            fn augment_subcommands_for_update(cmd: Command) -> Command {
                Self::augment_subcommands(cmd)
            }
            fn has_subcommand(name: &str) -> bool {
                crate::PROTOCOLS
                    .iter()
                    .any(|e| e.table == name && (e.$command)().is_some())
            }
        }
    };
}

tool_family!(
    Decode,
    decode_command,
    decode,
    "`tbgen decode <protocol>`: one decoder per protocol that has one; the rule verdict of the captured master pins on stderr.",
    crate::rule_verdict::with_capture_options,
    |e, args| {
        if let Some(v) = crate::rule_verdict::of_capture(e, args)? {
            eprint!("{v}");
        }
        Ok(())
    }
);

/// `tbgen decode <protocol>`'s command line of `e`, with the rule
/// verdict's options: what `tbgen check` parses a VCD's decoder options with.
pub fn decode_command(e: &Entry) -> Option<Command> {
    (e.decode_command)().map(|c| crate::rule_verdict::with_capture_options(e, c))
}
tool_family!(
    Timing,
    timing_command,
    timing,
    "`tbgen timing <protocol>`: one cycle budget per protocol that has one."
);

/// One line per registered protocol, for `tbgen protocols`: stem, core,
/// emulator, closed loops, whether it has a decoder and a budget, its
/// sigrok decoder.
pub fn table() -> String {
    let mut out = String::new();
    for e in crate::PROTOCOLS {
        let yes = |b: bool| if b { "yes" } else { "no" };
        let p = e.protocol;
        let loops: Vec<&str> = p.closed_loops.iter().map(|l| l.name).collect();
        out += &format!(
            "{:<10} {:<14} emulator={:<9} loops={:<29} decode={:<3} timing={:<3} sigrok={}\n",
            e.table,
            e.core,
            p.emulator.as_ref().map_or("none", |m| m.kind),
            if loops.is_empty() {
                "none".to_string()
            } else {
                loops.join(",")
            },
            yes((e.decode_command)().is_some()),
            yes((e.timing_command)().is_some()),
            e.sigrok_decoder.unwrap_or("none")
        );
    }
    out
}

/// `tbgen protocols --json`: every descriptor (`model::protocol::Protocol`)
/// with what `tbgen` adds (`decode`, `timing`: whether `tbgen decode|timing
/// <stem>` exists; `sigrok`: the sigrok decoder or null), one object per
/// protocol in registry order. The scripts read their lists from it.
pub fn json() -> String {
    let all: Vec<serde_json::Value> = crate::PROTOCOLS
        .iter()
        .map(|e| {
            let mut v = serde_json::to_value(e.protocol).expect("a descriptor is plain data");
            let o = v.as_object_mut().expect("a descriptor is a struct");
            o.insert("decode".into(), (e.decode_command)().is_some().into());
            o.insert("timing".into(), (e.timing_command)().is_some().into());
            o.insert("sigrok".into(), e.sigrok_decoder.into());
            v
        })
        .collect();
    serde_json::to_string_pretty(&all).expect("JSON of plain data")
}

/// Makes the protocol list: modules, `Setup`, the scenario file's tables and
/// [`PROTOCOLS`](crate::PROTOCOLS). Invoked once, in `lib.rs`, on the
/// model's list.
macro_rules! protocols {
    ($($table:ident => $variant:ident($module:ident)),+ $(,)?) => {
        $crate::registry::protocols!(@ $($table => $variant(model::$module::BenchConfig)),+);
    };
    (@ $($table:ident => $variant:ident($config:ty)),+) => {
        $(pub mod $table;)+

        /// The set-up a scenario describes, one variant per registered protocol.
        #[derive(Debug, Clone, PartialEq)]
        pub enum Setup {
            $(
                #[doc = concat!("A `[", stringify!($table), "]` scenario.")]
                $variant($config),
            )+
        }

        impl Setup {
            /// Hands the protocol's configuration to `visitor`.
            pub fn accept<V: $crate::registry::Visitor>(&self, visitor: V) -> V::Output {
                match self {
                    $(Setup::$variant(cfg) => visitor.visit(cfg),)+
                }
            }

            /// The configuration, if it is one of protocol `P`.
            pub fn get<P: $crate::registry::Protocol>(&self) -> Option<&P> {
                match self {
                    $(Setup::$variant(cfg) => (cfg as &dyn std::any::Any).downcast_ref::<P>(),)+
                }
            }

            /// What sigrok must read in the waveform of this set-up's run.
            pub fn sigrok(&self, transcript: &serde_json::Value) -> Option<$crate::registry::SigrokCheck> {
                match self {
                    $(Setup::$variant(cfg) => $crate::registry::Protocol::sigrok(cfg, transcript),)+
                }
            }
        }

        /// A scenario file as written: its name, description and protocol tables.
        #[derive(Debug, Clone, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub(crate) struct ScenarioFile {
            pub(crate) name: String,
            #[serde(default)]
            pub(crate) description: String,
            $(pub(crate) $table: Option<$config>,)+
        }

        impl ScenarioFile {
            /// The set-ups of every protocol table present.
            pub(crate) fn setups(&self) -> Vec<Setup> {
                let mut setups = Vec::new();
                $(setups.extend(self.$table.clone().map(Setup::$variant));)+
                setups
            }
        }

        /// Every registered protocol, in registry order (the order of
        /// `tbgen list` and `tbgen protocols`).
        pub static PROTOCOLS: &[$crate::registry::Entry] = &[$($crate::registry::Entry::of::<$config>()),+];

        #[cfg(test)]
        mod registry_tests {
            #[test]
            fn each_registry_name_is_the_models_table() {
                $(assert_eq!(stringify!($table), <$config as model::Setup>::TABLE);)+
                let stems: Vec<&str> = model::protocol::PROTOCOLS.iter().map(|p| p.stem).collect();
                assert_eq!(stems, [$(stringify!($table)),+]);
            }
        }
    };
}
pub(crate) use protocols;

/// A Data ID as written on the command line of `tbgen timing`: decimal or
/// 0x-prefixed hex (T-format and ESL).
pub fn parse_data_id(text: &str) -> std::result::Result<u8, String> {
    let value = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u8::from_str_radix(hex, 16),
        None => text.parse::<u8>(),
    };
    value
        .ok()
        .filter(|v| *v <= 0xF)
        .ok_or_else(|| format!("`{text}`: give a Data ID from 0 to 15 (e.g. 3 or 0xD)"))
}

/// The command line of a protocol's tool, parsed by its own parser.
pub fn parse_args<A: clap::FromArgMatches>(args: &ArgMatches) -> Result<A> {
    A::from_arg_matches(args).map_err(|e| Error::Decode(e.to_string()))
}

/// The built-in scenario or scenario file `arg` for `tool` (`timing esl`),
/// which must be one of protocol `P` (`kind`: "an ESL"): the scenario and
/// its configuration.
pub fn scenario_of<P: Protocol>(
    arg: &str,
    tool: &str,
    kind: &str,
) -> Result<(crate::scenario::Scenario, P)> {
    let s = crate::builtin::resolve(arg)?;
    match s.setup.get::<P>() {
        Some(cfg) => {
            let cfg = cfg.clone();
            Ok((s, cfg))
        }
        None => Err(Error::Decode(format!(
            "{tool}: scenario `{}` is not {kind} scenario",
            s.name
        ))),
    }
}

/// A model error from `tool` (`timing tformat`) run on scenario `s`: one
/// about a field the tool's command line sets (`options`: model field and
/// option, `("data_id", "--data-id")`) is blamed on the option, the rest on
/// the scenario file.
pub fn tool_error(
    tool: &str,
    s: &crate::scenario::Scenario,
    options: &[(&str, &str)],
    e: model::ConfigError,
) -> Error {
    let model::ConfigError::Invalid {
        field,
        problem,
        fix,
    } = &e;
    match options.iter().find(|(f, _)| f == field) {
        Some((_, option)) => Error::Decode(format!("{tool}: option {option}: {problem}; {fix}")),
        None => s.value_error(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sigrok_values_bare_and_labelled() {
        assert_eq!(SigrokCheck::value("3f"), Some(0x3f));
        assert_eq!(SigrokCheck::value("Identifier: 677 (0x2a5)"), Some(0x2a5));
        assert_eq!(SigrokCheck::value("Data byte 0: 0x00"), Some(0));
        assert_eq!(SigrokCheck::value("Data length code: 4"), Some(4));
        assert_eq!(SigrokCheck::value("ACK slot: NACK"), Some(0));
        assert_eq!(SigrokCheck::value("CRC-15 sequence: 0x3194"), Some(0x3194));
        assert_eq!(SigrokCheck::value("Start of frame"), None);
    }

    #[test]
    fn an_error_about_a_command_line_option_blames_the_option_not_the_file() {
        let s = crate::builtin::find("tformat_readout_all_ids").unwrap();
        let e = model::ConfigError::invalid("data_id", "0x5 is not in Table 1", "give 0, 1");
        let msg = tool_error("timing tformat", &s, &[("data_id", "--data-id")], e).to_string();
        assert_eq!(
            msg,
            "timing tformat: option --data-id: 0x5 is not in Table 1; give 0, 1"
        );
        let e = model::ConfigError::invalid("baud", "x", "y");
        assert!(
            tool_error("timing tformat", &s, &[("data_id", "--data-id")], e)
                .to_string()
                .starts_with("scenarios/tformat/readout_all_ids.toml:")
        );
    }

    #[test]
    fn each_protocols_subcommands_are_named_after_its_table() {
        // `Decode::run` finds the protocol by the subcommand's name: a
        // decoder or budget named otherwise than its table could not be run.
        for e in crate::PROTOCOLS {
            for cmd in [(e.decode_command)(), (e.timing_command)()]
                .into_iter()
                .flatten()
            {
                assert_eq!(
                    cmd.get_name(),
                    e.table,
                    "{}: a subcommand named `{}`",
                    e.table,
                    cmd.get_name()
                );
            }
        }
    }

    #[test]
    fn the_command_line_reaches_each_protocols_own_parser_and_refuses_others() {
        use clap::{FromArgMatches, Subcommand};
        let cli = Decode::augment_subcommands(Command::new("decode").subcommand_required(true));
        let m = cli
            .clone()
            .try_get_matches_from(["decode", "biss", "x.vcd", "--bits", "12,26"])
            .unwrap();
        let call = Decode::from_arg_matches(&m).unwrap();
        assert_eq!(call.0.protocol, "biss");
        assert_eq!(
            call.0
                .args
                .get_many::<u32>("bits")
                .unwrap()
                .copied()
                .collect::<Vec<_>>(),
            vec![12, 26]
        );
        // An option of another protocol's decoder is refused by this one's parser.
        assert!(cli
            .clone()
            .try_get_matches_from(["decode", "biss", "x.vcd", "--pos-bits", "13"])
            .is_err());
        // A protocol without a decoder is not a subcommand.
        assert!(
            !Decode::has_subcommand("uart")
                && cli
                    .try_get_matches_from(["decode", "uart", "x.vcd"])
                    .is_err()
        );
        assert!(Timing::has_subcommand("endat") && !Timing::has_subcommand("uart"));
    }

    #[test]
    fn the_protocol_table_has_one_line_per_registered_protocol() {
        let t = table();
        assert_eq!(t.lines().count(), crate::PROTOCOLS.len());
        for (line, e) in t.lines().zip(crate::PROTOCOLS) {
            assert!(line.starts_with(e.table) && line.contains(e.core), "{line}");
        }
        assert!(
            t.lines()
                .any(|l| l.starts_with("ssi ") && l.ends_with("sigrok=spi")),
            "{t}"
        );
    }

    #[test]
    fn every_state_name_is_the_rtl_state_of_that_value() {
        // The names come from the model's enum; the RTL must call the state
        // of that value the same (`IDLE = 3'd0,`).
        let mut named = 0;
        for e in crate::PROTOCOLS {
            // The core's own file, then the cores it instantiates (a
            // CANopen layout names its can_controller's states too).
            let dir = format!("{}/../hdl/rtl", env!("CARGO_MANIFEST_DIR"));
            let mut rtl = std::fs::read_to_string(format!("{dir}/{}.v", e.core)).unwrap();
            for f in std::fs::read_dir(&dir).unwrap() {
                let path = f.unwrap().path();
                let module = path.file_stem().unwrap().to_string_lossy().to_string();
                let instantiated = rtl.lines().any(|l| l.starts_with(&format!("{module} #(")));
                if module != e.core && instantiated {
                    rtl.push_str(&std::fs::read_to_string(&path).unwrap());
                }
            }
            for (signal, names) in (e.wave_names)() {
                assert!(!names.is_empty(), "{}: {signal}", e.core);
                for (value, name) in names {
                    let decl = rtl.lines().find(|l| {
                        l.trim_start().starts_with(&format!("{name} ")) && l.contains('=')
                    });
                    let decl =
                        decl.unwrap_or_else(|| panic!("{}: no state {name} in the RTL", e.core));
                    let rhs = decl
                        .split('=')
                        .nth(1)
                        .unwrap()
                        .trim()
                        .trim_end_matches([',', ';']);
                    let rtl_value = rhs.rsplit('d').next().unwrap().parse::<u64>().unwrap();
                    assert_eq!(rtl_value, value, "{}: {name}", e.core);
                    named += 1;
                }
            }
        }
        assert!(named >= 30, "only {named} state names");
    }

    #[test]
    fn enum_names_are_the_rtls_upper_case() {
        #[derive(Debug, Clone, Copy)]
        enum S {
            Idle = 0,
            NoAck = 10,
        }
        assert_eq!(
            enum_names(&[S::Idle, S::NoAck], |s| s as u64),
            vec![(0, "IDLE".to_string()), (10, "NOACK".to_string())]
        );
    }

    #[test]
    fn a_data_id_is_decimal_or_hex_up_to_15() {
        assert_eq!(parse_data_id("3"), Ok(3));
        assert_eq!(parse_data_id("0xD"), Ok(13));
        assert!(parse_data_id("16").unwrap_err().contains("0 to 15"));
    }
}
