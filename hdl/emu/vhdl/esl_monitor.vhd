-- esl_monitor: a pin-level monitor and protocol checker of an ESL host for a VHDL
-- testbench, the twin of hdl/emu/esl_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", 0) (abm << 24 | abs),
-- last_status("u_mon", 0, "crc1"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity esl_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "esl_monitor_config";
        F_MON_HZ : natural := 80000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "esl_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* The host's transceiver: DI, DE, RO */
        i_esl_data : in std_logic;
        i_esl_data_oe : in std_logic;
        i_esl_rx : in std_logic
    );
end entity;

architecture emu of esl_monitor is
begin
    -- Each input's level before reset ends: RO and DI high, driver off
    core : entity work.emu_core
        generic map (KIND => "esl_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => esl_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_esl_rx, i_esl_data, i_esl_data_oe", IDLE => "00000011")
        port map (i_clk => i_mon_clk, i_pins => "00000" & i_esl_data_oe & i_esl_data & i_esl_rx);
end architecture;
