-- can_monitor: a pin-level monitor and protocol checker of a CAN master for a VHDL
-- testbench, the twin of hdl/emu/can_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", field),
-- last_status("u_mon", 0, "ack"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity can_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "can_monitor_config";
        F_MON_HZ : natural := 10000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "can_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* The master's transceiver pins */
        i_can_tx : in std_logic;
        i_can_rx : in std_logic
    );
end entity;

architecture emu of can_monitor is
begin
    -- Each input's level before reset ends: TXD and RXD recessive
    core : entity work.emu_core
        generic map (KIND => "can_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => can_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_can_rx, i_can_tx", IDLE => "00000011")
        port map (i_clk => i_mon_clk, i_pins => "000000" & i_can_tx & i_can_rx);
end architecture;
