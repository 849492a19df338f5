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
    constant PATH : string := can_monitor'path_name;
    constant HANDLE : integer := emu_instance("can_monitor", CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_MON_HZ, PATH);
begin
    process (i_mon_clk)
        -- Each input's level before reset ends: TXD and RXD recessive
        variable pins : emu_pins_t := emu_pins_init("00000011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_mon_clk) then
            emu_clock(HANDLE, PATH, "monitor", "i_can_rx, i_can_tx", "000000" & i_can_tx & i_can_rx, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
        end if;
    end process;
end architecture;
