//! The clauses of the Bosch CAN Specification 2.0 (September 1991) the
//! core is held to, for `docs/compliance/can.md` ([`crate::compliance`]).
//!
//! Seed 003 §1.3 names the document ("CAN Specification Version 2.0 A,
//! Robert Bosch GmbH"); the sections are its own, read from a public scan
//! (part A §3.1.3 to §3.1.5 frames and spacing, §5 coding, §8 bit timing;
//! part B §7 error detection, §8 fault confinement, §9 oscillator
//! tolerance). The words are the specification's; how the core reads each
//! is in `docs/timing/can.md`.

use super::rules::{BIT_TIME, CRC, DOMINANT, FORM, INTERMISSION, STUFF};
use crate::compliance::{Clause, Roles, Standard, Text};

/// A fault confinement rule of part B §8: held as transmitter and as receiver.
const fn rule(
    n: &'static str,
    id: &'static str,
    short: &'static str,
    words: &'static str,
) -> Clause {
    Clause::quoted(id, short, Roles::TransmitterAndReceiver, n, words)
}

const ANY: Roles = Roles::Any;

/// Error detection (part B §7.1, §7.2).
static DETECTION: [Clause; 7] = [
    Clause::quoted(
        "bit-error",
        "a sender reads another level than it sends",
        ANY,
        "part B §7.1, BIT ERROR",
        "A unit that is sending a bit on the bus also monitors the bus. A BIT ERROR has to be detected at that bit time, when the bit value that is monitored is different from the bit value that is sent. An exception is the sending of a 'recessive' bit during the stuffed bit stream of the ARBITRATION FIELD or during the ACK SLOT. Then no BIT ERROR occurs when a 'dominant' bit is monitored. A TRANSMITTER sending a PASSIVE ERROR FLAG and detecting a 'dominant' bit does not interpret this as a BIT ERROR.",
    ),
    Clause {
        id: "stuff-error",
        short: "six equal bits in the stuffed part",
        roles: ANY,
        text: Text::Rule(&STUFF),
    },
    Clause {
        id: "crc-error",
        short: "received CRC differs from the calculated one",
        roles: ANY,
        text: Text::Rule(&CRC),
    },
    Clause::quoted(
        "crc-error-flag",
        "the CRC error's flag follows the ACK delimiter",
        ANY,
        "part B §7.2",
        "Whenever a CRC ERROR is detected, transmission of an ERROR FLAG starts at the bit following the ACK DELIMITER, unless an ERROR FLAG for another condition has already been started.",
    ),
    Clause {
        id: "form-error",
        short: "an illegal bit in a fixed-form field",
        roles: ANY,
        text: Text::Rule(&FORM),
    },
    Clause::quoted(
        "form-error-last-eof",
        "a receiver's dominant last EOF bit is no form error",
        ANY,
        "part B §7.1, note",
        "for a Receiver a dominant bit during the last bit of END OF FRAME is not treated as FORM ERROR.",
    ),
    Clause::quoted(
        "ack-error",
        "a transmitter reads a recessive ACK slot",
        ANY,
        "part B §7.1, ACKNOWLEDGMENT ERROR",
        "An ACKNOWLEDGMENT ERROR has to be detected by a TRANSMITTER whenever it does not monitor a 'dominant' bit during the ACK SLOT.",
    ),
];

/// Fault confinement (part B §3.4 and §8, rules 1 to 12).
static CONFINEMENT: [Clause; 13] = [
    Clause::quoted(
        "transmitter",
        "a node stays transmitter until the bus is idle",
        Roles::TransmitterAndReceiver,
        "part B §3.4, definition of TRANSMITTER / RECEIVER",
        "A unit originating a message is called 'TRANSMITTER' of that message. The unit stays TRANSMITTER until the bus is idle or the unit loses ARBITRATION. A unit is called 'RECEIVER' of a message, if it is not TRANSMITTER of that message and the bus is not idle.",
    ),
    rule(
        "part B §8, rule 1",
        "fc-1",
        "REC + 1 for a receiver's error",
        "When a RECEIVER detects an error, the RECEIVE ERROR COUNT will be increased by 1, except when the detected error was a BIT ERROR during the sending of an ACTIVE ERROR FLAG or an OVERLOAD FLAG.",
    ),
    rule(
        "part B §8, rule 2",
        "fc-2",
        "REC + 8 for a dominant bit after a receiver's error flag",
        "When a RECEIVER detects a 'dominant' bit as the first bit after sending an ERROR FLAG the RECEIVE ERROR COUNT will be increased by 8.",
    ),
    rule(
        "part B §8, rule 3",
        "fc-3",
        "TEC + 8 for a transmitter's error flag, two exceptions",
        "When a TRANSMITTER sends an ERROR FLAG the TRANSMIT ERROR COUNT is increased by 8. Exception 1: If the TRANSMITTER is 'error passive' and detects an ACKNOWLEDGMENT ERROR because of not detecting a 'dominant' ACK and does not detect a 'dominant' bit while sending its PASSIVE ERROR FLAG. Exception 2: If the TRANSMITTER sends an ERROR FLAG because a STUFF ERROR occurred during ARBITRATION, whereby the STUFFBIT is located before the RTR bit, and should have been 'recessive', and has been sent 'recessive' but monitored as 'dominant'.",
    ),
    rule(
        "part B §8, rule 4",
        "fc-4",
        "TEC + 8 for a bit error in a transmitter's active error or overload flag",
        "If a TRANSMITTER detects a BIT ERROR while sending an ACTIVE ERROR FLAG or an OVERLOAD FLAG the TRANSMIT ERROR COUNT is increased by 8.",
    ),
    rule(
        "part B §8, rule 5",
        "fc-5",
        "REC + 8 for a bit error in a receiver's active error or overload flag",
        "If a RECEIVER detects a BIT ERROR while sending an ACTIVE ERROR FLAG or an OVERLOAD FLAG the RECEIVE ERROR COUNT is increased by 8.",
    ),
    rule(
        "part B §8, rule 6",
        "fc-6",
        "+ 8 per 8 dominant bits after a flag's 7 tolerated",
        "Any node tolerates up to 7 consecutive 'dominant' bits after sending an ACTIVE ERROR FLAG, PASSIVE ERROR FLAG or OVERLOAD FLAG. After detecting the 14th consecutive 'dominant' bit (in case of an ACTIVE ERROR FLAG or an OVERLOAD FLAG) or after detecting the 8th consecutive 'dominant' bit following a PASSIVE ERROR FLAG, and after each sequence of additional eight consecutive 'dominant' bits every TRANSMITTER increases its TRANSMIT ERROR COUNT by 8 and every RECEIVER increases its RECEIVE ERROR COUNT by 8.",
    ),
    rule(
        "part B §8, rule 7",
        "fc-7",
        "TEC − 1 after a successful transmission",
        "After the successful transmission of a message (getting ACKNOWLEDGE and no error until END OF FRAME is finished) the TRANSMIT ERROR COUNT is decreased by 1 unless it was already 0.",
    ),
    rule(
        "part B §8, rule 8",
        "fc-8",
        "REC − 1 (or 119 to 127 from above 127) after a successful reception",
        "After the successful reception of a message (reception without error up to the ACKNOWLEDGE SLOT and the successful sending of the ACKNOWLEDGE bit), the RECEIVE ERROR COUNT is decreased by 1, if it was between 1 and 127. If the RECEIVE ERROR COUNT was 0, it stays 0, and if it was greater than 127, then it will be set to a value between 119 and 127.",
    ),
    rule(
        "part B §8, rule 9",
        "fc-9",
        "error-passive from a count of 128; that error still sends an active flag",
        "A node is 'error passive' when the TRANSMIT ERROR COUNT equals or exceeds 128, or when the RECEIVE ERROR COUNT equals or exceeds 128. An error condition letting a node become 'error passive' causes the node to send an ACTIVE ERROR FLAG.",
    ),
    rule(
        "part B §8, rule 10",
        "fc-10",
        "bus-off from TEC 256",
        "A node is 'bus off' when the TRANSMIT ERROR COUNT is greater than or equal to 256.",
    ),
    rule(
        "part B §8, rule 11",
        "fc-11",
        "error-active again when both counts are at most 127",
        "An 'error passive' node becomes 'error active' again when both the TRANSMIT ERROR COUNT and the RECEIVE ERROR COUNT are less than or equal to 127.",
    ),
    rule(
        "part B §8, rule 12",
        "fc-12",
        "bus-off recovery after 128 × 11 recessive bits, counts 0",
        "A node which is 'bus off' is permitted to become 'error active' (no longer 'bus off') with its error counters both set to 0 after 128 occurrence of 11 consecutive 'recessive' bits have been monitored on the bus.",
    ),
];

/// Frames, flags and spacing (part A §3.1.3 to §3.1.5, §5).
static FRAMING: [Clause; 7] = [
    Clause::quoted(
        "bit-stuffing",
        "a complementary bit after five equal bits",
        ANY,
        "part A §5, BIT STUFFING",
        "The frame segments START OF FRAME, ARBITRATION FIELD, CONTROL FIELD, DATA FIELD and CRC SEQUENCE are coded by the method of bit stuffing. Whenever a transmitter detects five consecutive bits of identical value in the bit stream to be transmitted it automatically inserts a complementary bit in the actual transmitted bit stream.",
    ),
    Clause {
        id: "active-error-flag",
        short: "six dominant bits, superposed up to twelve",
        roles: ANY,
        text: Text::Rule(&DOMINANT),
    },
    Clause::quoted(
        "passive-error-flag",
        "complete after six equal bits",
        ANY,
        "part A §3.1.3, ERROR FLAG",
        "The PASSIVE ERROR FLAG is complete when these 6 equal bits have been detected.",
    ),
    Clause::quoted(
        "error-delimiter",
        "wait for a recessive bit, then seven more",
        ANY,
        "part A §3.1.3, ERROR DELIMITER",
        "After transmission of an ERROR FLAG each station sends 'recessive' bits and monitors the bus until it detects a 'recessive' bit. Afterwards it starts transmitting seven more 'recessive' bits.",
    ),
    Clause {
        id: "intermission",
        short: "three recessive bits, no frame starts in them",
        roles: ANY,
        text: Text::Rule(&INTERMISSION),
    },
    Clause::quoted(
        "intermission-third-bit",
        "a dominant third intermission bit is a start of frame",
        ANY,
        "part A §3.1.4, OVERLOAD FLAG",
        "In case that there is a 'dominant' bit detected during the 3rd bit of INTERMISSION locally at some node, the other nodes will not interpret the OVERLOAD FLAG correctly, but interpret the first of these six 'dominant' bits as START OF FRAME.",
    ),
    Clause::quoted(
        "suspend",
        "an error-passive transmitter waits 8 more recessive bits",
        ANY,
        "part A §3.1.5, SUSPEND TRANSMISSION",
        "After an 'error passive' station has transmitted a message, it sends eight 'recessive' bits following INTERMISSION, before starting to transmit a further message or recognizing the bus to be idle. If meanwhile a transmission (caused by another station) starts, the station will become receiver of this message.",
    ),
];

/// Overload (part A §3.1.4).
static OVERLOAD: [Clause; 3] = [
    Clause::quoted(
        "overload-1",
        "a receiver's internal conditions delay the next frame",
        ANY,
        "part A §3.1.4, OVERLOAD condition 1",
        "The internal conditions of a receiver, which requires a delay of the next DATA FRAME or REMOTE FRAME. ... The start of an OVERLOAD FRAME due to OVERLOAD condition 1 is only allowed to be started at the first bit time of an expected INTERMISSION ... At most two OVERLOAD FRAMEs may be generated to delay the next DATA or REMOTE FRAME.",
    ),
    Clause::quoted(
        "overload-2",
        "a dominant bit in intermission starts an overload flag",
        ANY,
        "part A §3.1.4, OVERLOAD condition 2",
        "Detection of a 'dominant' bit during INTERMISSION. ... OVERLOAD FRAMEs due to OVERLOAD condition 2 start one bit after detecting the 'dominant' bit.",
    ),
    Clause::quoted(
        "overload-delimiter",
        "eight recessive bits after the flags",
        ANY,
        "part A §3.1.4, OVERLOAD DELIMITER",
        "After transmission of an OVERLOAD FLAG the station monitors the bus until it detects a transition from a 'dominant' to a 'recessive' bit. At this point of time every bus station has finished sending its OVERLOAD FLAG and all stations start transmission of seven more 'recessive' bits in coincidence.",
    ),
];

/// Bit timing and synchronisation (part A §8; the rule book's bit time adds part B §9's tolerance).
static TIMING: [Clause; 6] = [
    Clause {
        id: "bit-time",
        short: "the bit time's four segments, the sample point, the tolerance",
        roles: ANY,
        text: Text::Rule(&BIT_TIME),
    },
    Clause::quoted(
        "prop-seg",
        "PROP_SEG covers the network's delays",
        ANY,
        "part A §8, PROP SEG",
        "This part of the bit time is used to compensate for the physical delay times within the network.",
    ),
    Clause::quoted(
        "sync-1",
        "one synchronisation per bit time",
        ANY,
        "part A §8, SYNCHRONIZATION RULES, 1",
        "Only one SYNCHRONIZATION within one bit time is allowed.",
    ),
    Clause::quoted(
        "sync-2",
        "an edge counts only after the other level was sampled",
        ANY,
        "part A §8, SYNCHRONIZATION RULES, 2",
        "An edge will be used for SYNCHRONIZATION only if the value detected at the previous SAMPLE POINT (previous read bus value) differs from the bus value immediately after the edge.",
    ),
    Clause::quoted(
        "sync-3",
        "hard synchronisation on a falling edge in bus idle",
        ANY,
        "part A §8, SYNCHRONIZATION RULES, 3",
        "HARD SYNCHRONIZATION is performed whenever there is a 'recessive' to 'dominant' edge during BUS IDLE.",
    ),
    Clause::quoted(
        "sync-4",
        "resynchronisation on other falling edges, not by a node sending dominant",
        ANY,
        "part A §8, SYNCHRONIZATION RULES, 4",
        "All other 'recessive' to 'dominant' edges (and optionally 'dominant' to 'recessive' edges in case of low bit rates) fulfilling the rules 1 and 2 will be used for RESYNCHRONIZATION with the exception that a node transmitting a dominant bit will not perform a RESYNCHRONIZATION as a result of a 'recessive' to 'dominant' edge with a positive PHASE ERROR, if only 'recessive' to 'dominant' edges are used for resynchronization.",
    ),
];

/// The Bosch CAN Specification 2.0 as the compliance matrix lists it.
pub static STANDARD: Standard = Standard {
    protocol: "can",
    title: "Robert Bosch GmbH, CAN Specification Version 2.0 (September 1991), parts A and B",
    groups: &[
        ("Error detection", &DETECTION),
        ("Fault confinement", &CONFINEMENT),
        ("Frames, flags and spacing", &FRAMING),
        ("Overload", &OVERLOAD),
        ("Bit timing and synchronisation", &TIMING),
    ],
};
