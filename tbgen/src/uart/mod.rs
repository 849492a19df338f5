//! The shared 10-bit frame receiver in `tbgen`: sigrok's `uart` decoder
//! reads the receiver's line in the tests. [`line`] is the parity-aware
//! character reader the SAR58K24 and Modbus decoders share.

pub mod line;

use model::uart::BenchConfig;

use crate::registry::{Protocol, SigrokCheck, TransactionSignals, WaveNames};

impl Protocol for BenchConfig {
    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_valid", "o_frame_err", "o_start_err", "o_parity_err"], "o_data", "received");

    /// The state register's values by the model's [`model::uart::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::uart::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Start, S::Data, S::Stop, S::Recover], |s| s as u64))];
        names
    }
    const SIGROK_DECODER: Option<&'static str> = Some("uart");
    const SIGROK_MINIMUM: (usize, usize) = (1, 300);

    /// In a scenario where the receiver got every byte right, sigrok's
    /// `uart` decoder at the nominal rate must find the bytes it received.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let events = transcript["transactions"].as_array()?;
        if !events.iter().all(|e| e["kind"] == "byte" && e["received"] == e["sent"]) {
            return None;
        }
        Some(SigrokCheck {
            decoder: format!("uart:rx=rx_line:baudrate={}:parity={}", self.baud as u64, format!("{:?}", self.parity).to_lowercase()),
            annotation: "uart=rx-data",
            expected: events.iter().map(|e| e["received"].as_u64().map(u128::from)).collect(),
        })
    }
}
