-- modbus_monitor: a pin-level monitor and protocol checker of a Modbus RTU master for a VHDL
-- testbench, the twin of hdl/emu/modbus_monitor.v (same generics, ports and
-- behaviour; read its header): the encoder-tb library through emu_pkg.
--
-- Queries by instance label (emu_pkg): count("u_mon"), last_value("u_mon", 0),
-- last_status("u_mon", 0, "valid"), violations("u_mon").

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity modbus_monitor is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "modbus_monitor_config";
        F_MON_HZ : natural := 10000000;
        TRANSCRIPT : string := "";
        TRANSCRIPT_PLUSARG : string := "modbus_monitor_transcript";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Monitor clock */
        i_mon_clk : in std_logic;

        /* The master's transceiver: D, DE, R */
        i_line : in std_logic;
        i_line_en : in std_logic;
        i_rx : in std_logic
    );
end entity;

architecture emu of modbus_monitor is
    constant PATH : string := modbus_monitor'path_name;
    constant HANDLE : integer := emu_instance("modbus_monitor", CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_MON_HZ, PATH);
begin
    process (i_mon_clk)
        -- Each input's level before reset ends: R and D high, driver off
        variable pins : emu_pins_t := emu_pins_init("00000011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_mon_clk) then
            emu_clock(HANDLE, PATH, "monitor", "i_rx, i_line, i_line_en", "00000" & i_line_en & i_line & i_rx, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
        end if;
    end process;
end architecture;
