//! What sigrok's `modbus` decoder, stacked on `uart`, must print for a
//! Modbus run: the generic sigrok test compares the bytes; this adds the
//! Modbus fields (register count, byte count, register values, CRC verdicts,
//! exception codes). The two directions go to the decoder apart: the
//! master's `o_tx` as the client-to-server channel, the devices' driven
//! level `tx_device` as server-to-client.

/// The `-P` option for a run at `baud` with `parity` (`none`, `odd`, `even`).
pub fn decoder(baud: u64, parity: &str) -> String {
    format!("uart:rx=tx_device:tx=o_tx:baudrate={baud}:parity={parity},modbus")
}

/// Checks sigrok's `modbus` annotation lines against the transcript's
/// transactions; the error says what is missing.
pub fn check(lines: &[String], transactions: &[serde_json::Value]) -> Result<(), String> {
    let text = lines.join("\n");
    for t in transactions {
        if t["op"] == "read" && t["errors"].as_array().is_some_and(|e| e.is_empty()) {
            let v = t["value"].as_u64().ok_or("a good read without a value")?;
            let count = t["count"].as_u64().ok_or("a read without a count")?;
            for want in [format!("Read {count} units of data"), format!("Byte count: {}", 2 * count), format!("0x{:04X} / {}", v & 0xFFFF, v & 0xFFFF)] {
                if !text.contains(&want) {
                    return Err(format!("`{want}` (transaction {}) not in sigrok's output", t["index"]));
                }
            }
        }
        if let Some(code) = t["exception"].as_u64() {
            if !text.contains(&format!("Error {code}: ")) {
                return Err(format!("exception {code} (transaction {}) not in sigrok's output", t["index"]));
            }
        }
    }
    let bad = lines.iter().filter(|l| l.contains("CRC should be")).count();
    let flagged = transactions.iter().filter(|t| t["errors"].as_array().is_some_and(|e| e.iter().any(|e| e == "crc"))).count();
    if bad < flagged {
        return Err(format!("sigrok sees {bad} bad CRCs, the master flagged {flagged}"));
    }
    if !lines.iter().any(|l| l.contains("CRC correct")) {
        return Err("sigrok found no good CRC".into());
    }
    Ok(())
}
