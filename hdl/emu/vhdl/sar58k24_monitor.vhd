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
    constant PATH : string := sar58k24_monitor'path_name;
    constant HANDLE : integer := emu_instance("sar58k24_monitor", CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_MON_HZ, PATH);
begin
    process (i_mon_clk)
        -- Each input's level before reset ends: R and D high, driver off, trigger and CLR high
        variable pins : emu_pins_t := emu_pins_init("00011011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_mon_clk) then
            emu_clock(HANDLE, PATH, "monitor", "i_rx, i_line, i_line_en, i_trigger, i_clr", "000" & i_clr & i_trigger & i_line_en & i_line & i_rx, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
        end if;
    end process;
end architecture;
