-- sar58k24_encoder_emu: SAR58K24 encoders in an asynchronous mode and their cable for a VHDL
-- testbench, the twin of hdl/emu/sar58k24_encoder_emu.v (same generics, ports and
-- behaviour; read its header): the encoder-tb model through emu_pkg.
--
-- Controls by instance label (emu_pkg): set_position("u_emu", device, p), set_motion,
-- set_status, schedule_fault, count("u_emu"), last_value("u_emu", device), last_status, violations("u_emu").
-- CONFIG "" reads the plusarg +<PLUSARG>=<file>.

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity sar58k24_encoder_emu is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "sar58k24_emu_config";
        F_EMU_HZ : natural := 10000000;
        TRANSCRIPT : string := "";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Emulator clock */
        i_emu_clk : in std_logic;

        /* Host side of the cable */
        i_line : in std_logic;
        i_line_en : in std_logic;
        i_trigger : in std_logic;
        i_clr : in std_logic;
        o_line : out std_logic := '1';
        o_line_en : out std_logic := '0';
        o_bus : out std_logic := '1'
    );
end entity;

architecture emu of sar58k24_encoder_emu is
    signal answer : std_ulogic_vector(2 downto 0);
begin
    -- Each input's level before reset ends: trigger high, line high, driver off, CLR high
    core : entity work.emu_core
        generic map (KIND => "sar58k24", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_EMU_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => "", STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => sar58k24_encoder_emu'path_name, WHAT => "emulator", PIN_NAMES => "i_trigger, i_line, i_line_en, i_clr", IDLE => "00001011",
                     OE_PIN => 2, DATA_PIN => 1)
        port map (i_clk => i_emu_clk, i_pins => "0000" & i_clr & i_line_en & i_line & i_trigger, o_pins => answer);

    o_line <= answer(0);
    o_line_en <= answer(1);
    o_bus <= answer(2);
end architecture;
