//! The objects and services of seed 003, the Leine & Linde CANopen Encoder
//! Gateway application note (revision 1.3, 1999-03-19), for
//! `docs/compliance/canopen.md` ([`crate::compliance`]). Sections are the
//! note's; the words are its own, as the seed's text has them.

use crate::compliance::{Clause, Roles, Standard};

/// A clause of the note: held in one row.
const fn note(
    id: &'static str,
    short: &'static str,
    section: &'static str,
    words: &'static str,
) -> Clause {
    Clause::quoted(id, short, Roles::Any, section, words)
}

/// The identifiers (§2.1) and the boot-up message (§2.2).
static IDENTIFIERS: [Clause; 11] = [
    note("cob-id", "function code and node number", "§2.1", "This ID-allocation scheme consists of a functional part, which determines the object priority and a module-ID-part, which is equal to the node number (1 to 127)."),
    note("broadcast", "module-ID 0 for NMT, SYNC and node guarding", "§2.1", "Broadcasting of non-confirmed services (NMT, SYNC and node guarding) is indicated by a module-ID of zero."),
    note("nmt", "NMT on COB-ID 0", "§2.1, broadcast objects", "NMT 0000 0 0"),
    note("sync", "SYNC on COB-ID 128", "§2.1, broadcast objects", "SYNC 0001 128 0"),
    note("emergency", "EMERGENCY on 129 to 255", "§2.1, peer-to-peer objects", "EMERGENCY 0001 129 – 255 0, 1"),
    note("pdo1-tx", "PDO1 (tx) on 385 to 511", "§2.1, peer-to-peer objects", "PDO1 (tx) 0011 385 - 511 1, 2"),
    note("pdo2-tx", "PDO2 (tx) on 641 to 767", "§2.1, peer-to-peer objects", "PDO2 (tx) 0101 641 - 767 2, 3"),
    note("sdo-tx", "SDO (tx) on 1409 to 1535", "§2.1, peer-to-peer objects", "SDO (tx) 1011 1409 - 1535 6"),
    note("sdo-rx", "SDO (rx) on 1537 to 1663", "§2.1, peer-to-peer objects", "SDO (rx) 1100 1537 – 1663 6, 7"),
    note("nodeguard", "node guarding on 1793 to 1919", "§2.1, peer-to-peer objects", "Nodeguard 1110 1793 – 1919 -"),
    note("boot-up", "boot-up on the emergency identifier, no data bytes", "§2.2", "The encoder sends a Boot-up message after power-on and initialisation. This message uses the default emergency identifier and has no data bytes."),
];

/// Scaling (§3) and preset (§4).
static POSITION: [Clause; 7] = [
    note("scaling-order", "6001h before 6002h", "§3.1", "When scaling a Multiturn encoder the parameter \"Measuring units per revolution\" must be sent before the parameter \"Total measuring range in measuring units\"."),
    note("scaling-range", "both parameters 1 to 2^32, limited by the resolution", "§3.1", "The data type for both scaling parameters is unsigned 32 with a value range from 1 to 2^{32} limited by the encoder resolution."),
    note("scaling-formula", "output from units per revolution", "§3.2", "A = measuring_units_per_revolution * singleturn_position / 8192 output_position = (revolution_number * measuring_units_per_revolution) + A"),
    note("cyclic-operation", "binary scaling wraps", "§3.2.1 A", "If the desired measuring range is equal to the specified singleturn resolution * 2^x (where x <= 12) the encoder operates in endless cyclic operation (0 - max - 0 - max ...)."),
    note("non-cyclic-operation", "other ranges hold the range's value outside it", "§3.2.1 B", "If the position value increases or decreases outside the measuring range by rotating the encoder beyond the maximum value (measuring range-1) or below 0 the encoder outputs the total measuring range value"),
    note("preset", "offset = preset − current, output = current + offset", "§4.2", "Setup calculation: offset_value = preset_value - current_position ... Runtime calculation: output_position = current_position + offset_value"),
    note("preset-offset", "the offset read in 6509h", "§4.1", "The offset value can be read with the diagnostic function (Object 6509h)"),
];

/// Address, bit rate and the manufacturer objects (§5.4, §5.5, §6).
static SETTINGS: [Clause; 5] = [
    note("address-switch", "node 1 to 127 from the switch, read at power-up", "§5.4", "The physical address (node number) of the gateway must be set between 1 - 127 with the address switch inside the gateway. ... The gateway reads the address switch only at power-up."),
    note("bit-rate-switch", "codes 0 to 7, read at power-up", "§5.5", "The value is set with three dip-switches (Switch 8,9,10 on SW1) as a binary code representing the selected transmission rate. The gateway reads the Baudrate switch only at power-up."),
    note("object-5000", "transmission rate, valid after the next power-up", "§6.1", "By writing the value FFh to Object 5000h the encoder gets the transmission rate by hardware. Changing to Software mode is done by writing the desired transmission rate code to Object 5000h. The transmission rate will be valid after next power-up (next initialisation sequence)."),
    note("object-5001", "node number 1 to 127, valid after the next power-up", "§6.2", "By setting the value FFh the encoder gets the node number by hardware. Changing to Software mode is done by writing the desired node number to Object 5001h. The node number can be set in the range 1 - 127. The node number will be valid after next power-up (initialisation sequence)."),
    note("object-5500", "the gateway's serial number", "§6.3", "Object 5500h contains the CANopen Encoder Gateway serial number. It is given as an unsigned32 binary value. If the gateway serial number is not used the value is set to maximum value FF FF FF h."),
];

/// The setup example (§8).
static SETUP: [Clause; 4] = [
    note("setup-sdo", "6200h = 10 ms by SDO, confirmed", "§8, step 5", "To set a cyclic transmission of the position value with 10ms repetition rate we need to send an SDO request message (ID = 1536 + Gateway address) to the cyclic timer object (Object 6200h) with the data below. The Gateway will confirm with the SDO response message (ID = 1408 + Gateway address)."),
    note("setup-start", "NMT start remote node", "§8, step 6", "To get the Gateway in operation we need to send an NMT \"start remote node\" message, ID = 0, two data bytes with the following contents: 0x01 The Gateway address (Node Number)"),
    note("setup-position", "the position every 10 ms in operational", "§8", "The Gateway has now entered the operational state and the position message (ID = 384 + Gateway address) is transferred with a 10ms repetition rate."),
    note("setup-emergency", "an error sends an emergency message", "§8", "If an error occur the Gateway will send an emergency message (ID = 128 + Gateway address)."),
];

/// Seed 003 as the compliance matrix lists it.
pub static STANDARD: Standard = Standard {
    protocol: "canopen",
    title: "seed 003, Leine & Linde CANopen Encoder Gateway application note (revision 1.3, 1999-03-19)",
    groups: &[
        ("Identifiers and boot-up", &IDENTIFIERS),
        ("Scaling and preset", &POSITION),
        ("Address, bit rate and manufacturer objects", &SETTINGS),
        ("The setup example", &SETUP),
    ],
};
