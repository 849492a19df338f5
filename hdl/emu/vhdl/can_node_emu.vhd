-- can_node_emu: CAN nodes on a bus with the master for a VHDL
-- testbench, the twin of hdl/emu/can_node_emu.v (same generics, ports and
-- behaviour; read its header): the encoder-tb model through emu_pkg.
--
-- Controls by instance label (emu_pkg): set_position("u_emu", device, p), set_status,
-- schedule_fault("u_emu", "[[send]] ..."), count("u_emu"), last_value("u_emu", node + 16 * field), last_status, violations("u_emu").
-- CONFIG "" reads the plusarg +<PLUSARG>=<file>.

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity can_node_emu is
    generic (
        CONFIG : string := "";
        PLUSARG : string := "can_emu_config";
        F_EMU_HZ : natural := 10000000;
        TRANSCRIPT : string := "";
        STOP_ON_X : integer := 1;
        STOP_ON_VIOLATION : integer := 0
    );
    port (
        /* Emulator clock */
        i_emu_clk : in std_logic;

        /* The master's transceiver pins */
        i_can_tx : in std_logic;
        o_can_rx : out std_logic := '1'
    );
end entity;

architecture emu of can_node_emu is
    signal answer : std_ulogic_vector(2 downto 0);
begin
    -- Each input's level before reset ends: TXD recessive
    core : entity work.emu_core
        generic map (KIND => "can", CONFIG => CONFIG, PLUSARG => PLUSARG, F_HZ => F_EMU_HZ, TRANSCRIPT => TRANSCRIPT,
                     TRANSCRIPT_PLUSARG => "", STOP_ON_X => STOP_ON_X, STOP_ON_VIOLATION => STOP_ON_VIOLATION,
                     PATH => can_node_emu'path_name, WHAT => "emulator", PIN_NAMES => "(none), i_can_tx, (none), (none)", IDLE => "00001011")
        port map (i_clk => i_emu_clk, i_pins => "000010" & i_can_tx & '1', o_pins => answer);

    o_can_rx <= answer(0);
end architecture;
