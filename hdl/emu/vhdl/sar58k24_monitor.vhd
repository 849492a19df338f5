-- sar58k24_monitor: a pin-level monitor and protocol checker of a SAR58K24 host for a VHDL
-- testbench, the twin of hdl/emu/sar58k24_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", 0),
-- last_status("u_mon", 0, "frame_ok"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity sar58k24_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "sar58k24_monitor_config";
        F_MON_HZ : natural := 10000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "sar58k24_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* The host's transceiver: D, DE, R; its trigger and CLR outputs */
        i_line : in std_logic;
        i_line_en : in std_logic;
        i_rx : in std_logic;
        i_trigger : in std_logic;
        i_clr : in std_logic
    );
end entity;

architecture emu of sar58k24_monitor is
begin
    -- Each input's level before reset ends: R and D high, driver off, trigger and CLR high
    core : entity work.emu_core
        generic map (KIND => "sar58k24_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => sar58k24_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_rx, i_line, i_line_en, i_trigger, i_clr", IDLE => "00011011")
        port map (i_clk => i_mon_clk, i_pins => "000" & i_clr & i_trigger & i_line_en & i_line & i_rx);
end architecture;
