//! CANopen identifiers (COB-IDs) and network management, as the gateway note
//! lists them (seed 003, section 2.1): an 11-bit identifier is a 4-bit
//! function code (bits 10..7) and the node number 1 to 127 (bits 6..0);
//! node 0 addresses every node in the broadcast services.
//!
//! ```text
//!  object      function code  COB-ID            (seed 003 §2.1)
//!  NMT         0000           0
//!  SYNC        0001           128
//!  EMERGENCY   0001           129 .. 255        (also the gateway's boot-up, §2.2)
//!  PDO1 (tx)   0011           385 .. 511
//!  PDO2 (tx)   0101           641 .. 767
//!  SDO (tx)    1011           1409 .. 1535      (device → master)
//!  SDO (rx)    1100           1537 .. 1663      (master → device)
//!  Nodeguard   1110           1793 .. 1919
//! ```

use serde::{Deserialize, Serialize};

/// NMT commands (COB-ID 0).
pub const NMT: u16 = 0x000;
/// SYNC (and the base of EMERGENCY).
pub const SYNC: u16 = 0x080;
/// Emergency, 0x80 + node.
pub const EMCY: u16 = 0x080;
/// Transmit PDO 1, 0x180 + node.
pub const TPDO1: u16 = 0x180;
/// Transmit PDO 2, 0x280 + node.
pub const TPDO2: u16 = 0x280;
/// Receive PDO 1 of the DS 301 pre-defined set, 0x200 + node (the SAR58K24 command channel).
pub const RPDO1: u16 = 0x200;
/// SDO from the device (server response), 0x580 + node.
pub const SDO_TX: u16 = 0x580;
/// SDO to the device (client request), 0x600 + node.
pub const SDO_RX: u16 = 0x600;
/// Node guarding / heartbeat / DS 301 boot-up, 0x700 + node.
pub const NMT_ERR: u16 = 0x700;

/// The COB-ID of `function` (one of the bases above) for `node`.
pub fn cob_id(function: u16, node: u8) -> u16 {
    function | (node as u16 & 0x7F)
}

/// A CANopen service recognised from an 11-bit identifier (pre-defined connection set).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "service", content = "node", rename_all = "snake_case")]
pub enum Service {
    /// NMT command.
    Nmt,
    /// SYNC.
    Sync,
    /// Emergency (or the gateway's boot-up, no data) of a node.
    Emcy(u8),
    /// Transmit PDO 1.
    Tpdo1(u8),
    /// Receive PDO 1.
    Rpdo1(u8),
    /// Transmit PDO 2.
    Tpdo2(u8),
    /// SDO response (device to master).
    SdoTx(u8),
    /// SDO request (master to device).
    SdoRx(u8),
    /// Node guarding, heartbeat or DS 301 boot-up.
    NmtErr(u8),
    /// Anything else.
    Other,
}

/// The service an identifier carries in the pre-defined connection set.
pub fn classify(id: u16) -> Service {
    let node = (id & 0x7F) as u8;
    match (id >> 7, node) {
        (0, 0) => Service::Nmt,
        (1, 0) => Service::Sync,
        (1, n) => Service::Emcy(n),
        (3, n) if n > 0 => Service::Tpdo1(n),
        (4, n) if n > 0 => Service::Rpdo1(n),
        (5, n) if n > 0 => Service::Tpdo2(n),
        (0xB, n) if n > 0 => Service::SdoTx(n),
        (0xC, n) if n > 0 => Service::SdoRx(n),
        (0xE, n) if n > 0 => Service::NmtErr(n),
        _ => Service::Other,
    }
}

/// NMT command specifiers (byte 0 of a COB-ID 0 frame; byte 1 is the node, 0 = all).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NmtCommand {
    /// 0x01: start remote node (to OPERATIONAL).
    Start = 0x01,
    /// 0x02: stop remote node (to STOPPED).
    Stop = 0x02,
    /// 0x80: enter pre-operational.
    EnterPreOperational = 0x80,
    /// 0x81: reset node.
    ResetNode = 0x81,
    /// 0x82: reset communication.
    ResetCommunication = 0x82,
}

impl NmtCommand {
    /// The command of a specifier byte.
    pub fn from_byte(b: u8) -> Option<NmtCommand> {
        Some(match b {
            0x01 => NmtCommand::Start,
            0x02 => NmtCommand::Stop,
            0x80 => NmtCommand::EnterPreOperational,
            0x81 => NmtCommand::ResetNode,
            0x82 => NmtCommand::ResetCommunication,
            _ => return None,
        })
    }

    /// Name as in CiA 301.
    pub fn name(self) -> &'static str {
        match self {
            NmtCommand::Start => "start remote node",
            NmtCommand::Stop => "stop remote node",
            NmtCommand::EnterPreOperational => "enter pre-operational",
            NmtCommand::ResetNode => "reset node",
            NmtCommand::ResetCommunication => "reset communication",
        }
    }
}

/// NMT states of a slave; the value is the state byte of node guarding and heartbeat.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "SCREAMING_SNAKE_CASE")]
pub enum NmtState {
    /// Initialisation (boot-up sent on leaving it).
    Initialisation = 0,
    /// Stopped: only NMT and error control.
    Stopped = 4,
    /// Operational: PDOs run.
    Operational = 5,
    /// Pre-operational: SDO, SYNC, EMCY, no PDOs.
    PreOperational = 127,
}

impl NmtState {
    /// The state of a guarding or heartbeat byte (bit 7, the toggle, ignored).
    pub fn from_byte(b: u8) -> Option<NmtState> {
        Some(match b & 0x7F {
            0 => NmtState::Initialisation,
            4 => NmtState::Stopped,
            5 => NmtState::Operational,
            127 => NmtState::PreOperational,
            _ => return None,
        })
    }
}

/// How the encoder announces itself after power-on and reset.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum BootUp {
    /// The gateway note (seed 003 §2.2, §8 step 4): on the emergency
    /// identifier 0x80 + node, no data bytes.
    #[default]
    Emergency,
    /// CiA DS 301 (4.x): on 0x700 + node, one byte 0x00.
    Ds301,
}

impl BootUp {
    /// The boot-up frame's identifier and data for `node`.
    pub fn frame(self, node: u8) -> (u16, Vec<u8>) {
        match self {
            BootUp::Emergency => (cob_id(EMCY, node), Vec::new()),
            BootUp::Ds301 => (cob_id(NMT_ERR, node), vec![0x00]),
        }
    }
}
