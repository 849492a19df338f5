//! The silence before every request, measured on the line of every built-in
//! Modbus scenario: the Modbus serial-line specification (2.5.1.1) asks
//! for "a silent interval of at least 3.5 character times" between frames.
//! The measurement reads the line at the master and the master's driver,
//! cycle by cycle, and knows nothing of the master's counters: a character
//! begins at a falling edge after the previous one's stop-bit middle and
//! holds the line for its start, 8 data, parity and stop bits at the
//! configured baud (or to its last rising edge, if later: a low stop bit);
//! a low pulse shorter than half a bit is a glitch and holds the line to its
//! rising edge.

#[cfg(test)]
mod tests {
    use crate::builtin;
    use model::modbus::BenchConfig;
    use model::testbench::Testbench;
    use model::trace::Sample;
    use model::uart::Parity;
    use model::Setup as _;

    /// One request's start and the silence before it, in seconds.
    struct Gap {
        start_s: f64,
        silence_s: f64,
    }

    /// t3.5 in seconds: 3.5 characters, 1750 µs above 19200 baud (spec 2.5.1.1).
    fn t35_s(cfg: &BenchConfig) -> f64 {
        let bits = if cfg.parity == Parity::None { 10.0 } else { 11.0 };
        if cfg.baud > 19_200.0 {
            1750e-6
        } else {
            3.5 * bits / cfg.baud
        }
    }

    /// The silence before every request after the first of one scenario.
    fn silences(cfg: &BenchConfig) -> Vec<Gap> {
        let mut bench = cfg.bench().unwrap();
        let layout = bench.layout().clone();
        let line_col = layout.line.iter().position(|p| p.name == "line_at_master").unwrap();
        let en_col = layout.outputs.iter().position(|p| p.name == "o_tx_en").unwrap();
        let tx_col = layout.outputs.iter().position(|p| p.name == "o_tx").unwrap();
        let mut sample = Sample::for_layout(&layout);
        let f = cfg.f_sys_mhz * 1e6;
        let bits = if cfg.parity == Parity::None { 10.0 } else { 11.0 };
        let char_s = bits / cfg.baud;
        let half_bit_s = 0.5 / cfg.baud;
        // The line at the master: a character (or glitch) holds it busy until `busy_until`.
        let mut busy_until = f64::NEG_INFINITY;
        let mut in_char: Option<f64> = None;
        let mut last_line = true;
        let mut last_en = false;
        let mut request_open = false;
        let mut gaps = Vec::new();
        let mut requests = 0;
        while !bench.finished() {
            bench.step(Some(&mut sample));
            let t = (bench.cycle() - 1) as f64 / f;
            let line = sample.line[line_col] != 0;
            let en = sample.outputs[en_col] != 0;
            let tx = sample.outputs[tx_col] != 0;
            if en && !last_en {
                request_open = true;
            }
            if request_open && en && !tx {
                // The request's first start bit on the master's driver.
                if requests > 0 {
                    gaps.push(Gap { start_s: t, silence_s: t - busy_until });
                }
                requests += 1;
                request_open = false;
            }
            if let Some(start) = in_char {
                // Past its stop bit's middle a falling edge starts the next
                // character (a sender a little fast may begin it before the
                // nominal end of this one).
                if t >= start + char_s - half_bit_s {
                    in_char = None;
                }
            }
            if in_char.is_none() && last_line && !line {
                in_char = Some(t);
                busy_until = t + char_s;
            } else if !last_line && line {
                // A rising edge: the line was busy at least until now.
                busy_until = busy_until.max(t);
                if let Some(start) = in_char {
                    if t - start < half_bit_s {
                        // A glitch, not a start bit: the line is free from here.
                        busy_until = t;
                        in_char = None;
                    }
                }
            }
            last_line = line;
            last_en = en;
        }
        gaps
    }

    #[test]
    fn every_request_follows_t35_of_silence_on_the_line() {
        let mut measured = 0;
        for s in builtin::all().unwrap() {
            let Some(cfg) = s.setup.get::<BenchConfig>() else { continue };
            let t35 = t35_s(cfg);
            for g in silences(cfg) {
                assert!(
                    g.silence_s >= t35,
                    "{}: the request at {:.1} µs follows {:.1} µs of silence on the line; t3.5 is {:.1} µs",
                    s.name,
                    g.start_s * 1e6,
                    g.silence_s * 1e6,
                    t35 * 1e6
                );
                measured += 1;
            }
        }
        assert!(measured >= 40, "{measured} requests measured");
    }
}
