-- endat_monitor: a pin-level monitor and protocol checker of an EnDat master for a VHDL
-- testbench, the twin of hdl/emu/endat_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", 0),
-- last_status("u_mon", 0, "crc_ok"), violations("u_mon"). X on the driver
-- enable reads as 0 (one warning), as endat_encoder_emu reads it.

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity endat_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "endat_monitor_config";
        F_MON_HZ : natural := 64000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "endat_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* EnDat line at the master */
        i_endat_clk : in std_logic;
        i_endat_data : in std_logic;
        i_endat_data_oe : in std_logic;
        i_endat_data_in : in std_logic
    );
end entity;

architecture emu of endat_monitor is
    -- The data of a driver that is not on is not read (the line is R then).
    signal mon_data : std_logic;
begin
    mon_data <= i_endat_data when i_endat_data_oe = '1' else '1';

    -- Each input's level before reset ends: clock high, data high, driver off, receiver high
    core : entity work.emu_core
        generic map (KIND => "endat_monitor", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_MON_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => TRANSCRIPT_PLUSARG, STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => endat_monitor'path_name, WHAT => "monitor", PIN_NAMES => "i_endat_clk, i_endat_data, i_endat_data_oe, i_endat_data_in", IDLE => "00001011",
                     OE_PIN => 2, DATA_PIN => 1)
        port map (i_clk => i_mon_clk, i_pins => "0000" & i_endat_data_in & i_endat_data_oe & mon_data & i_endat_clk);
end architecture;
