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
    constant PATH : string := esl_monitor'path_name;
    constant HANDLE : integer := emu_instance("esl_monitor", CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_MON_HZ, PATH);
begin
    process (i_mon_clk)
        -- Each input's level before reset ends: RO and DI high, driver off
        variable pins : emu_pins_t := emu_pins_init("00000011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_mon_clk) then
            emu_clock(HANDLE, PATH, "monitor", "i_esl_rx, i_esl_data, i_esl_data_oe", "00000" & i_esl_data_oe & i_esl_data & i_esl_rx, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
        end if;
    end process;
end architecture;
