-- emu_core: the body every VHDL emulator and monitor of hdl/emu/vhdl/
-- instantiates (as emu_clocked.vh, emu_pair.vh, emu_half_duplex.vh and
-- emu_monitor.vh are the Verilog wrappers' bodies): opens the library's
-- KIND at elaboration under the wrapper's PATH (emu_pkg.emu_instance), and
-- on each rising edge of i_clk samples i_pins, steps the library once and
-- registers its answer (emu_pkg.emu_clock says how each pin is read).
--
--   i_pins  the wrapper's inputs in the library's layout, pin 0 in bit 0
--   o_pins  bit 0 the device's data at the master's end (idle high), bit 1
--           its driver enable (off), bit 2 a half-duplex line's resolved
--           level (high); a monitor leaves them open

library ieee;
use ieee.std_logic_1164.all;

use work.emu_pkg.all;

entity emu_core is
    generic (
        KIND : string;                  -- the library's emulator or monitor name
        CONFIG : string;
        PLUSARG : string;
        F_HZ : natural;
        TRANSCRIPT : string;
        TRANSCRIPT_PLUSARG : string;    -- "" for an emulator (its transcript is TRANSCRIPT alone)
        STOP_ON_X : integer;
        STOP_ON_VIOLATION : integer;
        PATH : string;                  -- the wrapper's 'path_name: the controls find it by it
        WHAT : string;                  -- "emulator" or "monitor", for messages
        PIN_NAMES : string;             -- the pins' names, pin 0 first, comma-separated
        IDLE : std_ulogic_vector(7 downto 0);    -- each pin's level before reset ends
        OE_PIN : integer := -1;         -- a driver enable whose unknown level reads as not driving
        DATA_PIN : integer := -1        -- that driver's data
    );
    port (
        i_clk : in std_logic;
        i_pins : in std_ulogic_vector(7 downto 0);
        o_pins : out std_ulogic_vector(2 downto 0) := "101"
    );
end entity;

architecture emu of emu_core is
    constant HANDLE : integer := emu_instance(KIND, CONFIG, PLUSARG, TRANSCRIPT, TRANSCRIPT_PLUSARG, F_HZ, PATH);
begin
    process (i_clk)
        variable pins : emu_pins_t := emu_pins_init(IDLE);
        variable output : std_ulogic_vector(2 downto 0);
    begin
        if rising_edge(i_clk) then
            emu_clock(HANDLE, PATH, WHAT, PIN_NAMES, i_pins, OE_PIN, DATA_PIN, STOP_ON_X, STOP_ON_VIOLATION,
                      pins, output);
            o_pins <= output;
        end if;
    end process;
end architecture;
