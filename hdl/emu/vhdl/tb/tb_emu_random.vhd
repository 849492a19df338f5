-- tb_emu_random: draws of emu_random_pkg, one per line in hex, for the
-- comparison with emu_random.vh (tb_emu_random.v prints the same draws;
-- scripts/vhdl_examples.sh compares the two outputs).
library ieee;
use ieee.numeric_std.all;
use std.textio.all;
use work.emu_random_pkg.all;

entity tb_emu_random is
end entity;

architecture bench of tb_emu_random is
begin
    process
        variable rng : emu_random_t;
        variable l : line;
    begin
        rng.seed(-5);
        for i in 1 to 6 loop
            write(l, to_hstring(rng.random32));
            writeline(output, l);
        end loop;
        write(l, to_hstring(rng.random64));
        writeline(output, l);
        rng.seed(0);
        write(l, to_hstring(rng.random32));
        writeline(output, l);
        rng.seed(7);
        write(l, to_hstring(rng.random64));
        writeline(output, l);
        wait;
    end process;
end architecture;
