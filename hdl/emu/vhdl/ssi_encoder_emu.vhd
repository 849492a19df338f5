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
    signal answer : std_ulogic_vector(2 downto 0);
begin
    -- Each input's level before reset ends: the clock high
    core : entity work.emu_core
        generic map (KIND => "ssi", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_EMU_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => "", STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => ssi_encoder_emu'path_name, WHAT => "emulator", PIN_NAMES => "i_ssi_clk", IDLE => "00000001")
        port map (i_clk => i_emu_clk, i_pins => "0000000" & i_ssi_clk, o_pins => answer);

    o_ssi_data <= answer(0);
end architecture;
