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
    constant PATH : string := endat_encoder_emu'path_name;
    constant HANDLE : integer := emu_instance("endat", CONFIG, PLUSARG, TRANSCRIPT, "", F_EMU_HZ, PATH);
begin
    process (i_emu_clk)
        -- Each input's level before reset ends: clock high, data high, driver off
        variable pins : emu_pins_t := emu_pins_init("00000011");
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_emu_clk) then
            emu_clock(HANDLE, PATH, "emulator", "i_endat_clk, i_endat_data, i_endat_data_oe", "00000" & i_endat_data_oe & i_endat_data & i_endat_clk, 2, 1,
                      STOP_ON_X, STOP_ON_VIOLATION, pins, output);
            o_endat_data <= output(0);
            o_endat_data_oe <= output(1);
        end if;
    end process;
end architecture;
