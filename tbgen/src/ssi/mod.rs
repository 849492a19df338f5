//! SSI in `tbgen`: no decoder or budget of its own; sigrok's `spi` decoder
//! reads the line at the encoder's pins in the tests.

use model::ssi::BenchConfig;

use crate::registry::{Protocol, SigrokCheck, TransactionSignals};

impl Protocol for BenchConfig {
    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_position", "position");

    /// The state register's values by the model's [`model::ssi::State`] (the RTL's state names).
    fn wave_names() -> Vec<(&'static str, Vec<(u64, String)>)> {
        use model::ssi::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Latch, S::High, S::Low, S::Pause], |s| s as u64))];
        names
    }
    const SIGROK_DECODER: Option<&'static str> = Some("spi");
    const SIGROK_MINIMUM: (usize, usize) = (10, 25);

    /// One SPI word per read that clocked, at the encoder's pins: the level
    /// at the storing edge (the idle line, 1) followed by every sampled bit;
    /// a read the reader flagged (a fault between encoder and reader) is not compared.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let words: Vec<(String, bool)> = transcript["transactions"]
            .as_array()?
            .iter()
            .filter_map(|t| {
                let bits = t["received_bits"].as_str().filter(|b| !b.is_empty())?;
                Some((format!("1{bits}"), t["errors"].as_array().is_some_and(|e| e.is_empty())))
            })
            .collect();
        let wordsize = words.first()?.0.len();
        Some(SigrokCheck {
            decoder: format!("spi:clk=ssi_clk_encoder:miso=ssi_data_encoder:cpol=1:cpha=0:wordsize={wordsize}"),
            annotation: "spi=miso-data",
            expected: words.iter().map(|(w, clean)| clean.then(|| u128::from_str_radix(w, 2).ok()).flatten()).collect(),
        })
    }
}
