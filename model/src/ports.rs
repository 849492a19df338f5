//! Named, sized port lists: how a model's `In`/`Out` structs map onto the
//! ports of the Verilog core, the columns of a vector file and the signals of
//! a VCD file.

/// One port of a core: its Verilog name and its width in bits.
///
/// A core's port lists are written once, in its model (`input_ports` and
/// `output_ports`); the replay testbenches' port declarations, drivers and
/// checks (`hdl/tb/<core>/tb_<core>_ports.vh`) are generated from them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Port {
    /// The Verilog port name, which is also the Rust field name.
    pub name: &'static str,
    /// Width in bits, 1 to 64.
    pub width: u32,
    /// The Verilog parameter (of the core or its testbench) that sets the
    /// width, where the configuration does; `None` for a fixed width.
    pub width_param: Option<&'static str>,
    /// The level an input rests at before the first vector drives it (while
    /// reset is held): 1 for a line that idles high, which the core's
    /// unreset synchroniser must see from the start; 0 otherwise.
    pub idle: u64,
}

impl Port {
    /// A port of `width` bits.
    pub const fn new(name: &'static str, width: u32) -> Self {
        Port {
            name,
            width,
            width_param: None,
            idle: 0,
        }
    }

    /// The same port, its width set by the Verilog parameter `param`.
    pub const fn width_from(self, param: &'static str) -> Self {
        Port {
            width_param: Some(param),
            ..self
        }
    }

    /// The same input, resting high (a line's idle level) until driven.
    pub const fn idle_high(self) -> Self {
        Port { idle: 1, ..self }
    }

    /// The mask of the port's bits in a `u64`.
    pub fn mask(&self) -> u64 {
        if self.width >= 64 {
            u64::MAX
        } else {
            (1u64 << self.width) - 1
        }
    }
}

/// A struct of port values, listed in the same order as its port list.
pub trait Ports {
    /// Writes the values of the ports, one `u64` each, in port-list order,
    /// into `dst` (which has one slot per port). Allocates nothing, so that
    /// benches can record every cycle of a long run cheaply.
    fn write_values(&self, dst: &mut [u64]);

    /// The values of the ports as a new vector (for tests and tools).
    fn values(&self, ports: usize) -> Vec<u64> {
        let mut v = vec![0; ports];
        self.write_values(&mut v);
        v
    }
}

/// The total width of a port list.
pub fn total_width(ports: &[Port]) -> u32 {
    ports.iter().map(|p| p.width).sum()
}
