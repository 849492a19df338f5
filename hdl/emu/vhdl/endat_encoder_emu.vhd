-- endat_encoder_emu: an EnDat 2.2 encoder and its cable for a VHDL
-- testbench, the twin of hdl/emu/endat_encoder_emu.v (same generics, ports and
-- behaviour; read its header): the encoder-tb model through emu_pkg.
--
-- Controls by instance label (emu_pkg): set_position("u_emu", 0, p), set_status,
-- schedule_fault, count("u_emu"), last_value("u_emu", 0), last_status("u_emu", 0, "f1"), violations("u_emu").
-- X on the driver enable reads as 0 (one warning), the data of a driver
-- whose enable is unknown is not read (emu_pkg.emu_clock).
-- CONFIG "" reads the plusarg +<PLUSARG>=<file>.

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity endat_encoder_emu is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "endat_emu_config";
        F_EMU_HZ : natural := 64000000;
        TRANSCRIPT : string := "";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Emulator clock */
        i_emu_clk : in std_logic;

        /* EnDat lines at the master's end of the cable */
        i_endat_clk : in std_logic;
        i_endat_data : in std_logic;
        i_endat_data_oe : in std_logic;
        o_endat_data : out std_logic := '1';
        o_endat_data_oe : out std_logic := '0'
    );
end entity;

architecture emu of endat_encoder_emu is
    signal answer : std_ulogic_vector(2 downto 0);
begin
    -- Each input's level before reset ends: clock high, data high, driver off
    core : entity work.emu_core
        generic map (KIND => "endat", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_EMU_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => "", STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => endat_encoder_emu'path_name, WHAT => "emulator", PIN_NAMES => "i_endat_clk, i_endat_data, i_endat_data_oe", IDLE => "00000011",
                     OE_PIN => 2, DATA_PIN => 1)
        port map (i_clk => i_emu_clk, i_pins => "00000" & i_endat_data_oe & i_endat_data & i_endat_clk, o_pins => answer);

    o_endat_data <= answer(0);
    o_endat_data_oe <= answer(1);
end architecture;
