-- ssi_monitor: a pin-level monitor and protocol checker of an SSI master for
-- a VHDL testbench, the twin of hdl/emu/ssi_monitor.v (same generics, ports
-- and behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", 0),
-- last_status("u_mon", 0, "error"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity ssi_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "ssi_monitor_config";
        F_MON_HZ : natural := 50000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "ssi_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* SSI line at the master */
        i_ssi_clk : in std_logic;
        i_ssi_data : in std_logic
    );
end entity;

architecture emu of ssi_monitor is
begin
    -- Each input's level before reset ends: clock and data high
    core : entity work.emu_core
        generic map (KIND => "ssi_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => ssi_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_ssi_clk, i_ssi_data", IDLE => "00000011")
        port map (i_clk => i_mon_clk, i_pins => "000000" & i_ssi_data & i_ssi_clk);
end architecture;
