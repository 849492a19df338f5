//! What a bench shows the outside world each cycle: the core's ports (for
//! vector files), the line-level signals and the model's decoded view (for
//! waveforms). Writers live in `tbgen`; this module only defines the shape.

use crate::Port;

/// The signals a bench reports, grouped as the VCD scopes group them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// The core's input ports, in vector-file order (Verilog port names).
    pub inputs: Vec<Port>,
    /// The core's output ports, in vector-file order (Verilog port names).
    pub outputs: Vec<Port>,
    /// Line-level signals (clock, data, driver enables), each one bit wide so
    /// that scalar-only readers such as sigrok can decode them.
    pub line: Vec<Port>,
    /// The model's own view: state, bit counter, fields as they are decoded.
    pub decoded: Vec<Port>,
}

/// One cycle's values, in the order of the [`Layout`]'s lists. Benches fill
/// one `Sample` in place each cycle so that long runs allocate nothing.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Sample {
    /// Values of [`Layout::inputs`].
    pub inputs: Vec<u64>,
    /// Expected values of [`Layout::outputs`].
    pub outputs: Vec<u64>,
    /// Which bits of each output must match (1) and which are don't-care (0).
    pub care: Vec<u64>,
    /// Values of [`Layout::line`].
    pub line: Vec<u64>,
    /// Values of [`Layout::decoded`].
    pub decoded: Vec<u64>,
}

impl Sample {
    /// This sample with the decoded columns `counters` zeroed: what a
    /// quiet stretch holds ([`crate::testbench::Testbench::counters`]).
    pub fn without_counters(&self, counters: &[usize]) -> Sample {
        let mut s = self.clone();
        for &k in counters {
            s.decoded[k] = 0;
        }
        s
    }

    /// A zeroed sample sized for `layout`.
    pub fn for_layout(layout: &Layout) -> Self {
        Sample {
            inputs: vec![0; layout.inputs.len()],
            outputs: vec![0; layout.outputs.len()],
            care: layout.outputs.iter().map(|p| p.mask()).collect(),
            line: vec![0; layout.line.len()],
            decoded: vec![0; layout.decoded.len()],
        }
    }
}

/// Receives a bench's samples, one call per system-clock cycle, in order.
pub trait Sink {
    /// Error type of the sink (I/O for file writers).
    type Error;
    /// Cycle `cycle` has the values in `sample`.
    fn sample(&mut self, cycle: u64, sample: &Sample) -> Result<(), Self::Error>;
}

/// A sink that keeps nothing: for running a model alone (benchmarks).
pub struct Discard;

impl Sink for Discard {
    type Error = std::convert::Infallible;
    fn sample(&mut self, _cycle: u64, _sample: &Sample) -> Result<(), Self::Error> {
        Ok(())
    }
}
