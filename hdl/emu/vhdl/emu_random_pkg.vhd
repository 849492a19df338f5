-- emu_random_pkg: random numbers for a VHDL testbench, the sequence of
-- hdl/emu/emu_random.vh (xorshift64, Marsaglia 2003) draw for draw, so a
-- VHDL and a Verilog bench seeded alike test the same values.
--
--   variable rng : emu_random_t;      -- in a process
--   rng.seed(7);
--   position := rng.random64;          -- unsigned(63 downto 0)
--   flags := rng.random32;             -- unsigned(31 downto 0)

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

package emu_random_pkg is

    type emu_random_t is protected
        -- Any integer, 0 included.
        procedure seed(s : integer);
        -- The next 32 random bits (the high half of the state).
        impure function random32 return unsigned;
        -- The next 64 random bits: two draws, the first the high half.
        impure function random64 return unsigned;
    end protected;

end package;

package body emu_random_pkg is

    type emu_random_t is protected body
        constant START : unsigned(63 downto 0) := x"9E3779B97F4A7C15";
        variable state : unsigned(63 downto 0) := START;

        -- The state is never 0 (xorshift would stay there): the seed is
        -- mixed into a non-zero constant, and 0 is replaced.
        procedure seed(s : integer) is
            constant s32 : unsigned(31 downto 0) := unsigned(to_signed(s, 32));
        begin
            state := START xor (s32 & not s32);
            if state = 0 then
                state := START;
            end if;
        end procedure;

        -- Returned as (31 downto 0), not as the state's slice (63 downto 32).
        impure function random32 return unsigned is
            variable r : unsigned(31 downto 0);
        begin
            state := state xor shift_left(state, 13);
            state := state xor shift_right(state, 7);
            state := state xor shift_left(state, 17);
            r := state(63 downto 32);
            return r;
        end function;

        impure function random64 return unsigned is
            constant high : unsigned(31 downto 0) := random32;
        begin
            return high & random32;
        end function;
    end protected body;

end package body;
