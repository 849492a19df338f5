-- ssi_encoder_emu: an SSI encoder and its cable for a VHDL testbench, the
-- twin of hdl/emu/ssi_encoder_emu.v (same generics, ports and behaviour;
-- read its header): the encoder-tb model through emu_pkg (VHPIDIRECT).
--
-- Controls by instance label (emu_pkg): set_position("u_emu", 0, p),
-- schedule_fault("u_emu", "fault = { level = false, from_read = 3 }"),
-- count("u_emu"), last_value("u_emu", 0), violations("u_emu").
-- CONFIG "" reads the plusarg +<PLUSARG>=<file> (ghdl -r tb +ssi_emu_config=encoder.toml).

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity ssi_encoder_emu is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "ssi_emu_config";
        F_EMU_HZ : natural := 50000000;
        TRANSCRIPT : string := "";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Emulator clock */
        i_emu_clk : in std_logic;

        /* SSI line at the master's end of the cable */
        i_ssi_clk : in std_logic;
        o_ssi_data : out std_logic := '1'
    );
end entity;

architecture emu of ssi_encoder_emu is
    constant PATH : string := ssi_encoder_emu'path_name;
    constant HANDLE : integer := emu_instance("ssi", CONFIG, PLUSARG, TRANSCRIPT, "", F_EMU_HZ, PATH);
begin
    process (i_emu_clk)
        -- The clock idle high before reset ends.
        variable pins : emu_pins_t := emu_pins_init("00000001");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_emu_clk) then
            emu_clock(HANDLE, PATH, "emulator", "i_ssi_clk", "0000000" & i_ssi_clk, -1, -1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
            o_ssi_data <= output(0);
        end if;
    end process;
end architecture;
