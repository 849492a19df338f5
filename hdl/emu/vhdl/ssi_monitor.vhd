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
    constant PATH : string := ssi_monitor'path_name;
    constant HANDLE : integer := emu_instance("ssi_monitor", CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_MON_HZ, PATH);
begin
    process (i_mon_clk)
        variable pins : emu_pins_t := emu_pins_init("00000011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_mon_clk) then
            emu_clock(HANDLE, PATH, "monitor", "i_ssi_clk, i_ssi_data", "000000" & i_ssi_data & i_ssi_clk, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
        end if;
    end process;
end architecture;
