-- biss_monitor: a pin-level monitor and protocol checker of a BiSS-C master for a VHDL
-- testbench, the twin of hdl/emu/biss_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", slave),
-- last_status("u_mon", slave, "crc_ok"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity biss_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "biss_monitor_config";
        F_MON_HZ : natural := 80000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "biss_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* BiSS-C line at the master */
        i_ma : in std_logic;
        i_slo : in std_logic
    );
end entity;

architecture emu of biss_monitor is
begin
    -- Each input's level before reset ends: MA and SLO high
    core : entity work.emu_core
        generic map (KIND => "biss_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => biss_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_ma, i_slo", IDLE => "00000011")
        port map (i_clk => i_mon_clk, i_pins => "000000" & i_slo & i_ma);
end architecture;
