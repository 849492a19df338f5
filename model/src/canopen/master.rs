//! The CANopen master, cycle by cycle: the machine `hdl/rtl/canopen_master.v`
//! is to mirror (same ports, parameters and state names). It sits on one
//! [`Controller`] (`can_controller` in the RTL), boots and configures one
//! DS 406 encoder and then receives its position.
//!
//! ```text
//!  WAIT_BOOT ──boot-up (0x80+N no data, or 0x700+N 00)──> SDO_SEND ─o_tx_done─> SDO_WAIT
//!      │ BOOT_TIMEOUT: NMT 81 N (reset node), wait again      │ 60 idx sub: next parameter (or NMT_SEND after the last)
//!      │ after RETRIES: o_node_lost, FAILED                   │ 80 idx sub code: o_sdo_abort, FAILED
//!                                                             │ SDO_TIMEOUT: resend; after RETRIES o_node_lost, FAILED
//!  SDO_SEND with the buffer still busy for SDO_TIMEOUT (a frame nobody acknowledges): o_node_lost, FAILED
//!  NMT_SEND (01 N on COB-ID 0) ─o_tx_done─> RUN (o_config_done)
//!  RUN: TPDO1/TPDO2 of N → o_pos_valid, o_position; PDO_TIMEOUT cycles without one → o_pos_timeout (once), o_pos_stale
//!       (the age counter is internal: an output that changes every cycle would put a vector record in every cycle)
//!       EMCY of N (DLC 8) → o_emcy_valid, o_emcy_code, o_emcy_reg; boot-up of N → SDO_SEND (reconfigure)
//!       SYNC_PERIOD ≠ 0: a SYNC (0x80, no data) every SYNC_PERIOD cycles
//!  FAILED: until i_start; i_start in any state restarts at WAIT_BOOT
//! ```
//! Timing: the controller's outputs are registered; the master's next state
//! is computed from the controller outputs of the previous cycle and its own
//! registers, and its transmit request (`tx_start`) reaches the controller
//! at the next edge: one cycle from `o_rx_valid` to the master's reaction,
//! one more to `i_tx_start`.

use serde::{Deserialize, Serialize};

use super::cob::{cob_id, EMCY, NMT, NMT_ERR, SDO_RX, SDO_TX, SYNC, TPDO1, TPDO2};
use crate::can::frame::pack;
use crate::can::{Controller, ControllerConfig};
use crate::{ConfigError, Result};

/// The most SDO downloads of a parameter table: the RTL's `PARAM0_*` to `PARAM7_*`.
pub const MAX_PARAMS: usize = 8;

/// One SDO download of the configuration list (ROM of the RTL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Param {
    /// Index.
    pub index: u16,
    /// Sub-index.
    #[serde(default)]
    pub sub: u8,
    /// Size in bytes (1, 2 or 4): expedited download with the size indicated.
    pub size: u8,
    /// Value.
    pub value: u32,
}

impl Param {
    /// The request's 8 data bytes.
    pub fn request(&self) -> [u8; 8] {
        super::sdo::download(
            self.index,
            self.sub,
            &self.value.to_le_bytes()[..self.size as usize],
        )
    }

    /// The RTL's `PARAMk_OBJECT`: index, sub-index and size in one word.
    pub fn object_word(&self) -> u32 {
        (self.index as u32) << 16 | (self.sub as u32) << 8 | self.size as u32
    }
}

/// The master's configuration; each field is the Verilog parameter of the same name in upper case.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MasterConfig {
    /// The controller.
    pub can: ControllerConfig,
    /// The encoder's node number, 1 to 127.
    pub node: u8,
    /// SDO downloads, in order.
    pub params: Vec<Param>,
    /// Cycles to wait for the boot-up before a reset-node NMT.
    pub boot_timeout: u64,
    /// Cycles to wait for an SDO answer before sending again.
    pub sdo_timeout: u64,
    /// Retries after a timeout before `o_node_lost`.
    pub retries: u32,
    /// Cycles without a position PDO before `o_pos_timeout`.
    pub pdo_timeout: u64,
    /// SYNC period in cycles (0: no SYNC).
    pub sync_period: u64,
}

impl MasterConfig {
    /// Checks the fields.
    pub fn validate(&self) -> Result<()> {
        self.can.validate()?;
        if !(1..=127).contains(&self.node) {
            return Err(ConfigError::invalid(
                "master.node",
                format!("{}", self.node),
                "give the encoder's node number, 1 to 127",
            ));
        }
        if self.params.len() > MAX_PARAMS {
            return Err(ConfigError::invalid(
                "master.params",
                format!("{} entries", self.params.len()),
                format!("give at most {MAX_PARAMS} SDO downloads (the RTL's PARAM0..PARAM7)"),
            ));
        }
        for (k, p) in self.params.iter().enumerate() {
            if ![1, 2, 4].contains(&p.size) || (p.size < 4 && p.value >> (8 * p.size as u32) != 0) {
                return Err(ConfigError::invalid(
                    format!("master.params[{k}].size"),
                    format!("size {} value {:#x}", p.size, p.value),
                    "give size 1, 2 or 4 bytes and a value that fits it",
                ));
            }
        }
        for (f, v) in [
            ("master.boot_timeout", self.boot_timeout),
            ("master.sdo_timeout", self.sdo_timeout),
            ("master.pdo_timeout", self.pdo_timeout),
        ] {
            if v == 0 || v >= 1 << 31 {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v} cycles"),
                    "give 1 to 2^31 − 1 cycles",
                ));
            }
        }
        if self.sync_period >= 1 << 31 {
            return Err(ConfigError::invalid(
                "master.sync_period",
                format!("{} cycles", self.sync_period),
                "give 0 (off) to 2^31 − 1 cycles",
            ));
        }
        if self.retries > 255 {
            return Err(ConfigError::invalid(
                "master.retries",
                format!("{}", self.retries),
                "give 0 to 255",
            ));
        }
        Ok(())
    }
}

/// The master's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "SCREAMING_SNAKE_CASE")]
pub enum State {
    /// Waiting for the encoder's boot-up.
    WaitBoot = 0,
    /// Loading the next SDO download into the controller.
    SdoSend = 1,
    /// Waiting for the SDO answer.
    SdoWait = 2,
    /// Sending NMT start.
    NmtSend = 3,
    /// Operational: receiving positions.
    Run = 4,
    /// Stopped after an abort or a silent node.
    Failed = 5,
}

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Restart from WAIT_BOOT (pulse).
    pub i_start: bool,
    /// CAN transceiver receive output (asynchronous).
    pub i_can_rx: bool,
}

impl Default for In {
    fn default() -> Self {
        In {
            i_start: false,
            i_can_rx: true,
        }
    }
}

/// Registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// CAN transceiver transmit input.
    pub o_can_tx: bool,
    /// State code.
    pub o_state: u8,
    /// The encoder's boot-up was seen (pulse).
    pub o_booted: bool,
    /// Every parameter confirmed and NMT start sent (pulse).
    pub o_config_done: bool,
    /// The encoder aborted an SDO (pulse); `o_abort_*` hold it.
    pub o_sdo_abort: bool,
    /// Abort code.
    pub o_abort_code: u32,
    /// Index of the aborted parameter.
    pub o_abort_index: u16,
    /// Sub-index of the aborted parameter.
    pub o_abort_sub: u8,
    /// The node stayed silent through every retry (pulse).
    pub o_node_lost: bool,
    /// A position PDO arrived (pulse); `o_position` holds it.
    pub o_pos_valid: bool,
    /// The last position.
    pub o_position: u32,
    /// No position for PDO_TIMEOUT cycles (pulse, once per silence).
    pub o_pos_timeout: bool,
    /// No position for PDO_TIMEOUT cycles (level, until the next position).
    pub o_pos_stale: bool,
    /// An emergency arrived (pulse); `o_emcy_*` hold it.
    pub o_emcy_valid: bool,
    /// Emergency error code.
    pub o_emcy_code: u16,
    /// Emergency error register.
    pub o_emcy_reg: u8,
    /// A SYNC was sent (pulse).
    pub o_sync_sent: bool,
}

/// The master.
#[derive(Debug, Clone)]
pub struct Master {
    cfg: MasterConfig,
    ctrl: Controller,
    c_out: crate::can::Out,
    state: State,
    k: usize,
    timer: u64,
    tries: u32,
    sync_cnt: u64,
    sync_pending: bool,
    tx_start: bool,
    tx_id: u16,
    tx_dlc: u8,
    tx_data: u64,
    tx_sync: bool,
    out: Out,
}

impl Master {
    /// A master after reset, waiting for the boot-up.
    pub fn new(cfg: &MasterConfig) -> Result<Master> {
        cfg.validate()?;
        let ctrl = Controller::new(cfg.can)?;
        Ok(Master {
            cfg: cfg.clone(),
            c_out: ctrl.out(),
            ctrl,
            state: State::WaitBoot,
            k: 0,
            timer: 0,
            tries: 0,
            sync_cnt: 0,
            sync_pending: false,
            tx_start: false,
            tx_id: 0,
            tx_dlc: 0,
            tx_data: 0,
            tx_sync: false,
            out: Out {
                o_can_tx: true,
                ..Out::default()
            },
        })
    }

    /// The state.
    pub fn state(&self) -> State {
        self.state
    }

    /// The controller.
    pub fn controller(&self) -> &Controller {
        &self.ctrl
    }

    /// The outputs of the last edge.
    pub fn out(&self) -> Out {
        self.out
    }

    fn request(&mut self, id: u16, dlc: u8, data: &[u8], sync: bool) {
        self.tx_start = true;
        self.tx_id = id;
        self.tx_dlc = dlc;
        self.tx_data = pack(data);
        self.tx_sync = sync;
    }

    /// One rising edge of f_sys.
    pub fn step(&mut self, i: &In) -> Out {
        let ci = crate::can::In {
            i_tx_start: self.tx_start,
            i_tx_id: self.tx_id,
            i_tx_rtr: false,
            i_tx_dlc: self.tx_dlc,
            i_tx_data: self.tx_data,
            i_filter_id: 0,
            i_filter_mask: 0,
            i_can_rx: i.i_can_rx,
        };
        let c_next = self.ctrl.step(&ci);
        let c = self.c_out;
        let n = self.cfg.node;
        let mut o = Out {
            o_can_tx: c_next.o_can_tx,
            o_booted: false,
            o_config_done: false,
            o_sdo_abort: false,
            o_node_lost: false,
            o_pos_valid: false,
            o_pos_timeout: false,
            o_emcy_valid: false,
            o_sync_sent: false,
            ..self.out
        };
        // `free`: the buffer is empty and no request is on its way to it.
        let free = !c.o_tx_busy && !self.tx_start;
        self.tx_start = false;
        let rx = c.o_rx_valid && !c.o_rx_ide && !c.o_rx_rtr;
        let id = c.o_rx_id as u16;
        let byte = |k: u32| (c.o_rx_data >> (56 - 8 * k)) as u8;
        let boot = rx
            && ((id == cob_id(EMCY, n) && c.o_rx_dlc == 0)
                || (id == cob_id(NMT_ERR, n) && c.o_rx_dlc == 1 && byte(0) == 0));
        if c.o_tx_done && self.tx_sync {
            o.o_sync_sent = true;
            self.tx_sync = false;
        }
        // SYNC producer: counts in every state; the SYNC goes out in RUN when the buffer is free.
        if self.cfg.sync_period != 0 {
            if self.sync_cnt + 1 >= self.cfg.sync_period {
                self.sync_cnt = 0;
                self.sync_pending = true;
            } else {
                self.sync_cnt += 1;
            }
        }
        // 32 bits in the RTL, saturating.
        self.timer = (self.timer + 1).min(u32::MAX as u64);
        if i.i_start {
            self.state = State::WaitBoot;
            self.timer = 0;
            self.tries = 0;
        } else {
            match self.state {
                State::WaitBoot => {
                    if boot {
                        o.o_booted = true;
                        self.k = 0;
                        self.tries = 0;
                        self.state = if self.cfg.params.is_empty() {
                            State::NmtSend
                        } else {
                            State::SdoSend
                        };
                    } else if self.timer >= self.cfg.boot_timeout {
                        self.timer = 0;
                        if self.tries >= self.cfg.retries {
                            o.o_node_lost = true;
                            self.state = State::Failed;
                        } else {
                            // NMT reset node, if the buffer is free (a frame nobody acknowledges keeps it busy).
                            self.tries += 1;
                            if free {
                                self.request(cob_id(NMT, 0), 2, &[0x81, n], false);
                            }
                        }
                    }
                }
                State::SdoSend => {
                    if free {
                        let p = self.cfg.params[self.k];
                        self.request(cob_id(SDO_RX, n), 8, &p.request(), false);
                        self.state = State::SdoWait;
                        self.timer = 0;
                    } else if self.timer >= self.cfg.sdo_timeout {
                        o.o_node_lost = true;
                        self.state = State::Failed;
                    }
                }
                State::SdoWait => {
                    let p = self.cfg.params[self.k];
                    let ours = rx
                        && id == cob_id(SDO_TX, n)
                        && c.o_rx_dlc >= 8
                        && byte(1) as u16 | (byte(2) as u16) << 8 == p.index
                        && byte(3) == p.sub;
                    if boot {
                        // The node started again: the table from its first
                        // entry, with all its retries (a new node, not a late answer).
                        o.o_booted = true;
                        self.k = 0;
                        self.timer = 0;
                        self.tries = 0;
                        self.state = State::SdoSend;
                    } else if ours && byte(0) == 0x60 {
                        self.tries = 0;
                        self.k += 1;
                        self.state = if self.k == self.cfg.params.len() {
                            State::NmtSend
                        } else {
                            State::SdoSend
                        };
                    } else if ours && byte(0) == 0x80 {
                        o.o_sdo_abort = true;
                        o.o_abort_code = u32::from_le_bytes([byte(4), byte(5), byte(6), byte(7)]);
                        o.o_abort_index = p.index;
                        o.o_abort_sub = p.sub;
                        self.state = State::Failed;
                    } else if self.timer >= self.cfg.sdo_timeout {
                        if self.tries >= self.cfg.retries {
                            o.o_node_lost = true;
                            self.state = State::Failed;
                        } else {
                            self.tries += 1;
                            self.timer = 0;
                            self.state = State::SdoSend;
                        }
                    }
                }
                State::NmtSend => {
                    if free {
                        self.request(cob_id(NMT, 0), 2, &[0x01, n], false);
                        self.state = State::Run;
                        o.o_config_done = true;
                        o.o_pos_stale = false;
                        self.timer = 0;
                    }
                }
                State::Run => {
                    if boot {
                        o.o_booted = true;
                        self.k = 0;
                        self.state = if self.cfg.params.is_empty() {
                            State::NmtSend
                        } else {
                            State::SdoSend
                        };
                    } else if rx
                        && (id == cob_id(TPDO1, n) || id == cob_id(TPDO2, n))
                        && c.o_rx_dlc >= 4
                    {
                        o.o_pos_valid = true;
                        o.o_position = u32::from_le_bytes([byte(0), byte(1), byte(2), byte(3)]);
                        o.o_pos_stale = false;
                        self.timer = 0;
                    } else if rx && id == cob_id(EMCY, n) && c.o_rx_dlc == 8 {
                        o.o_emcy_valid = true;
                        o.o_emcy_code = byte(0) as u16 | (byte(1) as u16) << 8;
                        o.o_emcy_reg = byte(2);
                    }
                    if self.timer == self.cfg.pdo_timeout {
                        o.o_pos_timeout = true;
                        o.o_pos_stale = true;
                    }
                    if self.sync_pending && free {
                        self.sync_pending = false;
                        self.request(cob_id(SYNC, 0), 0, &[], true);
                    }
                }
                State::Failed => {}
            }
        }
        o.o_state = self.state as u8;
        self.c_out = c_next;
        self.out = o;
        o
    }
}

impl Master {
    /// How many of the next cycles, with `i_can_rx` at `rx` and no
    /// `i_start`, change no output, state, parameter index or try count:
    /// the controller's bit clock only counting ([`Controller::quiet`]:
    /// idle with nothing to send, or short of its next sample point or bit
    /// end), nothing on its way to it, no pulse standing, and none of
    /// the timers due: the boot or SDO timeout (`timer` reaching it), the
    /// PDO timeout (`timer` equal to it, in `RUN`) and, in `RUN`, the SYNC
    /// period (`sync_cnt` wrapping, which requests the SYNC at once).
    /// `SDO_SEND` and `NMT_SEND` request a frame as soon as the buffer is
    /// free, so they are never quiet.
    pub fn quiet(&self, rx: bool) -> u64 {
        let o = &self.out;
        let pulse = o.o_booted
            || o.o_config_done
            || o.o_sdo_abort
            || o.o_node_lost
            || o.o_pos_valid
            || o.o_pos_timeout
            || o.o_emcy_valid
            || o.o_sync_sent;
        let ctrl = self.ctrl.quiet(rx);
        if pulse
            || self.tx_start
            || self.tx_sync
            || self.c_out != self.ctrl.out()
            || ctrl == 0
            || o.o_can_tx != self.c_out.o_can_tx
        {
            return 0;
        }
        self.timers_quiet().min(ctrl)
    }

    /// Steps before the first of the master's own timers is due.
    fn timers_quiet(&self) -> u64 {
        // Steps before `timer` (incremented first) reaches `limit`.
        let before = |limit: u64| limit.saturating_sub(self.timer + 1);
        let sync = if self.cfg.sync_period == 0 {
            u64::MAX
        } else {
            self.cfg.sync_period - self.sync_cnt - 1
        };
        match self.state {
            State::WaitBoot => before(self.cfg.boot_timeout),
            State::SdoWait => before(self.cfg.sdo_timeout),
            State::SdoSend | State::NmtSend => 0,
            State::Run => {
                if self.sync_pending {
                    return 0;
                }
                let pdo = if self.timer < self.cfg.pdo_timeout {
                    before(self.cfg.pdo_timeout)
                } else {
                    u64::MAX
                };
                pdo.min(sync)
            }
            State::Failed => u64::MAX,
        }
    }

    /// Advances `n` cycles, at most [`Master::quiet`]: the controller's bit
    /// clock, the SYNC counter (a wrap outside `RUN` leaves a SYNC pending,
    /// as stepping does) and the saturating timer.
    pub fn skip(&mut self, n: u64) {
        self.ctrl.skip(n);
        let p = self.cfg.sync_period;
        if p != 0 {
            if self.sync_cnt + n >= p {
                self.sync_pending = true;
            }
            self.sync_cnt = (self.sync_cnt + n) % p;
        }
        self.timer = (self.timer + n).min(u32::MAX as u64);
    }
}

impl Master {
    /// The input ports, in vector order (the Verilog port names).
    pub fn input_ports() -> Vec<crate::ports::Port> {
        use crate::ports::Port;
        vec![
            Port::new("i_start", 1),
            Port::new("i_can_rx", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order (the Verilog port names).
    pub fn output_ports() -> Vec<crate::ports::Port> {
        use crate::ports::Port;
        vec![
            Port::new("o_can_tx", 1),
            Port::new("o_state", 3),
            Port::new("o_booted", 1),
            Port::new("o_config_done", 1),
            Port::new("o_sdo_abort", 1),
            Port::new("o_abort_code", 32),
            Port::new("o_abort_index", 16),
            Port::new("o_abort_sub", 8),
            Port::new("o_node_lost", 1),
            Port::new("o_pos_valid", 1),
            Port::new("o_position", 32),
            Port::new("o_pos_timeout", 1),
            Port::new("o_pos_stale", 1),
            Port::new("o_emcy_valid", 1),
            Port::new("o_emcy_code", 16),
            Port::new("o_emcy_reg", 8),
            Port::new("o_sync_sent", 1),
        ]
    }

    /// The table entry being downloaded (`k_reg`).
    pub fn param_index(&self) -> usize {
        self.k
    }

    /// Timeouts counted so far (`tries_reg`).
    pub fn tries(&self) -> u32 {
        self.tries
    }

    /// The boot-up / SDO / age counter (`timer_reg`).
    pub fn timer(&self) -> u64 {
        self.timer
    }
}

impl crate::Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = self.i_can_rx as u64;
    }
}

impl crate::Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.o_can_tx as u64;
        dst[1] = self.o_state as u64;
        dst[2] = self.o_booted as u64;
        dst[3] = self.o_config_done as u64;
        dst[4] = self.o_sdo_abort as u64;
        dst[5] = self.o_abort_code as u64;
        dst[6] = self.o_abort_index as u64;
        dst[7] = self.o_abort_sub as u64;
        dst[8] = self.o_node_lost as u64;
        dst[9] = self.o_pos_valid as u64;
        dst[10] = self.o_position as u64;
        dst[11] = self.o_pos_timeout as u64;
        dst[12] = self.o_pos_stale as u64;
        dst[13] = self.o_emcy_valid as u64;
        dst[14] = self.o_emcy_code as u64;
        dst[15] = self.o_emcy_reg as u64;
        dst[16] = self.o_sync_sent as u64;
    }
}
