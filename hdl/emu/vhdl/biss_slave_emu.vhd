-- biss_slave_emu: a chain of one to three BiSS-C slaves and its cable for a VHDL
-- testbench, the twin of hdl/emu/biss_slave_emu.v (same generics, ports and
-- behaviour; read its header): the encoder-tb model through emu_pkg.
--
-- Controls by instance label (emu_pkg): set_position("u_emu", slave, p),
-- set_status("u_emu", slave, "error", 1), schedule_fault("u_emu", "flips = [{ frame = 7, bits = [0] }]"),
-- count("u_emu"), last_value("u_emu", slave), last_status("u_emu", slave, "error"), violations("u_emu").
-- CONFIG "" reads the plusarg +<PLUSARG>=<file>.

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity biss_slave_emu is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "biss_emu_config";
        F_EMU_HZ : natural := 80000000;
        TRANSCRIPT : string := "";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Emulator clock */
        i_emu_clk : in std_logic;

        /* BiSS-C line at the master's end of the cable */
        i_ma : in std_logic;
        o_slo : out std_logic := '1'
    );
end entity;

architecture emu of biss_slave_emu is
    signal answer : std_ulogic_vector(2 downto 0);
begin
    -- Each input's level before reset ends: MA idle high
    core : entity work.emu_core
        generic map (KIND => "biss", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_EMU_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => "", STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => biss_slave_emu'path_name, WHAT => "emulator", PIN_NAMES => "i_ma", IDLE => "00000001")
        port map (i_clk => i_emu_clk, i_pins => "0000000" & i_ma, o_pins => answer);

    o_slo <= answer(0);
end architecture;
